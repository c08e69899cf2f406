#pragma once
// libFuzzer hands a target bytes; most rcbench parsers take a path. These
// helpers put the bytes in a file of the right name and define what a
// finding is, the same way for every target.
//
// A parser under fuzzing may return a value or throw InputError or
// UsageError, the errors rcbench reports with their documented exit codes
// (common/exit_codes.h). Anything else that escapes (std::bad_alloc, a
// std::out_of_range, an MRPT or OpenCV exception) is a finding: it would
// reach the user as an internal error. So do a crash, a sanitizer report,
// a timeout (-timeout) and an allocation above -malloc_limit_mb.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace rc::fuzz {

// The bytes as text.
inline std::string_view AsText(const std::uint8_t* data, std::size_t size) {
  return std::string_view(reinterpret_cast<const char*>(data), size);
}

// Writes `bytes` to <per-process folder>/<name> and returns the path. The
// folder is in /dev/shm when it exists (no disk traffic per input).
std::string WriteInputFile(const std::string& name, std::string_view bytes);

// Splits an input at the first occurrence of `separator`: a target that
// needs two files (a ROS YAML and its image) takes both from one input.
// Without the separator, everything is `first` and `second` is empty.
void SplitInput(std::string_view input, std::string_view separator, std::string_view* first, std::string_view* second);

// Runs `parse`; swallows InputError and UsageError, rethrows everything else
// (libFuzzer then reports the uncaught exception as a crash).
template <typename Parse>
void ExpectParsedOrInputError(Parse&& parse);

}  // namespace rc::fuzz

#include "common/input_error.h"

namespace rc::fuzz {

// With RC_FUZZ_VERBOSE set, says whether each input parsed or why not
// (to check that seeds parse, and to triage).
void Report(const char* outcome);

template <typename Parse>
void ExpectParsedOrInputError(Parse&& parse) {
  try {
    parse();
    Report("parsed");
  } catch (const InputError& e) {
    Report(e.what());
  } catch (const UsageError& e) {
    Report(e.what());
  }
}

// A property every successful parse must have; abort() makes it a finding.
void Require(bool condition, const char* what);

}  // namespace rc::fuzz
