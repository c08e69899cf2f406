#pragma once
// A user-facing input error (gem5's fatal(), as opposed to an internal bug).
// Every loader and reader throws this with the file, the 1-based line and the
// field that was wrong, so the CLI can print one clear message and exit
// nonzero without writing any partial output.
#include <stdexcept>
#include <string>

namespace rc {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, long line, std::string field, const std::string& problem)
      : std::runtime_error(Format(file, line, field, problem)),
        file_(std::move(file)),
        line_(line),
        field_(std::move(field)) {}

  const std::string& file() const { return file_; }
  // 1-based line number; 0 when the problem concerns the whole file.
  long line() const { return line_; }
  const std::string& field() const { return field_; }

 private:
  static std::string Format(const std::string& file, long line, const std::string& field, const std::string& problem) {
    std::string where = file;
    if (line > 0) where += ":" + std::to_string(line);
    if (!field.empty()) where += ": field '" + field + "'";
    return where + ": " + problem;
  }

  std::string file_;
  long line_;
  std::string field_;
};

// A bad command-line value or option combination (no file involved).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output file or folder that cannot be created or written (a missing
// permission, a full disk). Like InputError it is the user's to fix, not a
// bug; the message names the path.
class OutputError : public std::runtime_error {
 public:
  OutputError(const std::string& path, const std::string& problem) : std::runtime_error(path + ": " + problem) {}
};

}  // namespace rc
