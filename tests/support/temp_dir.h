#pragma once
// The one scratch folder of the tests: each TempDir is a fresh, private
// folder under the system temp dir (mkdtemp, so parallel ctest processes
// never share one), removed with everything in it when the object dies.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace rc::test {

class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "rc_test_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed for " + pattern);
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  // The path of `name` inside the folder; nothing is created.
  std::string Path(const std::string& name) const { return (path_ / name).string(); }
  // Writes `content` verbatim (binary, so "\r\n" stays), creating parent
  // folders, and returns the path.
  std::string Write(const std::string& name, const std::string& content) const {
    const std::string path = Path(name);
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    std::ofstream(path, std::ios::binary) << content;
    return path;
  }
  // Entries directly in the folder: proves that nothing partial was left.
  int FileCount() const {
    int count = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(path_)) ++count;
    return count;
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// A path in the test program's own TempDir (made on first use, removed at
// exit), for helpers that write files outside any one test.
inline std::string ProgramTempPath(const std::string& name) {
  static const TempDir dir;
  return dir.Path(name);
}

}  // namespace rc::test
