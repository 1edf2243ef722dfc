#pragma once
// The trace file's layout, shared by the writer and the reader (docs/report-format.md,
// "Trace files"). Little-endian throughout; doubles as their IEEE-754 bits.

#include <cstdint>

namespace stitchsim::trace::codec {

inline constexpr char kMagic[8] = {'S', 'T', 'S', 'M', 'T', 'R', 'C', 'E'};

/// Record tags.
inline constexpr std::uint8_t kLineTag = 'L';
inline constexpr std::uint8_t kSampleTag = 'S';
inline constexpr std::uint8_t kEndTag = 'E';

/// Sample flags (u16).
inline constexpr std::uint16_t kEventMask = 0x7;  ///< SampleEvent in bits 0-2
inline constexpr std::uint16_t kDriveAdvancing = 1u << 3;
inline constexpr std::uint16_t kNeedlesIn = 1u << 4;
inline constexpr std::uint16_t kHasJoints = 1u << 5;
inline constexpr std::uint16_t kCollisionChecked = 1u << 6;
inline constexpr std::uint16_t kHasContacts = 1u << 7;
inline constexpr std::uint16_t kHasError = 1u << 8;
inline constexpr std::uint16_t kSameRotation = 1u << 9;  ///< rotation as the previous sample's
inline constexpr std::uint16_t kHasClearancePair = 1u << 10;
inline constexpr std::uint16_t kHasTiming = 1u << 11;  ///< timed_s (+ velocities... with joints)
inline constexpr std::uint16_t kTracked = 1u << 12;    ///< tracking errors (dynamic mode)
inline constexpr std::uint16_t kCollisionProbe = 1u << 13;  ///< a collision subdivision sample
inline constexpr std::uint16_t kKnownSampleFlags = (1u << 14) - 1;

/// Line flags (u8).
inline constexpr std::uint8_t kRapid = 1u << 0;
inline constexpr std::uint8_t kStitching = 1u << 1;
inline constexpr std::uint8_t kHeadRetracted = 1u << 2;
inline constexpr std::uint8_t kOverSampleLimit = 1u << 3;
inline constexpr std::uint8_t kKnownLineFlags = (1u << 4) - 1;

/// Bounds the reader holds a file to (a corrupt count never allocates gigabytes).
inline constexpr std::uint32_t kMaxStringBytes = 1u << 20;
inline constexpr std::uint32_t kMaxBodies = 1u << 20;
inline constexpr std::uint32_t kMaxFingerprints = 64;
inline constexpr std::uint32_t kMaxContacts = 1u << 20;

/// Arm configuration in a byte: bit 0 back shoulder, bit 1 elbow down, bit 2 wrist flip.
inline constexpr std::uint8_t kKnownConfigurationBits = 0x7;

}  // namespace stitchsim::trace::codec
