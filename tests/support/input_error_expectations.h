#pragma once
// The tests' checks of bad input: a call must throw an InputError whose
// fields, and whose message (what a user sees), name where the input is
// wrong.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "common/input_error.h"
#include "support/temp_dir.h"

namespace rc::test {

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

// The InputError that f() throws, for a test that checks several of its
// parts. When f() throws none, the test fails (naming `input`, what f()
// read) and an empty error comes back.
template <typename F>
InputError InputErrorFrom(F&& f, const std::string& input = "") {
  try {
    std::forward<F>(f)();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for: " << input;
  return InputError("", 0, "", "");
}

// For EXPECT_TRUE: success when f() throws an InputError whose line and
// field match and whose message contains problem_part (the file is not
// checked: the caller may not know the path).
template <typename F>
::testing::AssertionResult ThrowsInputError(F&& f, long line, const std::string& field,
                                            const std::string& problem_part) {
  try {
    std::forward<F>(f)();
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (e.line() != line || e.field() != field || what.find(problem_part) == std::string::npos)
      return ::testing::AssertionFailure()
             << "InputError mismatch: got line " << e.line() << ", field '" << e.field() << "', message '" << what
             << "'; expected line " << line << ", field '" << field << "', message containing '" << problem_part << "'";
    return ::testing::AssertionSuccess() << what;
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "threw a different exception: " << e.what();
  }
  return ::testing::AssertionFailure() << "did not throw";
}

// A malformed file and the InputError it must raise (as ThrowsInputError).
struct MalformedCase {
  const char* name;
  std::string content;
  long line;
  const char* field;
  const char* problem;
};

// Writes each case to `file_name` in a fresh TempDir and expects `load(path)`
// to refuse it with the case's line, field and problem.
template <typename Load>
void ExpectEveryCaseRefused(const std::vector<MalformedCase>& cases, const std::string& file_name, Load&& load) {
  for (const MalformedCase& c : cases) {
    SCOPED_TRACE(c.name);
    const TempDir dir;
    const std::string path = dir.Write(file_name, c.content);
    EXPECT_TRUE(ThrowsInputError([&] { load(path); }, c.line, c.field, c.problem));
  }
}

}  // namespace rc::test
