#pragma once
// Output files are written to a temporary sibling and renamed into place only
// when complete, so a failed run never leaves a partial or corrupt file.
#include <fstream>
#include <string>

namespace rc {

class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();  // Removes the temporary file if Commit() was not reached.
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  // Flushes, checks for write errors and renames into place. Throws
  // std::runtime_error naming the path on failure.
  void Commit();

 private:
  std::string path_;
  std::string temp_path_;
  std::ofstream out_;
  bool committed_ = false;
};

}  // namespace rc
