#pragma once
// Parameters every modelled backend shares: the GPU around the cores
// (SMs, caches, DRAM, clocks, kernel launch) and the energy per operation.
// The backends model one GPU, so a sweep over SMs or cache sizes changes
// all of them alike.
//
// Every field is listed twice: declared with a comment (unit; source), and
// in Fields(), the machine-readable table that printing and the JSON
// override file use. "paper" is the RoboGPU paper's Vulkan-Sim
// configuration table, "artifact" its gpgpusim.config
// (code/workloads/collision_detection), "Horowitz" the 45 nm energies of
// ISSCC 2014 (REFERENCE.md sections 1, 2, 4).
#include <string>

namespace rc {

struct GpuParams {
  int sms = 8;                          // count; paper
  int max_warps_per_sm = 32;            // warps; paper
  int warp_size = 32;                   // threads; paper (CUDA warp)
  int registers_per_sm = 32768;         // 32-bit registers; paper
  int warps_per_block = 8;              // warps; assumption: 256-thread blocks, the common CUDA choice
  double core_clock_hz = 1365e6;        // Hz; paper (compute clock, also interconnect and L2)
  double dram_clock_hz = 3500e6;        // Hz; paper
  int sector_bytes = 32;                // bytes; artifact (sectored L1/L2, 32-byte sectors)
  int line_bytes = 128;                 // bytes; artifact (-gpgpu_cache:dl1 / dl2 block size)
  int l1_bytes = 64 * 1024;             // bytes per SM; paper (L1 data + shared, fully associative LRU)
  int l1_latency_cycles = 20;           // core cycles; paper
  int l2_bytes = 3 * 1024 * 1024;       // bytes; paper (16-way LRU)
  int l2_ways = 16;                     // ways; paper
  int l2_latency_cycles = 160;          // core cycles beyond L1; paper (artifact -gpgpu_l2_rop_latency)
  int dram_latency_dram_cycles = 100;   // DRAM cycles beyond L2; artifact (-dram_latency)
  int dram_cas_dram_cycles = 20;        // DRAM cycles; artifact (-gpgpu_dram_timing_opt CL=20)
  int dram_channels = 4;                // count; artifact (-gpgpu_n_mem)
  int dram_bus_bytes = 2;               // bytes per transfer per channel; artifact (-gpgpu_dram_buswidth)
  int dram_transfers_per_clock = 2;     // count; assumption: double data rate
  int kernel_launch_cycles = 5000;      // core cycles; artifact (-gpgpu_kernel_launch_latency)

  // Core cycles a DRAM access adds beyond an L2 miss.
  int DramExtraCycles() const;
  double DramBytesPerCoreCycle() const;
  bool IsValid(std::string* error) const;

