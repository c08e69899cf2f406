#include "traces/mrpt/mrpt_archive_bytes.h"

#include <algorithm>
#include <filesystem>
#include <string_view>
#include <utility>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CAction.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/poses/CPosePDF.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/serialization/CArchive.h>

#include "common/allocation_budget.h"
#include "common/input_error.h"
#include "common/memory_cap.h"

namespace rc {

std::vector<unsigned char> ReadArchiveBytes(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path, 0, "", "cannot open " + what + " file (missing or not a regular file)");
  std::vector<unsigned char> bytes;
  try {
    // CFileGZInputStream reads plain files unchanged, so one path serves
    // both the compressed and the uncompressed form.
    mrpt::io::CFileGZInputStream in;
    if (!in.open(path)) throw InputError(path, 0, "", "cannot open " + what + " file");
    unsigned char chunk[1 << 16];
    for (;;) {
      const std::size_t got = in.Read(chunk, sizeof chunk);
      if (got == 0) break;
      // zlib's gzread returns -1 for a corrupt stream; it arrives here as
      // SIZE_MAX through MRPT's size_t (a finding of tests/fuzz).
      if (got > sizeof chunk) throw InputError(path, 0, "", "cannot read " + what + " file: corrupt gzip stream");
      if (bytes.size() + got > MemoryCapBytes())
        throw InputError(path, 0, "",
                         "the " + what + " file uncompresses to more than " + std::to_string(bytes.size()) +
                             " bytes and " + DescribeOverCap(bytes.size() + got));
      bytes.insert(bytes.end(), chunk, chunk + got);
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, 0, "", "cannot read " + what + " file (corrupt gzip stream?): " + MrptMessage(e.what()));
  }
  if (bytes.empty()) throw InputError(path, 0, "", "the " + what + " file is empty");
  return bytes;
}

bool ReadArchiveObjectHead(const std::vector<unsigned char>& bytes, ArchiveObjectHead* head) {
  if (bytes.empty()) return false;
  std::size_t length = 0, name_at = 0, version_bytes = 0;
  if (bytes[0] & 0x80) {
    length = bytes[0] & 0x7F;
    name_at = 1;
    version_bytes = 1;
  } else {
    if (bytes.size() < 4) return false;
    length = static_cast<std::size_t>(bytes[0]) | static_cast<std::size_t>(bytes[1]) << 8 |
             static_cast<std::size_t>(bytes[2]) << 16 | static_cast<std::size_t>(bytes[3]) << 24;
    name_at = 4;
    version_bytes = 4;
  }
  if (length == 0 || length > 255 || bytes.size() < name_at + length + version_bytes) return false;
  head->class_name.assign(bytes.begin() + static_cast<std::ptrdiff_t>(name_at),
                          bytes.begin() + static_cast<std::ptrdiff_t>(name_at + length));
  head->version = 0;
  for (std::size_t i = 0; i < version_bytes; ++i)
    head->version |= static_cast<std::uint32_t>(bytes[name_at + length + i]) << (8 * i);
  head->data_offset = name_at + length + version_bytes;
  return true;
}

std::uint32_t ArchiveUint32(const std::vector<unsigned char>& bytes, std::size_t offset, const std::string& path,
                            const std::string& field) {
  if (offset + 4 > bytes.size()) throw InputError(path, 0, field, "the archive ends before this field");
  return static_cast<std::uint32_t>(bytes[offset]) | static_cast<std::uint32_t>(bytes[offset + 1]) << 8 |
         static_cast<std::uint32_t>(bytes[offset + 2]) << 16 | static_cast<std::uint32_t>(bytes[offset + 3]) << 24;
}

