// rcbench: robotics kernels on modelled GPU backends.
//
// Exit codes: one table for every subcommand, common/exit_codes.h.
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>
#if defined(__GLIBC__)  // defined by the headers above
#include <malloc.h>
#endif

#include <CLI/CLI.hpp>

#include "common/cpu_features.h"
#include "common/exit_codes.h"
#include "common/input_error.h"
#include "common/memory_cap.h"
#include "workloads/rcbench/commands.h"

int main(int argc, char** argv) {
  // One malloc arena for every thread: a priced launch's buffers are
  // allocated by whichever OpenMP thread runs its task, and with an arena
  // per thread a buffer freed in one was not reused by the next launch on
  // the other, so peak memory depended on scheduling (docs/pricing.md, "One
  // malloc arena").
  //
  // Buffers below 4 MiB come from the heap, and the heap keeps up to 256 MiB
  // of freed memory instead of returning it to the kernel: a priced launch
  // allocates and frees per-query buffers of a few MiB, and with glibc's
  // defaults each was mapped afresh and page-faulted again, launch after
  // launch (docs/pricing.md, "Freed buffers kept for the next launch").
  //
  // Host time and memory only: a failed call changes no result.
#if defined(__GLIBC__)
  mallopt(M_ARENA_MAX, 1);
  mallopt(M_MMAP_THRESHOLD, 4 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
  CLI::App app{"rcbench: robotics kernels (MCL ray casting, A*, RRT*) on modelled GPU backends"};
  app.require_subcommand(1);
  // Options of the top level (--max-memory) may follow the subcommand.
  app.fallthrough();
  app.footer(rc::ExitCodeFooter("carribot: a query found no path; movebot: no exact path (outputs are still written)"));
  app.add_option_function<double>(
         "--max-memory",
         [](double gib) {
           if (!(gib > 0.0) || !std::isfinite(gib) || gib > 1e9)
             throw rc::UsageError("--max-memory must be a positive number of GiB");
           rc::SetMemoryCapBytes(static_cast<std::uint64_t>(gib * 1073741824.0));
         },
         "Memory cap (GiB) that maps, particle sets and batches are checked against before they are allocated; "
         "default: the machine's memory")
      ->trigger_on_parse();
  app.add_option_function<std::string>(
         "--simd",
         [](const std::string& text) {
           rc::SimdLevel level;
           if (!rc::ParseSimdLevel(text, &level))
             throw rc::UsageError("--simd must be scalar, avx2 or avx512, got '" + text + "'");
           try {
             rc::LimitSimd(level);
           } catch (const std::invalid_argument& e) {  // a level this CPU does not run
             throw rc::UsageError("--simd " + text + ": " + e.what());
           }
         },
         "Widest SIMD code used (scalar, avx2, avx512; default: the widest this CPU runs). Results are the same "
         "on every level; only the host time changes")
      ->trigger_on_parse();
  rc::AddDelibotCommand(app);
  rc::AddCarribotCommand(app);
  rc::AddSimulateCommand(app);
  rc::AddMakeMapCommand(app);
  rc::AddBackendsCommand(app);
  rc::AddCollideCommand(app);
  rc::AddCalibrateCommand(app);
  rc::AddMovebotCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // The same "rcbench: usage:" line as a UsageError thrown by a subcommand.
    std::cerr << "rcbench: usage: " << e.what() << "\nRun with --help for more information.\n";
    return rc::ToInt(rc::ExitCode::kUsage);
  } catch (...) {
    return rc::ToInt(rc::ReportException(std::current_exception(), std::cerr));
  }
  return rc::ToInt(rc::ExitCode::kSuccess);
}
