#pragma once
// Diagnostic code strings, one constant each, so a typo is a compile error.

namespace stitchsim::program::codes {

// Lexical: characters, numbers, words.
inline constexpr char kInvalidCharacter[] = "gcode-invalid-character";
inline constexpr char kLineTooLong[] = "gcode-line-too-long";
inline constexpr char kTooManyLines[] = "gcode-too-many-lines";
inline constexpr char kUnknownWord[] = "gcode-unknown-word";
inline constexpr char kMissingLetter[] = "gcode-missing-letter";
inline constexpr char kMissingValue[] = "gcode-missing-value";
inline constexpr char kBadNumber[] = "gcode-bad-number";
inline constexpr char kExponentNotAllowed[] = "gcode-exponent-not-allowed";
inline constexpr char kNan[] = "gcode-nan";
inline constexpr char kNumberOverflow[] = "gcode-number-overflow";
inline constexpr char kFractionalCode[] = "gcode-fractional-code";
inline constexpr char kSignedCode[] = "gcode-signed-code";
inline constexpr char kDuplicateWord[] = "gcode-duplicate-word";
// Comments.
inline constexpr char kUnclosedComment[] = "gcode-unclosed-comment";
inline constexpr char kNestedComment[] = "gcode-nested-comment";
inline constexpr char kUnmatchedParen[] = "gcode-unmatched-paren";
inline constexpr char kBadHeader[] = "gcode-bad-header";
// Programme structure ('%' marks).
inline constexpr char kTextAfterPercent[] = "gcode-text-after-percent";
inline constexpr char kDuplicateStart[] = "gcode-duplicate-start";
inline constexpr char kMissingEnd[] = "gcode-missing-end";
inline constexpr char kTextAfterEnd[] = "gcode-text-after-end";
inline constexpr char kEmptyProgram[] = "gcode-empty-program";
// Codes within one block.
inline constexpr char kUnknownGCode[] = "gcode-unknown-g-code";
inline constexpr char kUnknownMCode[] = "gcode-unknown-m-code";
inline constexpr char kUnsupportedDistanceMode[] = "gcode-unsupported-distance-mode";
inline constexpr char kUnsupportedMotion[] = "gcode-unsupported-motion";
inline constexpr char kConflictingMotion[] = "gcode-conflicting-motion";
inline constexpr char kConflictingUnits[] = "gcode-conflicting-units";
inline constexpr char kConflictingModes[] = "gcode-conflicting-modes";
inline constexpr char kTooManyMCodes[] = "gcode-too-many-m-codes";
inline constexpr char kNegativeFeed[] = "gcode-negative-feed";
inline constexpr char kZeroFeed[] = "gcode-zero-feed";
inline constexpr char kUnknownTool[] = "gcode-unknown-tool";
inline constexpr char kMissingParameter[] = "gcode-missing-parameter";
inline constexpr char kUnexpectedParameter[] = "gcode-unexpected-parameter";
// Modal state (across blocks).
inline constexpr char kNoMotionMode[] = "gcode-no-motion-mode";
inline constexpr char kMissingFeed[] = "gcode-missing-feed";
inline constexpr char kMissingTool[] = "gcode-missing-tool";
inline constexpr char kCodeAfterProgramEnd[] = "gcode-code-after-program-end";
inline constexpr char kAfpStructure[] = "gcode-afp-structure";

// Dialect files.
inline constexpr char kDialectFileNotFound[] = "dialect-file-not-found";
inline constexpr char kDialectYamlSyntax[] = "dialect-yaml-syntax";
inline constexpr char kDialectUnknownKey[] = "dialect-unknown-key";
inline constexpr char kDialectBadValue[] = "dialect-bad-value";
inline constexpr char kDialectBadLetter[] = "dialect-bad-letter";
inline constexpr char kDialectDuplicateLetter[] = "dialect-duplicate-letter";
inline constexpr char kDialectBadEulerOrder[] = "dialect-bad-euler-order";
inline constexpr char kDialectDuplicateCode[] = "dialect-duplicate-code";

}  // namespace stitchsim::program::codes
