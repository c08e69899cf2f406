#pragma once
// The CUDA-core baseline: one query per thread, warps of 32 consecutive
// queries, 8 SMs with up to 32 resident warps each, GTO issue (paper).
//
// Instructions: what one thread of the kernel issues, by class, from the
// compiled CUDA kernel of the record's step program (backends/cuda/,
// simt_instruction_table.h): its prologue and epilogue once per query (the
// kernel with the beam leaf compiled in when the record has that leaf: by
// default the max-log leaf of beam_leaf.asm that the RT units price,
// simt.beam_leaf = exact for the host's exact density), its loop once per
// node. The precision and ISA are parameters
// (simt.precision: host follows the kernel that ran; simt.isa: PTX as the
// artifact simulates, or SASS). A program with no compiled kernel (a
// ConfigRoboCore program, or a custom leaf) is counted by the per-op
// fallback of SimtParams, and InstructionMix says so.
//
// A warp runs until its slowest lane: it issues the whole loop body on each
// of its max-lane-nodes steps; a lane is active in step k while it has more
// than k nodes. SIMT efficiency = thread instructions / (32 x warp
// instructions).
//
// Memory: per warp step, the active lanes' nodes are coalesced into unique
// 32-byte sectors (memory_replay.h, coalesced pattern over the resident
// warps); the step waits for its slowest sector.
//
// Time, per SM (first-order latency hiding): the largest of
//   issue     warp instructions / (4 schedulers x 1 per cycle)
//   pipes     per pipe, the sum over its classes of warp instructions x
//             the class's initiation interval, over 4 schedulers: FP32 pipe
//             (fp32, other, branch), INT pipe (int), SFU pipe (sfu, the
//             divisions, and fp64 while simt.fp64_units_per_scheduler is 0,
//             as in the artifact), FP64 pipe (fp64 otherwise), LD/ST pipe
//             (loads and stores, one per cycle)
//   L1        sector requests / l1_sectors_per_cycle
//   latency   list-schedule makespan of the warps' latencies over the
//             resident slots (registers per thread from ptxas); a warp's
//             latency = the sum over its instructions of their class
//             latency (the loop body is one dependent chain; loads and
//             stores add none, the memory replay times the loads) + its
//             steps' memory latencies
// and the kernel takes the launch (artifact: 5000 cycles) plus the slowest
// SM, or DRAM bandwidth if slower. Left out: scoreboard stalls beyond the
// fixed class latencies, dual issue, register-bank conflicts, instruction
// cache misses, divergence reconvergence cost, the out-of-line slow paths of
// SASS division and square root, and partial overlap between the bounds
// (max() is optimistic when they are close).
#include <string>

#include "backends/backend.h"
#include "backends/simt_instruction_table.h"

namespace rc {

// What one thread of a record's kernel issues.
struct SimtInstructionMix {
  SimtClassCounts once{};  // prologue + epilogue (+ leaf): once per query
  SimtClassCounts pass{};  // one loop pass: once per node
  int registers = 0;       // per thread
  bool fp64 = false;       // the precision priced
  bool compiled = false;   // false: the per-op fallback (no compiled kernel)
  std::string source;      // where the counts come from, for reports and tests
};

class SimtBackend final : public Backend {
 public:
  explicit SimtBackend(const BackendParameters& params);
  const BackendSpecs& specs() const override { return specs_; }

  SimtInstructionMix InstructionMix(const KernelRecord& record) const;
  void AnnouncePricing(const KernelRecord& record, PricingContext& context) const override;
  // The per-op fallback's instructions for one execution of `ops` (loop:
  // one pass, with its branches).
  SimtClassCounts FallbackInstructions(const std::vector<MicroOp>& ops, bool loop, bool fp64) const;

 protected:
  BatchCost DoPrice(const KernelRecord& record, PricingContext& context) const override;

 private:
  // Coalesced, in waves of the warps that fit an SM at the mix's registers.
  AccessPattern MemoryPattern(const SimtInstructionMix& mix) const;

  GpuParams gpu_;
  SimtParams simt_;
  EnergyParams energy_;
  BackendSpecs specs_;
};

}  // namespace rc
