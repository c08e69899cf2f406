#pragma once
// What the GPU check's exporters write about each priced launch
// (docs/gpu_check.md): the SIMT kernel variants they price, and one CSV
// layout for a SIMT BatchCost, shared by model.csv and sact_model.csv.
#include <cstdint>
#include <ostream>
#include <utility>

#include "backends/backend.h"
#include "backends/calibration/pricing_helpers.h"

namespace rc::gpu_check {

// Precision x instruction set: PTX, as the artifact simulates, and SASS,
// what sm_75 hardware issues (backends/simt_instruction_table.h).
inline constexpr std::pair<SimtPrecision, SimtIsa> kSimtVariants[] = {{SimtPrecision::kFp64, SimtIsa::kPtx},
                                                                      {SimtPrecision::kFp32, SimtIsa::kPtx},
                                                                      {SimtPrecision::kFp64, SimtIsa::kSass},
                                                                      {SimtPrecision::kFp32, SimtIsa::kSass}};

inline const char* PrecisionName(SimtPrecision p) { return p == SimtPrecision::kFp64 ? "fp64" : "fp32"; }
inline const char* IsaName(SimtIsa isa) { return isa == SimtIsa::kPtx ? "ptx" : "sass"; }

// The columns WriteSimtCost writes, comma-separated, without a newline.
inline constexpr const char* kSimtCostColumns =
    "queries,nodes,cycles,launch_cycles,clock_hz,kernel_s,total_s,simt_efficiency,warp_instructions,"
    "thread_instructions,sector_requests,l1_hit_rate,l2_hit_rate,bound";

inline double Ratio(std::uint64_t part, std::uint64_t whole) {
  return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

// One launch's kSimtCostColumns (kernel_s without the launch, total_s with it).
inline void WriteSimtCost(std::ostream& csv, const BatchCost& cost) {
  csv << cost.queries << ',' << cost.nodes << ',' << cost.cycles << ',' << cost.launch_cycles << ',' << cost.clock_hz
      << ',' << KernelSeconds(cost) << ',' << cost.seconds << ',' << cost.simt_efficiency << ','
      << cost.warp_instructions << ',' << cost.thread_instructions << ',' << cost.memory.sector_requests << ','
      << Ratio(cost.memory.l1_hits, cost.memory.sector_requests) << ','
      << Ratio(cost.memory.l2_hits, cost.memory.l2_accesses) << ',' << cost.bound;
}

}  // namespace rc::gpu_check