namespace {

// MRPT resolves a class by the name after its last "::" (findRegisteredClass
// ignores the namespace), so a head names a class by that suffix.
std::string_view BareClassName(std::string_view name) {
  const std::size_t colons = name.rfind("::");
  return colons == std::string_view::npos ? name : name.substr(colons + 2);
}

// The object head at `at`, in either of CArchive's formats, as
// CArchive::internal_ReadObjectHeader reads it: a length byte with its top
// bit set, at most 120 name bytes, a version byte ("nullptr" has none); or
// a uint32 length below 128, the name, a uint32 version. False when the
// bytes there are not such a head.
bool ReadObjectHeadAt(const std::vector<unsigned char>& bytes, std::size_t at, ArchiveObjectHead* head) {
  if (at >= bytes.size()) return false;
  const bool old_format = !(bytes[at] & 0x80);
  const std::size_t length = bytes[at] & 0x7F;
  const std::size_t name_at = at + (old_format ? 4 : 1);
  if (length == 0 || length > 120 || name_at + length > bytes.size()) return false;
  if (old_format && (bytes[at + 1] || bytes[at + 2] || bytes[at + 3])) return false;
  head->class_name.assign(bytes.begin() + static_cast<std::ptrdiff_t>(name_at),
                          bytes.begin() + static_cast<std::ptrdiff_t>(name_at + length));
  const std::size_t version_at = name_at + length;
  if (!old_format && head->class_name == "nullptr") {
    head->version = 0;
    head->data_offset = version_at;
    return true;
  }
  const std::size_t version_bytes = old_format ? 4 : 1;
  if (version_at + version_bytes > bytes.size()) return false;
  head->version = 0;
  for (std::size_t i = 0; i < version_bytes; ++i)
    head->version |= static_cast<std::uint32_t>(bytes[version_at + i]) << (8 * i);
  head->data_offset = version_at + version_bytes;
  return true;
}

// Where every head of a class named `bare` (with any namespace) starts.
std::vector<std::size_t> HeadsOfClass(const std::vector<unsigned char>& bytes, const std::string& bare) {
  std::vector<std::size_t> heads;
  const std::string_view all(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  for (std::size_t q = all.find(bare); q != std::string_view::npos; q = all.find(bare, q + 1)) {
    const std::size_t name_end = q + bare.size();
    // The name starts at q, or earlier with "::" just before q.
    for (std::size_t name_at = q + 1; name_at-- > 0;) {
      if (name_end - name_at > 120) break;
      if (name_at != q && (q < 2 || all.compare(q - 2, 2, "::") != 0)) break;
      const std::size_t length = name_end - name_at;
      if (name_at >= 1 && bytes[name_at - 1] == (0x80 | length)) heads.push_back(name_at - 1);
      if (name_at >= 4 && bytes[name_at - 4] == length && !bytes[name_at - 3] && !bytes[name_at - 2] &&
          !bytes[name_at - 1])
        heads.push_back(name_at - 4);
    }
  }
  return heads;
}

// True when MRPT knows the class and it derives from CPosePDF: only then does
// CArchive::ReadObject<CPosePDF> return a non-null pointer.
bool IsPosePdfClass(const std::string& name) {
  const mrpt::rtti::TRuntimeClassId* id = mrpt::rtti::findRegisteredClass(name);
  return id != nullptr && id->derivedFrom(CLASS_ID(mrpt::poses::CPosePDF));
}

// An object that MRPT reads through a typed pointer and then dereferences:
// an object of another class (or "nullptr") reads as a null pointer, so it
// must be of class `base`. A null `base` accepts any object (read only to
// reach the next one).
struct ListedObject {
  const char* field;
  const mrpt::rtti::TRuntimeClassId* base;
};

// A class whose body holds a uint32 count, then that many groups of objects
// in `group` order. `count_at` gives the count's offset from the head's
// data_offset for a version, or -1 for a version MRPT itself refuses or
// reads without dereferencing.
struct ObjectList {
  const char* class_name;
  std::ptrdiff_t (*count_at)(std::uint32_t version);
  std::vector<ListedObject> group;
};

// The lists whose null entries crash MRPT (tests/fuzz findings):
// - CActionCollection (version 0): copies each action into a
//   deepcopy_poly_ptr, which dereferences a null one.
// - CSensoryFrame (versions 0-2): version 0 sets each observation's
//   timestamp; every version's observations are dereferenced by whoever
//   inserts the frame into a map (CMetricMap::loadFromSimpleMap).
// - CSimpleMap (version 0): converts each keyframe's 2D pose PDF with
//   CPose3DPDF::createFrom2D(*pdf).
const std::vector<ObjectList>& CrashingObjectLists() {
  static const std::vector<ObjectList> lists = {
      {"CActionCollection",
       [](std::uint32_t v) -> std::ptrdiff_t { return v == 0 ? 0 : -1; },
       {{"action", CLASS_ID(mrpt::obs::CAction)}}},
      // Version 0 and 1 start with a uint32 ID, version 0 then a timestamp.
      {"CSensoryFrame",
       [](std::uint32_t v) -> std::ptrdiff_t {
         return v == 0 ? 12 : v == 1 ? 4 : v == 2 ? 0 : -1;
       },
       {{"observation", CLASS_ID(mrpt::obs::CObservation)}}},
      {"CSimpleMap",
       [](std::uint32_t v) -> std::ptrdiff_t { return v == 0 ? 0 : -1; },
       {{"keyframe pose", CLASS_ID(mrpt::poses::CPosePDF)}, {"keyframe sensory frame", nullptr}}},
  };
  return lists;
}

// Reads every listed object with MRPT's generic ReadObject, which keeps a
// null, and checks its class. Lists are checked from the last head in the
// file to the first, so one nested in another's objects (a sensory frame
// in a simplemap) has been checked before MRPT reads it here.
void CheckObjectLists(const std::vector<unsigned char>& bytes, const std::string& path, const std::string& what) {
  std::vector<std::pair<std::size_t, const ObjectList*>> heads;
  for (const ObjectList& list : CrashingObjectLists())
    for (const std::size_t at : HeadsOfClass(bytes, list.class_name)) heads.emplace_back(at, &list);
  std::sort(heads.rbegin(), heads.rend());
  for (const auto& [at, list] : heads) {
    ArchiveObjectHead head;
    if (!ReadObjectHeadAt(bytes, at, &head) || BareClassName(head.class_name) != list->class_name) continue;
    const std::ptrdiff_t count_at = list->count_at(head.version);
    if (count_at < 0 || head.data_offset + static_cast<std::size_t>(count_at) + 4 > bytes.size())
      continue;  // MRPT reports another version or a truncated count itself
    const std::size_t first = head.data_offset + static_cast<std::size_t>(count_at) + 4;
    const std::uint32_t count = ArchiveUint32(bytes, first - 4, path, std::string(list->class_name) + " count");
    mrpt::io::CMemoryStream memory;
    memory.assignMemoryNotOwn(bytes.data() + first, bytes.size() - first);
    auto archive = mrpt::serialization::archiveFrom(memory);
    bool readable = true;
    for (std::uint32_t i = 0; readable && i < count; ++i) {
      for (const ListedObject& listed : list->group) {
        const std::size_t object_at = first + static_cast<std::size_t>(memory.getPosition());
        mrpt::serialization::CSerializable::Ptr object;
        try {
          ParseWithinBudget(ParseBudgetBytes(bytes.size()), [&] { object = archive.ReadObject(); });
        } catch (...) {
          readable = false;  // a malformed object: MRPT raises its own exception on it
          break;
        }
        if (!listed.base || (object && object->GetRuntimeClass()->derivedFrom(listed.base))) continue;
        ArchiveObjectHead held;
        const std::string name = ReadObjectHeadAt(bytes, object_at, &held) ? held.class_name : "?";
        throw InputError(path, 0, listed.field,
                         "the " + std::string(list->class_name) + " at byte " + std::to_string(at) + " holds a '" +
                             name + "' at byte " + std::to_string(object_at) + " as its " + listed.field + " " +
                             std::to_string(i) + " (not a " + listed.base->className + "): corrupt " + what);
      }
    }
  }
}

}  // namespace

void CheckMrptCrashFields(const std::vector<unsigned char>& bytes, const std::string& path, const std::string& what) {
  for (const std::size_t at : HeadsOfClass(bytes, "CActionRobotMovement2D")) {
    ArchiveObjectHead head;
    if (!ReadObjectHeadAt(bytes, at, &head) || BareClassName(head.class_name) != "CActionRobotMovement2D") continue;
    const std::string where =
        "the CActionRobotMovement2D (version " + std::to_string(head.version) + ") at byte " + std::to_string(at);
    // Versions 2 to 7 start with the estimation method; all but odometry
    // (0) read the pose PDF object next. Versions 0 and 1 start with it.
    std::size_t pdf_at = head.data_offset;
    if (head.version >= 2 && head.version <= 7) {
      if (head.data_offset + 4 > bytes.size()) continue;  // MRPT reports the end of file
      const std::uint32_t method = ArchiveUint32(bytes, head.data_offset, path, "estimationMethod");
      if (method == 0) continue;
      if (method != 1)
        throw InputError(path, 0, "estimationMethod",
                         where + " has estimation method " + std::to_string(static_cast<std::int32_t>(method)) +
                             " (MRPT knows 0, odometry, and 1, scan matching): corrupt " + what);
      pdf_at = head.data_offset + 4;
    } else if (head.version > 1) {
      continue;  // MRPT refuses an unknown version itself
    }
    ArchiveObjectHead pdf;
    if (!ReadObjectHeadAt(bytes, pdf_at, &pdf)) continue;  // MRPT reports a malformed head itself
    if (!IsPosePdfClass(pdf.class_name))
      throw InputError(path, 0, "poseChange",
                       where + " holds a '" + pdf.class_name +
                           "' where its pose PDF belongs (a CPosePDF class): corrupt " + what);
  }
  CheckObjectLists(bytes, path, what);
}

std::string MrptMessage(const std::string& text) {
  // MRPT nests exceptions: "==== MRPT exception ====", "Message: ...",
  // "Original exception:", then the inner one. The innermost Message: says
  // what went wrong; the call-stack lines around it do not help a user.
  std::string message, first;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    const std::size_t begin = line.find_first_not_of(" \t");
    line = begin == std::string::npos ? "" : line.substr(begin);
    if (line.rfind("Message:", 0) == 0) {
      const std::size_t body = line.find_first_not_of(" \t", 8);
      if (body != std::string::npos) message = line.substr(body);
    } else if (first.empty() && !line.empty() && line.find("====") == std::string::npos) {
      first = line;
    }
    start = end + 1;
  }
  if (!message.empty()) return message;
  return first.empty() ? text : first;
}

}  // namespace rc
