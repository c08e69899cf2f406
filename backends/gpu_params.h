#pragma once
// Parameters every modelled backend shares: the GPU around the cores
// (SMs, caches, DRAM, clocks, kernel launch) and the energy per operation.
// The backends model one GPU, so a sweep over SMs or cache sizes changes
// all of them alike.
//
// Each parameter is declared once (common/parameter_spec.h): type, name,
// default, unit, valid range, source. "paper" is the RoboGPU paper's
// Vulkan-Sim configuration table, "artifact" its gpgpusim.config
// (code/workloads/collision_detection), "Horowitz" the 45 nm energies of
// ISSCC 2014 (REFERENCE.md sections 1, 2, 4).
#include <string>

#include "common/parameter_spec.h"

namespace rc {

#define RC_GPU_PARAMETERS(X)                                                                                    \
  X(int, sms, 8, "count", 1, 256, "paper: Vulkan-Sim configuration table")                                      \
  X(int, max_warps_per_sm, 32, "warps", 1, 64, "paper")                                                         \
  X(int, warp_size, 32, "threads", 1, 64, "paper (CUDA warp)")                                                  \
  X(int, registers_per_sm, 32768, "registers", 1024, 1 << 20, "paper")                                          \
  X(int, warps_per_block, 8, "warps", 1, 32,                                                                    \
    "assumption: 256-thread blocks, the common CUDA choice, dealt to SMs round-robin")                          \
  X(double, core_clock_hz, 1365e6, "Hz", 1e8, 5e9, "paper (compute : interconnect : L2 clock)")                 \
  X(double, dram_clock_hz, 3500e6, "Hz", 1e8, 2e10, "paper (memory clock)")                                     \
  X(int, sector_bytes, 32, "bytes", 8, 128, "artifact: sectored L1D/L2, 32-byte sectors")                       \
  X(int, line_bytes, 128, "bytes", 32, 512, "artifact: -gpgpu_cache:dl1 and dl2 block size")                    \
  X(int, l1_bytes, 64 * 1024, "bytes per SM", 1024, 1 << 24,                                                    \
    "paper: L1 data + shared, fully associative LRU (the artifact's dl1 line describes 8 KB)")                  \
  X(int, l1_latency_cycles, 20, "core cycles", 1, 200, "paper")                                                 \
  X(int, l2_bytes, 3 * 1024 * 1024, "bytes", 16 * 1024, 1 << 28,                                                \
    "paper: unified, 16-way LRU (the artifact's dl2 lines describe 512 KB)")                                    \
  X(int, l2_ways, 16, "ways", 1, 64, "paper")                                                                   \
  X(int, l2_latency_cycles, 160, "core cycles beyond L1", 0, 2000, "paper; artifact -gpgpu_l2_rop_latency 160") \
  X(int, dram_latency_dram_cycles, 100, "DRAM cycles beyond L2", 0, 5000, "artifact: -dram_latency 100")        \
  X(int, dram_cas_dram_cycles, 20, "DRAM cycles", 0, 500, "artifact: -gpgpu_dram_timing_opt CL=20")             \
  X(int, dram_channels, 4, "count", 1, 64, "artifact: -gpgpu_n_mem 4")                                          \
  X(int, dram_bus_bytes, 2, "bytes per transfer", 1, 64, "artifact: -gpgpu_dram_buswidth 2")                    \
  X(int, dram_transfers_per_clock, 2, "transfers per DRAM cycle", 1, 8, "assumption: double data rate")         \
  X(int, kernel_launch_cycles, 5000, "core cycles", 0, 1000000, "artifact: -gpgpu_kernel_launch_latency 5000")

struct GpuParams {
  RC_GPU_PARAMETERS(RC_PARAMETER_MEMBER)

  // Core cycles a DRAM access adds beyond an L2 miss.
  int DramExtraCycles() const;
  double DramBytesPerCoreCycle() const;
  // Ranges, and what the ranges cannot say (powers of two, sizes that
  // divide into lines and ways).
  bool IsValid(std::string* error) const;

  template <class Self, class Visitor>
  static void Fields(Self& s, Visitor& v) {
    RC_GPU_PARAMETERS(RC_PARAMETER_FIELD)
  }
};

// Energy per event at 45 nm. SRAM and DRAM figures are per 64-bit access;
// the *_accesses fields say how many such accesses an event makes. The L1
// (64 KB) is priced as 32 KB arrays and the L2 (3 MB) as 1 MB arrays
// (assumption). Leakage and static energy are not modelled.
#define RC_ENERGY_PARAMETERS(X)                                                                               \
  X(double, fp32_add_pj, 0.9, "pJ", 0, 1e3, "Horowitz ISSCC 2014, 45 nm")                                     \
  X(double, fp32_mul_pj, 3.7, "pJ", 0, 1e3, "Horowitz")                                                       \
  X(double, int32_add_pj, 0.1, "pJ", 0, 1e3, "Horowitz")                                                      \
  X(double, fp32_reciprocal_pj, 14.8, "pJ", 0, 1e3, "assumption: about 4 FP32 multiplies (Newton-Raphson)")   \
  X(double, sram_8kb_pj, 10.0, "pJ per 64-bit access", 0, 1e4, "Horowitz")                                    \
  X(double, sram_32kb_pj, 20.0, "pJ per 64-bit access", 0, 1e4,                                               \
    "Horowitz; also the 64 KB L1, as 32 KB arrays (assumption)")                                              \
  X(double, sram_1mb_pj, 100.0, "pJ per 64-bit access", 0, 1e4,                                               \
    "Horowitz; also the 3 MB L2, as 1 MB arrays (assumption)")                                                \
  X(double, dram_pj, 1950.0, "pJ per 64-bit access", 0, 1e5, "assumption: midpoint of Horowitz's 1.3-2.6 nJ") \
  X(double, simt_icache_accesses_per_warp_instruction, 1.0, "32 KB accesses", 0, 16,                          \
    "assumption: one 64-bit fetch from a 32 KB bank of the 128 KB icache per warp instruction")               \
  X(double, simt_register_accesses_per_thread_instruction, 1.5, "8 KB accesses", 0, 16,                       \
    "2 reads + 1 write of 32 bits; 8 KB banks = 128 KB RF / 16 (artifact -gpgpu_num_reg_banks 16)")           \
  X(double, rt_packet_accesses_per_micro_op, 1.0, "8 KB accesses", 0, 16,                                     \
    "assumption: operands read from and result written to the thread's packet")                               \
  X(double, rt_packet_accesses_per_hop, 2.0, "8 KB accesses", 0, 16,                                          \
    "assumption: a packet written into and read out of an interconnect buffer")                               \
  X(double, rt_packet_accesses_per_predicated_op, 1.0, "8 KB accesses", 0, 16,                                \
    "assumption: a predicated packet passes one buffer")                                                      \
  X(double, rt_warp_buffer_accesses_per_thread, 4.0, "8 KB accesses", 0, 64,                                  \
    "assumption: ray state in, result out of the warp buffer")

struct EnergyParams {
  RC_ENERGY_PARAMETERS(RC_PARAMETER_MEMBER)

  template <class Self, class Visitor>
  static void Fields(Self& s, Visitor& v) {
    RC_ENERGY_PARAMETERS(RC_PARAMETER_FIELD)
  }
};

}  // namespace rc
