#include "stitchsim/program/diagnostic_codes.h"

#include <array>

#include "codes.h"

namespace stitchsim::program {

std::span<const std::string_view> AllProgramDiagnosticCodes() {
  using namespace codes;
  static constexpr std::array<std::string_view, 40> kAll = {
      kInvalidCharacter,  kLineTooLong,         kUnknownWord,        kMissingLetter,
      kMissingValue,      kBadNumber,           kExponentNotAllowed, kNan,
      kNumberOverflow,    kFractionalCode,      kSignedCode,         kDuplicateWord,
      kUnclosedComment,   kNestedComment,       kUnmatchedParen,     kBadHeader,
      kTextAfterPercent,  kDuplicateStart,      kMissingEnd,         kTextAfterEnd,
      kEmptyProgram,      kUnknownGCode,        kUnknownMCode,       kUnsupportedDistanceMode,
      kUnsupportedMotion, kConflictingMotion,   kConflictingUnits,   kConflictingModes,
      kTooManyMCodes,     kNegativeFeed,        kZeroFeed,           kUnknownTool,
      kMissingParameter,  kUnexpectedParameter, kNoMotionMode,       kMissingFeed,
      kMissingTool,       kCodeAfterProgramEnd, kTooManyLines,       kAfpStructure,
  };
  return kAll;
}

std::span<const std::string_view> AllDialectDiagnosticCodes() {
  using namespace codes;
  static constexpr std::array<std::string_view, 8> kAll = {
      kDialectFileNotFound, kDialectYamlSyntax,      kDialectUnknownKey,    kDialectBadValue,
      kDialectBadLetter,    kDialectDuplicateLetter, kDialectBadEulerOrder, kDialectDuplicateCode,
  };
  return kAll;
}

}  // namespace stitchsim::program
