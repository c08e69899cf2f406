#pragma once
// Helpers for the traces tests: scratch files, and a check that a reader
// fails with an InputError that names the file, the line and the field in its
// message, which is what a user sees.
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "common/input_error.h"

namespace rc::test {

// A fresh directory per test, removed afterwards.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("rc_traces_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
            std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~ScratchDir() { std::filesystem::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Write(const std::string& name, const std::string& content) const {
    const std::string path = Path(name);
    std::ofstream(path, std::ios::binary) << content;
    return path;
  }
  // Files in the directory, to prove nothing partial was left behind.
  int FileCount() const {
    int n = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_)) ++n;
    return n;
  }

 private:
  std::filesystem::path dir_;
};

// Runs `read` and expects an InputError at (file, line, field) whose message
// shows all three ("file:line: field 'field': ...", or no ":line" for line 0).
inline void ExpectInputError(const std::function<void()>& read, const std::string& file, long line,
                             const std::string& field) {
  try {
    read();
    ADD_FAILURE() << "expected InputError at " << file << ":" << line << " field '" << field << "'";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.file(), file) << message;
    EXPECT_EQ(e.line(), line) << message;
    EXPECT_EQ(e.field(), field) << message;
    const std::string where = line > 0 ? file + ":" + std::to_string(line) : file;
    EXPECT_NE(message.find(where), std::string::npos) << message;
    if (!field.empty()) {
      EXPECT_NE(message.find("'" + field + "'"), std::string::npos) << message;
    }
  }
}

}  // namespace rc::test
