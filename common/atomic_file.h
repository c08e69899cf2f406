#pragma once
// Output files are written to a temporary sibling and renamed into place only
// when complete, so a failed or killed run never leaves a partial or corrupt
// file at the output path: it holds the previous file, or none, or the
// complete new one. Missing parent folders are created here, the one place
// every output passes through.
//
// Guarantee: survives the death of the process (any signal, including
// SIGKILL); a temporary "<path>.tmp<pid>" may then remain beside the output.
// It does not fsync, so it promises nothing about an operating-system crash.
#include <fstream>
#include <string>
#include <vector>

namespace rc {

// Creates the folders above `path` (nothing for a bare file name). Throws
// OutputError naming the folder when that fails.
void CreateParentFolders(const std::string& path);

// Checks that each of `paths` (empty ones skipped) can become an output file:
// it is not an existing folder, no file stands where a folder above it must
// be, and no two of them are the same path. A command with several outputs
// calls it with all of them before it starts work: each output is atomic,
// but they are written one after another at the end, so without the check
// a bad last path would fail the run after the first outputs were in place.
// Throws OutputError naming the path.
void CheckOutputPaths(const std::vector<std::string>& paths);

class AtomicFile {
 public:
  // Creates missing parent folders and opens the temporary file. Throws
  // OutputError naming the path if either fails.
  explicit AtomicFile(std::string path);
  ~AtomicFile();  // Removes the temporary file if Commit() was not reached.
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  // Flushes, checks for write errors and renames into place. Throws
  // OutputError naming the path on failure.
  void Commit();

 private:
  std::string path_;
  std::string temp_path_;
  std::ofstream out_;
  bool committed_ = false;
};

}  // namespace rc
