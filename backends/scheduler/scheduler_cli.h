#pragma once
// The scheduler's command-line front end, shared by every subcommand that
// prices (delibot, carribot, movebot): one set of options, one mapping onto
// LedgerOptions, one printed summary and one JSON block, so the
// subcommands cannot drift apart.
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "backends/backend_params.h"
#include "backends/backend_preset.h"
#include "backends/scheduler/backend_ledger.h"

namespace rc {

struct SchedulerCli {
  std::string policy = "adaptive";
  std::string candidates;   // comma-separated; empty: every modelled backend
  double threshold = -1.0;  // threshold policy; < 0: derived
  double hysteresis = 0.0;
  double switch_cost = 0.0;                       // core cycles
  int replay_sms = kReplaySms;                    // SMs replayed exactly; 0 = all
  int replay_block_stride = kReplayBlockStride;   // of a replayed SM's blocks, every this-many-th replayed
  int priced_launches = kPricedLaunchesPerBatch;  // full launches of a split batch priced; 0 = all
  std::string backend_params;                     // JSON override file
  bool no_pricing = false;
};

// Adds --backend, --candidates, --threshold, --hysteresis, --switch-cost,
// --replay-sms, --priced-launches, --backend-params and --no-pricing. `counter` names the
// workload's traversal counter in the help text ("nodes per ray").
void AddSchedulerOptions(CLI::App& command, SchedulerCli& cli, const std::string& counter);

// The ledger options the flags describe. Throws UsageError naming the flag.
LedgerOptions ToLedgerOptions(const SchedulerCli& cli);

// The --backend-params preset: defaults, a named preset ("artifact") or a
// file (backends/backend_preset.h; throws InputError naming the file and
// the key). Its kernel choices apply to workloads that cast rays (DeliBot).
BackendPreset BackendPresetOf(const SchedulerCli& cli);
// The preset's backend parameters.
BackendParameters BackendParametersOf(const SchedulerCli& cli);

// The priced summary every subcommand prints: each static backend's total,
// the policy's (switches, agreement with the oracle), the oracle's, and for
// the threshold policy its threshold. `what` names the iteration ("update",
// "launch"), `counter` the traversal counter.
void PrintLedgerSummary(std::ostream& out, const LedgerSummary& summary, const LedgerOptions& options, double clock_hz,
                        const std::string& what, const std::string& counter);

// The same as JSON (units in the keys).
nlohmann::json LedgerSummaryJson(const LedgerSummary& summary, const LedgerOptions& options);

}  // namespace rc
