#include "traces/mrpt/mrpt_archive_bytes.h"

#include <filesystem>

#include <mrpt/io/CFileGZInputStream.h>

#include "common/input_error.h"

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