  template <class Self, class Visitor>
  static void Fields(Self& s, Visitor& v) {
    v("sms", s.sms, "count", "paper: Vulkan-Sim configuration table");
    v("max_warps_per_sm", s.max_warps_per_sm, "warps", "paper");
    v("warp_size", s.warp_size, "threads", "paper (CUDA warp)");
    v("registers_per_sm", s.registers_per_sm, "registers", "paper");
    v("warps_per_block", s.warps_per_block, "warps", "assumption: 256-thread blocks, blocks dealt to SMs round-robin");
    v("core_clock_hz", s.core_clock_hz, "Hz", "paper (compute : interconnect : L2 clock)");
    v("dram_clock_hz", s.dram_clock_hz, "Hz", "paper (memory clock)");
    v("sector_bytes", s.sector_bytes, "bytes", "artifact: sectored L1D/L2, 32-byte sectors");
    v("line_bytes", s.line_bytes, "bytes", "artifact: -gpgpu_cache:dl1 and dl2 block size");
    v("l1_bytes", s.l1_bytes, "bytes per SM", "paper: L1 data + shared, fully associative LRU");
    v("l1_latency_cycles", s.l1_latency_cycles, "core cycles", "paper");
    v("l2_bytes", s.l2_bytes, "bytes", "paper: unified, 16-way LRU");
    v("l2_ways", s.l2_ways, "ways", "paper");
    v("l2_latency_cycles", s.l2_latency_cycles, "core cycles beyond L1", "paper; artifact -gpgpu_l2_rop_latency");
    v("dram_latency_dram_cycles", s.dram_latency_dram_cycles, "DRAM cycles beyond L2", "artifact: -dram_latency");
    v("dram_cas_dram_cycles", s.dram_cas_dram_cycles, "DRAM cycles", "artifact: -gpgpu_dram_timing_opt CL=20");
    v("dram_channels", s.dram_channels, "count", "artifact: -gpgpu_n_mem");
    v("dram_bus_bytes", s.dram_bus_bytes, "bytes per transfer", "artifact: -gpgpu_dram_buswidth");
    v("dram_transfers_per_clock", s.dram_transfers_per_clock, "transfers per DRAM cycle", "assumption: double data rate");
    v("kernel_launch_cycles", s.kernel_launch_cycles, "core cycles", "artifact: -gpgpu_kernel_launch_latency");
  }
};

// Energy per event at 45 nm. SRAM and DRAM figures are per 64-bit access;
// the *_accesses fields say how many such accesses an event makes.
// Leakage and static energy are not modelled.
struct EnergyParams {
  double fp32_add_pj = 0.9;             // pJ; Horowitz
  double fp32_mul_pj = 3.7;             // pJ; Horowitz
  double int32_add_pj = 0.1;            // pJ; Horowitz
  double fp32_reciprocal_pj = 14.8;     // pJ; assumption: about 4 FP32 multiplies (Newton-Raphson)
  double sram_8kb_pj = 10.0;            // pJ per 64-bit access; Horowitz
  double sram_32kb_pj = 20.0;           // pJ per 64-bit access; Horowitz
  double sram_1mb_pj = 100.0;           // pJ per 64-bit access; Horowitz
  double dram_pj = 1950.0;              // pJ per 64-bit access; assumption: midpoint of Horowitz's 1.3-2.6 nJ
  // L1 (64 KB) priced as 32 KB arrays, L2 (3 MB) as 1 MB arrays: assumption.
  double simt_icache_accesses_per_warp_instruction = 1.0;    // 32 KB accesses; assumption: one 64-bit fetch from a 32 KB bank of the 128 KB icache
  double simt_register_accesses_per_thread_instruction = 1.5;  // 8 KB accesses; 2 reads + 1 write of 32 bits; 128 KB RF / 16 banks (artifact -gpgpu_num_reg_banks) = 8 KB
  double rt_packet_accesses_per_micro_op = 1.0;  // 8 KB accesses; assumption: operands read from and result written to the thread's packet
  double rt_packet_accesses_per_hop = 2.0;       // 8 KB accesses; assumption: a packet written into and read out of an interconnect buffer
  double rt_packet_accesses_per_predicated_op = 1.0;  // 8 KB accesses; assumption: a predicated packet passes one buffer
  double rt_warp_buffer_accesses_per_thread = 4.0;    // 8 KB accesses; assumption: ray state in, result out of the warp buffer

  bool IsValid(std::string* error) const;

  template <class Self, class Visitor>
  static void Fields(Self& s, Visitor& v) {
    v("fp32_add_pj", s.fp32_add_pj, "pJ", "Horowitz ISSCC 2014, 45 nm");
    v("fp32_mul_pj", s.fp32_mul_pj, "pJ", "Horowitz");
    v("int32_add_pj", s.int32_add_pj, "pJ", "Horowitz");
    v("fp32_reciprocal_pj", s.fp32_reciprocal_pj, "pJ", "assumption: about 4 FP32 multiplies (Newton-Raphson)");
    v("sram_8kb_pj", s.sram_8kb_pj, "pJ per 64-bit access", "Horowitz");
    v("sram_32kb_pj", s.sram_32kb_pj, "pJ per 64-bit access", "Horowitz; also the 64 KB L1, as 32 KB arrays (assumption)");
    v("sram_1mb_pj", s.sram_1mb_pj, "pJ per 64-bit access", "Horowitz; also the 3 MB L2, as 1 MB arrays (assumption)");
    v("dram_pj", s.dram_pj, "pJ per 64-bit access", "assumption: midpoint of Horowitz's 1.3-2.6 nJ");
    v("simt_icache_accesses_per_warp_instruction", s.simt_icache_accesses_per_warp_instruction, "32 KB accesses", "assumption: one 64-bit fetch per warp instruction");
    v("simt_register_accesses_per_thread_instruction", s.simt_register_accesses_per_thread_instruction, "8 KB accesses", "2 reads + 1 write of 32 bits; 8 KB banks = 128 KB RF / 16 (artifact -gpgpu_num_reg_banks)");
    v("rt_packet_accesses_per_micro_op", s.rt_packet_accesses_per_micro_op, "8 KB accesses", "assumption: operands and result in the thread's packet");
    v("rt_packet_accesses_per_hop", s.rt_packet_accesses_per_hop, "8 KB accesses", "assumption: into and out of an interconnect buffer");
    v("rt_packet_accesses_per_predicated_op", s.rt_packet_accesses_per_predicated_op, "8 KB accesses", "assumption: a predicated packet passes one buffer");
    v("rt_warp_buffer_accesses_per_thread", s.rt_warp_buffer_accesses_per_thread, "8 KB accesses", "assumption: ray state in, result out");
  }
};

}  // namespace rc
