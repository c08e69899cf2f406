#include "traces/mrpt/mrpt_archive_bytes.h"

#include <filesystem>
#include <string_view>

#include <mrpt/io/CFileGZInputStream.h>

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
      if (got > sizeof chunk)
        throw InputError(path, 0, "", "cannot read " + what + " file: corrupt gzip stream");
      if (bytes.size() + got > MemoryCapBytes())
        throw InputError(path, 0, "", "the " + what + " file uncompresses to more than " +
                                          std::to_string(bytes.size()) + " bytes and " +
                                          DescribeOverCap(bytes.size() + got));
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

void CheckMrptCrashFields(const std::vector<unsigned char>& bytes, const std::string& path, const std::string& what) {
  // Every object head of the class, in CArchive's format: length byte with
  // the top bit set, the name, the version byte.
  static const std::string kName = "mrpt::obs::CActionRobotMovement2D";
  std::string head(1, static_cast<char>(0x80 | kName.size()));
  head += kName;
  const std::string_view all(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  for (std::size_t at = all.find(head); at != std::string_view::npos; at = all.find(head, at + 1)) {
    const std::size_t version_at = at + head.size();
    if (version_at + 5 > bytes.size() || bytes[version_at] != 7) continue;
    const std::uint32_t method = ArchiveUint32(bytes, version_at + 1, path, "estimationMethod");
    if (method > 1)
      throw InputError(path, 0, "estimationMethod",
                       "the CActionRobotMovement2D at byte " + std::to_string(at) + " has estimation method " +
                           std::to_string(method) + " (MRPT knows 0, odometry, and 1, scan matching): corrupt " +
                           what);
  }
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
