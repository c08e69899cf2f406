#pragma once
// The CUDA-core baseline: one query per thread, warps of 32 consecutive
// queries, 8 SMs with up to 32 resident warps each, GTO issue (paper).
//
// Instructions: each micro-op of the kernel's program (robocore/programs)
// becomes SimtParams::instructions_per_element[op] x width scalar
// instructions (SACT micro-ops through their TTA+ expansion, a LOAD
// instructions_per_load), plus loop_branch_instructions per loop pass. The
// programs are written from the C++ kernels, so the counts follow the code
// the GPU would run; the per-op table is an assumption about its SASS.
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
//   issue     warp instructions / (4 schedulers x 1 per cycle), and x 2
//             cycles each on the schedulers' ALUs (artifact initiation
//             interval of FP/INT add, mul, mad)
//   L1        sector requests / l1_sectors_per_cycle
//   latency   list-schedule makespan of the warps' latencies over the
//             resident slots; a warp's latency = its instructions x the
//             dependent-instruction latency (the loop body is one
//             dependent chain) + its steps' memory latencies
// and the kernel takes the launch (artifact: 5000 cycles) plus the slowest
// SM, or DRAM bandwidth if slower. Left out: scoreboard stalls within a
// chain beyond the fixed latency, register-bank conflicts, instruction
// cache misses, divergence reconvergence cost, and partial overlap between
// the bounds (max() is optimistic when they are close).
#include "backends/backend.h"

namespace rc {

class SimtBackend final : public Backend {
 public:
  explicit SimtBackend(const BackendParameters& params);
  const BackendSpecs& specs() const override { return specs_; }

  // Scalar instructions of one execution of `ops` (loop: one pass).
  std::uint64_t SectionInstructions(const std::vector<MicroOp>& ops, bool loop) const;

 protected:
  BatchCost DoPrice(const KernelRecord& record, PricingContext& context) const override;

 private:
  GpuParams gpu_;
  SimtParams simt_;
  EnergyParams energy_;
  BackendSpecs specs_;
};

}  // namespace rc
