#include "common/exit_codes.h"

#include <cstdlib>
#include <iostream>
#include <new>
#include <ostream>

#include "common/input_error.h"

namespace rc {

const std::vector<ExitCodeEntry>& ExitCodeTable() {
  static const std::vector<ExitCodeEntry> kTable = {
      {ExitCode::kSuccess, "success"},
      {ExitCode::kInputError,
       "bad input: a file cannot be read or written, or holds a malformed or impossible value "
       "(the message names file, line and field), or the input makes the run impossible"},
      {ExitCode::kUsage,
       "bad command line: an unknown option, a value out of range, or a size that cannot fit in memory"},
      {ExitCode::kNoPath, "no path was found (outputs are still written)"},
      {ExitCode::kInternalError, "internal error (a bug; please report it with the command line)"},
  };
  return kTable;
}

std::string ExitCodeFooter(const std::string& no_path_meaning) {
  std::string text = "Exit codes:";
  for (const ExitCodeEntry& e : ExitCodeTable()) {
    std::string meaning = e.meaning;
    if (e.code == ExitCode::kNoPath) {
      if (no_path_meaning.empty()) continue;
      meaning = no_path_meaning;
    }
    text += " " + std::to_string(ToInt(e.code)) + " " + meaning + ";";
  }
  text.back() = '.';
  return text;
}

ExitCode ReportException(const std::exception_ptr& error, std::ostream& err, const char* program) {
  try {
    std::rethrow_exception(error);
  } catch (const UsageError& e) {
    err << program << ": usage: " << e.what() << "\n";
    return ExitCode::kUsage;
  } catch (const InputError& e) {
    err << program << ": error: " << e.what() << "\n";
    return ExitCode::kInputError;
  } catch (const OutputError& e) {
    err << program << ": error: " << e.what() << "\n";
    return ExitCode::kInputError;
  } catch (const std::bad_alloc&) {
    err << program
        << ": internal error: out of memory in a step no size check foresaw; please report it "
           "with the command line\n";
    return ExitCode::kInternalError;
  } catch (const std::exception& e) {
    err << program << ": internal error: " << e.what() << " (please report it with the command line)\n";
    return ExitCode::kInternalError;
  } catch (...) {
    err << program << ": internal error: unknown exception (please report it with the command line)\n";
    return ExitCode::kInternalError;
  }
}

void ExitUnlessSuccess(int code) {
  if (code == 0) return;
  std::cout.flush();
  std::cerr.flush();
  std::exit(code);
}

}  // namespace rc
