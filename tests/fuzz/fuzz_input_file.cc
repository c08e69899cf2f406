#include "fuzz/fuzz_input_file.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "common/memory_cap.h"

namespace rc::fuzz {
namespace {

// Sizes are checked against the memory cap before allocation; a cap far
// below the machine's makes every fuzzed header that declares a big map or
// scan meet that check, and keeps each run fast. -malloc_limit_mb still
// catches any allocation that bypasses it.
constexpr std::uint64_t kFuzzMemoryCapBytes = 64ULL << 20;
[[maybe_unused]] const bool kCapSet = [] {
  SetMemoryCapBytes(kFuzzMemoryCapBytes);
  return true;
}();

const std::string& Folder() {
  static const std::string folder = [] {
    const std::filesystem::path base =
        std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path();
    // The pid keeps parallel fuzzers apart; padded to a fixed width so the
    // path, which error messages quote, has the same length in every run
    // (a length that varies varies the coverage libFuzzer sees, and with it
    // the inputs a seeded run tries).
    char pid[16];
    std::snprintf(pid, sizeof pid, "%010ld", static_cast<long>(::getpid()));
    const std::filesystem::path dir = base / (std::string("rcbench-fuzz-") + pid);
    std::filesystem::create_directories(dir);
    // Removed at exit; a crashed fuzzer leaves it for inspection.
    static const std::string kept = dir.string();
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(kept, ignored);
    });
    return dir.string();
  }();
  return folder;
}

}  // namespace

std::string WriteInputFile(const std::string& name, std::string_view bytes) {
  const std::string path = Folder() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz harness: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

void SplitInput(std::string_view input, std::string_view separator, std::string_view* first, std::string_view* second) {
  const std::size_t at = input.find(separator);
  if (at == std::string_view::npos) {
    *first = input;
    *second = {};
    return;
  }
  *first = input.substr(0, at);
  *second = input.substr(at + separator.size());
}

void Report(const char* outcome) {
  static const bool verbose = std::getenv("RC_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "fuzz input: %s\n", outcome);
}

void Require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz finding: a parse succeeded but %s\n", what);
  std::abort();
}

}  // namespace rc::fuzz
