#pragma once
// The process exit codes of every rcbench subcommand: one table, used by
// main() to map an error to its code and by every subcommand's --help footer.
// A script can rely on these across subcommands; tests/cli checks each one
// per subcommand.
#include <exception>
#include <iosfwd>
#include <string>
#include <vector>

namespace rc {

enum class ExitCode : int {
  kSuccess = 0,
  // A file cannot be read or written, or holds a malformed or impossible
  // value (InputError / OutputError; the message names file, line and
  // field), or the input makes the run impossible (a map with no free cell).
  kInputError = 1,
  // A bad command-line option or value (CLI11 errors and UsageError),
  // including a particle count or batch that cannot fit in memory.
  kUsage = 2,
  // carribot: at least one query found no path; movebot: no exact path.
  // Every output is written before exiting with this code.
  kNoPath = 3,
  // A bug: any other exception (a failed internal check, out of memory in a
  // place no cap foresaw). The message asks for a report.
  kInternalError = 4,
};

struct ExitCodeEntry {
  ExitCode code;
  const char* meaning;
};

// The table above, in order, for documentation and --help.
const std::vector<ExitCodeEntry>& ExitCodeTable();

// "Exit codes: 0 success; 1 ...; 2 ...; 3 <no_path_meaning>; 4 ..." for a
// subcommand's --help footer. Subcommands that never exit with 3 pass "".
std::string ExitCodeFooter(const std::string& no_path_meaning);

// Prints one "<program>: ..." line for the exception to `err` and returns
// its code: UsageError -> kUsage; InputError, OutputError -> kInputError;
// anything else -> kInternalError.
ExitCode ReportException(const std::exception_ptr& error, std::ostream& err, const char* program = "rcbench");

constexpr int ToInt(ExitCode code) { return static_cast<int>(code); }

// Ends a subcommand's run that returned `code`: returns for 0; otherwise
// flushes stdout and stderr and exits the process with `code` (a
// subcommand's documented outcome such as kNoPath, its outputs written).
void ExitUnlessSuccess(int code);

}  // namespace rc
