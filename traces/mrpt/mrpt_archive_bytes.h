#pragma once
// Reading an MRPT serialization archive (.rawlog, .gridmap, .simplemap,
// plain or gzip-compressed) into memory, so a reader can tell a clean end of
// file from a truncated object: the archive ends cleanly only at its last
// byte. Kept free of MRPT headers so callers stay light.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rc {

// The uncompressed bytes of the file. Throws InputError naming the file when
// it cannot be opened, is empty, its gzip stream is corrupt, or it
// uncompresses to more than the memory cap (common/memory_cap.h). `what` names
// the kind of file in messages ("rawlog", "gridmap").
std::vector<unsigned char> ReadArchiveBytes(const std::string& path, const std::string& what);

// The head of the object an archive holds: its class name and version, in
// CArchive's format (a length byte with its top bit set, the name, a version
// byte) or the format of MRPT 1.x files (a uint32 length, the name, a uint32
// version); the object's own fields start at data_offset. MRPT trusts the
// counts and sizes that follow and allocates them before it finds out the
// file is too short, so callers check those against the bytes that are
// really there first.
struct ArchiveObjectHead {
  std::string class_name;
  std::uint32_t version = 0;
  std::size_t data_offset = 0;
};

// False when the bytes start with neither form (MRPT then reports it).
bool ReadArchiveObjectHead(const std::vector<unsigned char>& bytes, ArchiveObjectHead* head);

// The little-endian uint32 at `offset`; throws InputError naming `field`
// when the archive ends before it.
std::uint32_t ArchiveUint32(const std::vector<unsigned char>& bytes, std::size_t offset, const std::string& path,
                            const std::string& field);

// Fields that crash MRPT's deserializer instead of raising its exception,
// checked in the bytes before MRPT reads them (tests/fuzz findings). Every
// object head of the class is checked, wherever it sits (a rawlog entry, an
// action inside a CActionCollection, an object in a sensory frame), in both
// of CArchive's head formats and with any namespace:
// - CActionRobotMovement2D: unless its estimation method is odometry, it
//   reads a pose PDF object and copies the pointer it gets; an object of a
//   class that is not a CPosePDF gives a null pointer, whose copy MRPT
//   dereferences. Refused: an estimation method other than 0 (odometry) or
//   1 (scan matching), and a pose PDF head naming anything but a CPosePDF
//   class MRPT knows.
// - CActionCollection: MRPT copies each object's pointer the same way, so
//   an object that is not a CAction (or "nullptr") is refused.
// - CSensoryFrame: an object that is not a CObservation (MRPT's version 0
//   reader and every map insertion dereference it).
// - CSimpleMap version 0: a keyframe pose that is not a CPosePDF (MRPT
//   converts it to 3D through the pointer).
// Throws InputError naming the file, the byte offset and the field.
void CheckMrptCrashFields(const std::vector<unsigned char>& bytes, const std::string& path, const std::string& what);

// MRPT's exception texts nest exceptions and call traces over many lines;
// returns the innermost "Message:" text, the one a user needs.
std::string MrptMessage(const std::string& text);

}  // namespace rc
