#include "common/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <unistd.h>

#include "common/input_error.h"

namespace rc {

void CreateParentFolders(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (parent.empty()) return;
  std::error_code error;
  std::filesystem::create_directories(parent, error);
  if (error) throw OutputError(path, "cannot create the output folder '" + parent.string() + "': " + error.message());
}

void CheckOutputPaths(const std::vector<std::string>& paths) {
  namespace fs = std::filesystem;
  std::vector<fs::path> seen;
  for (const std::string& path : paths) {
    if (path.empty()) continue;
    std::error_code error;
    if (fs::is_directory(path, error)) throw OutputError(path, "is a folder; give a file path for this output");
    for (fs::path above = fs::path(path).parent_path(); !above.empty(); above = above.parent_path()) {
      if (!fs::exists(above, error)) {
        if (above == above.parent_path()) break;
        continue;
      }
      if (!fs::is_directory(above, error))
        throw OutputError(path, "cannot create the output: '" + above.string() + "' is a file, not a folder");
      break;
    }
    const fs::path normal = fs::absolute(path, error).lexically_normal();
    for (const fs::path& other : seen)
      if (other == normal) throw OutputError(path, "given for two outputs; each output needs its own path");
    seen.push_back(normal);
  }
}

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)), temp_path_(path_ + ".tmp" + std::to_string(::getpid())) {
  CreateParentFolders(path_);
  out_.open(temp_path_, std::ios::binary | std::ios::trunc);
  if (!out_) throw OutputError(path_, std::string("cannot open for writing: ") + std::strerror(errno));
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::remove(temp_path_.c_str());
  }
}

void AtomicFile::Commit() {
  out_.flush();
  if (!out_) throw OutputError(path_, "write error (disk full?)");
  out_.close();
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0)
    throw OutputError(path_, std::string("cannot move the output into place: ") + std::strerror(errno));
  committed_ = true;
}

}  // namespace rc
