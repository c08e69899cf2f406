#pragma once
// One parameter struct per modelled backend, plus the shared GPU and energy
// structs (gpu_params.h), gathered in BackendParameters.
//
// Each field: declared with a comment (unit; source) and listed in Fields(),
// the machine-readable table used by PrintBackendParameters and by
// LoadBackendParameters' JSON override file. A JSON file names the struct,
// then the field, nested or dotted:
//   {"gpu": {"sms": 16, "l1_bytes": 131072},
//    "robocore": {"sact_latency_scale": 2.0},
//    "simt": {"precision": "fp32", "instructions_per_element": {"DOT": 2}}}
// A choice (simt.precision, simt.isa) is a JSON string.
// Unknown keys and wrong types are InputErrors naming the file and the key.
#include <array>
#include <iosfwd>
#include <string>
#include <vector>

#include "backends/gpu_params.h"
#include "backends/simt_instruction_table.h"
#include "robocore/datapath_params.h"
#include "robocore/micro_op.h"

namespace rc {

// The CUDA-core (SIMT) baseline. Instruction counts come from the compiled
// CUDA kernels (simt_instruction_table.h); the timing of each instruction
// class is the artifact's (gpgpusim.config, code/workloads/
// collision_detection: -ptx_opcode_latency_* and -ptx_opcode_initiation_*,
// "ADD,MAX,MUL,MAD,DIV"; REFERENCE.md section 2). A program with no compiled
// kernel (a ConfigRoboCore program) is counted by the per-op fallback below.
struct SimtParams {
  int schedulers_per_sm = 4;                 // count; artifact -gpgpu_num_sched_per_core
  int issue_per_scheduler_per_cycle = 1;     // warp instructions; artifact -gpgpu_max_insn_issue_per_warp
  SimtPrecision precision = SimtPrecision::kHost;  // host: the scalar type of the kernel that ran (KernelRecord::scalar_bytes)
  SimtIsa isa = SimtIsa::kPtx;               // PTX: what the artifact simulates (-gpgpu_ptx_convert_to_ptxplus 0)
  SimtBeamLeaf beam_leaf = SimtBeamLeaf::kMaxLog;  // maxlog: beam_leaf.asm's computation, as the RT units price it
  // Per class: dependent-issue latency and initiation interval (core cycles).
  int fp32_latency_cycles = 4;               // artifact -ptx_opcode_latency_fp (ADD)
  int fp32_initiation_cycles = 2;            // artifact -ptx_opcode_initiation_fp (ADD)
  int fp64_latency_cycles = 8;               // artifact -ptx_opcode_latency_dp (ADD)
  int fp64_initiation_cycles = 4;            // artifact -ptx_opcode_initiation_dp (ADD)
  int int_latency_cycles = 4;                // artifact -ptx_opcode_latency_int (ADD)
  int int_initiation_cycles = 2;             // artifact -ptx_opcode_initiation_int (ADD)
  int fp32_div_latency_cycles = 39;          // artifact -ptx_opcode_latency_fp (DIV)
  int fp32_div_initiation_cycles = 4;        // artifact -ptx_opcode_initiation_fp (DIV)
  int fp64_div_latency_cycles = 330;         // artifact -ptx_opcode_latency_dp (DIV)
  int fp64_div_initiation_cycles = 130;      // artifact -ptx_opcode_initiation_dp (DIV)
  int int_div_latency_cycles = 145;          // artifact -ptx_opcode_latency_int (DIV)
  int int_div_initiation_cycles = 8;         // artifact -ptx_opcode_initiation_int (DIV)
  int sfu_latency_cycles = 100;              // artifact -ptx_opcode_latency_sfu
  int sfu_initiation_cycles = 8;             // artifact -ptx_opcode_initiation_sfu
  int other_latency_cycles = 1;              // artifact: GPGPU-Sim's default for every other opcode (and branches)
  int other_initiation_cycles = 1;           // artifact: as above
  int fp64_units_per_scheduler = 0;          // count; artifact -gpgpu_pipeline_widths DP = 0: FP64 runs on the SFU unit
  int l1_sectors_per_cycle = 4;              // sectors per SM; assumption: one per L1 bank (artifact -gpgpu_l1_banks 4)
  int registers_per_thread = 0;              // registers; 0: the compiled kernel's (ptxas -v)
  // The per-op fallback, for programs with no compiled kernel: each micro-op
  // becomes instructions_per_element[op] x width instructions (SACT micro-ops
  // through their TTA+ expansion) of its class (arithmetic: FP of the
  // precision; CMP and logic: other; PUSH: int; RCP: sfu; RETURN, RETURN_IF:
  // branch), a LOAD one load plus instructions_per_load - 1 int (address),
  // and each loop pass loop_branch_instructions branches.
  int fallback_registers_per_thread = 32;    // registers; assumption: a small traversal kernel
  int loop_branch_instructions = 2;          // per loop pass; assumption: ISETP + BRA back edge
  int instructions_per_load = 6;             // per node fetch; assumption: 2 FMUL, 2 F2I.FLOOR, IMAD, LDG
  std::array<int, kOpcodeCount> instructions_per_element = DefaultInstructionsPerElement();

  static std::array<int, kOpcodeCount> DefaultInstructionsPerElement();
  // Resident warps per SM for a kernel of `registers` registers per thread.
  int ResidentWarps(const GpuParams& gpu, int registers) const;
  bool IsValid(std::string* error) const;

  template <class Self, class Visitor>
  static void Fields(Self& s, Visitor& v) {
    v("schedulers_per_sm", s.schedulers_per_sm, "count", "artifact: -gpgpu_num_sched_per_core");
    v("issue_per_scheduler_per_cycle", s.issue_per_scheduler_per_cycle, "warp instructions", "artifact: -gpgpu_max_insn_issue_per_warp");
    v("precision", s.precision, "host | fp32 | fp64", "host: the kernel that ran (ray casting, ball query, MoveBot/CarriBot collision: double; rcbench collide --precision float: float)");
    v("isa", s.isa, "ptx | sass", "ptx: the artifact simulates PTX (-gpgpu_ptx_convert_to_ptxplus 0); sass: what sm_75 hardware issues");
    v("beam_leaf", s.beam_leaf, "maxlog | exact", "maxlog: programs/beam_leaf.asm, the leaf every RT backend prices; exact: the host's BeamLogDensity (exp, log)");
    v("fp32_latency_cycles", s.fp32_latency_cycles, "core cycles", "artifact: -ptx_opcode_latency_fp 4,13,4,5,39 (ADD)");
    v("fp32_initiation_cycles", s.fp32_initiation_cycles, "core cycles", "artifact: -ptx_opcode_initiation_fp 2,2,2,2,4 (ADD)");
    v("fp64_latency_cycles", s.fp64_latency_cycles, "core cycles", "artifact: -ptx_opcode_latency_dp 8,19,8,8,330 (ADD)");
    v("fp64_initiation_cycles", s.fp64_initiation_cycles, "core cycles", "artifact: -ptx_opcode_initiation_dp 4,4,4,4,130 (ADD)");
    v("int_latency_cycles", s.int_latency_cycles, "core cycles", "artifact: -ptx_opcode_latency_int 4,13,4,5,145,32 (ADD)");
    v("int_initiation_cycles", s.int_initiation_cycles, "core cycles", "artifact: -ptx_opcode_initiation_int 2,2,2,2,8,4 (ADD)");
    v("fp32_div_latency_cycles", s.fp32_div_latency_cycles, "core cycles", "artifact: -ptx_opcode_latency_fp (DIV)");
    v("fp32_div_initiation_cycles", s.fp32_div_initiation_cycles, "core cycles", "artifact: -ptx_opcode_initiation_fp (DIV)");
    v("fp64_div_latency_cycles", s.fp64_div_latency_cycles, "core cycles", "artifact: -ptx_opcode_latency_dp (DIV)");
    v("fp64_div_initiation_cycles", s.fp64_div_initiation_cycles, "core cycles", "artifact: -ptx_opcode_initiation_dp (DIV)");
    v("int_div_latency_cycles", s.int_div_latency_cycles, "core cycles", "artifact: -ptx_opcode_latency_int (DIV)");
    v("int_div_initiation_cycles", s.int_div_initiation_cycles, "core cycles", "artifact: -ptx_opcode_initiation_int (DIV)");
    v("sfu_latency_cycles", s.sfu_latency_cycles, "core cycles", "artifact: -ptx_opcode_latency_sfu 100 (rcp, sqrt, rsqrt, ex2, lg2, sin, cos)");
    v("sfu_initiation_cycles", s.sfu_initiation_cycles, "core cycles", "artifact: -ptx_opcode_initiation_sfu 8");
    v("other_latency_cycles", s.other_latency_cycles, "core cycles", "artifact: GPGPU-Sim default latency 1 (mov, setp, selp, cvt, logic, branches)");
    v("other_initiation_cycles", s.other_initiation_cycles, "core cycles", "artifact: GPGPU-Sim default initiation 1");
    v("fp64_units_per_scheduler", s.fp64_units_per_scheduler, "count (0: on the SFU unit)", "artifact: -gpgpu_pipeline_widths DP 0, no -gpgpu_num_dp_units: DP ops issue to the SFU unit");
    v("l1_sectors_per_cycle", s.l1_sectors_per_cycle, "sectors per SM", "assumption: one per L1 bank (artifact -gpgpu_l1_banks 4)");
    v("registers_per_thread", s.registers_per_thread, "registers (0: compiled)", "ptxas -v of the compiled kernel (backends/simt_instruction_table.json)");
    v("fallback_registers_per_thread", s.fallback_registers_per_thread, "registers", "assumption (programs with no compiled kernel): a small traversal kernel");
    v("loop_branch_instructions", s.loop_branch_instructions, "instructions per loop pass", "assumption (fallback): ISETP + BRA back edge");
    v("instructions_per_load", s.instructions_per_load, "instructions per node fetch", "assumption (fallback): 2 FMUL, 2 F2I.FLOOR, IMAD, LDG");
    for (int i = 0; i < kOpcodeCount; ++i) {
      const Opcode op = static_cast<Opcode>(i);
      if (InfoOf(op).sact || op == Opcode::kLoad) continue;
      v(std::string("instructions_per_element.") + MnemonicOf(op), s.instructions_per_element[i],
        "instructions", "assumption (fallback): SASS per element (see backend_params.h)");
    }
  }
};

// The named values of the SIMT choices, as written in JSON and printed.
const char* ToString(SimtPrecision p);  // "host", "fp32", "fp64"
const char* ToString(SimtIsa isa);      // "ptx", "sass"
const char* ToString(SimtBeamLeaf leaf);  // "none", "maxlog", "exact"
bool ParseChoice(const std::string& text, SimtPrecision* out);
bool ParseChoice(const std::string& text, SimtIsa* out);
bool ParseChoice(const std::string& text, SimtBeamLeaf* out);  // maxlog | exact

// The ray-tracing-unit side shared by TTA+ and RoboCore: one unit per SM.
struct RtUnitParams {
  int warp_buffer_warps = 4;            // warps; paper, artifact -gpgpu_rt_max_warps
  int intersection_unit_sets = 4;       // count; paper, artifact -gpgpu_rt_func_units
  int threads_accepted_per_cycle_per_set = 2;  // threads; artifact -gpgpu_rt_func_bw
  int sector_requests_per_cycle = 1;    // 32-byte requests per unit; artifact (REFERENCE.md section 2)
  int interconnect_hop_cycles = 1;      // core cycles; artifact -gpgpu_rt_interconnect 1,1
  int predicated_op_cycles = 1;         // core cycles; artifact rt_op_unit::cycle
  int program_config_cycles_per_micro_op = 1;  // core cycles; assumption: one micro-op written per cycle to every unit's program store
  OpUnitLatencies latencies;            // core cycles; paper micro-op table (RCP: artifact)

  template <class Self, class Visitor>
  static void Fields(Self& s, Visitor& v) {
    v("warp_buffer_warps", s.warp_buffer_warps, "warps", "paper; artifact -gpgpu_rt_max_warps");
    v("intersection_unit_sets", s.intersection_unit_sets, "count", "paper; artifact -gpgpu_rt_func_units");
    v("threads_accepted_per_cycle_per_set", s.threads_accepted_per_cycle_per_set, "threads", "artifact: -gpgpu_rt_func_bw");
    v("sector_requests_per_cycle", s.sector_requests_per_cycle, "32-byte requests", "artifact, as read (REFERENCE.md section 2)");
    v("interconnect_hop_cycles", s.interconnect_hop_cycles, "core cycles", "artifact: -gpgpu_rt_interconnect 1,1");
    v("predicated_op_cycles", s.predicated_op_cycles, "core cycles", "artifact: rt_op_unit::cycle, predicated-off threads take 1 cycle");
    v("program_config_cycles_per_micro_op", s.program_config_cycles_per_micro_op, "core cycles", "assumption: one micro-op per cycle into every unit's program store");
    auto& l = s.latencies;
    v("addsub_cycles", l.addsub_cycles, "core cycles", "paper: micro-op table");
    v("minmax_cycles", l.minmax_cycles, "core cycles", "paper");
    v("maxmin_cycles", l.maxmin_cycles, "core cycles", "paper");
    v("cmp_cycles", l.cmp_cycles, "core cycles", "paper");
    v("mul_cycles", l.mul_cycles, "core cycles", "paper");
    v("rcp_cycles", l.rcp_cycles, "core cycles", "artifact: -gpgpu_rt_intersection_latency (rcp)");
    v("rcp_initiation_cycles", l.rcp_initiation_cycles, "core cycles", "artifact: -gpgpu_rt_init_cycles (rcp)");
    v("pre_process_cycles", l.pre_process_cycles, "core cycles", "paper (PRE, XFORM)");
    v("box_normal_cycles", l.box_normal_cycles, "core cycles", "paper (BOX, DOT)");
    v("edge_edge_cycles", l.edge_edge_cycles, "core cycles", "paper (EDGE, CROSS)");
    v("logic_cycles", l.logic_cycles, "core cycles", "paper");
    v("push_cycles", l.push_cycles, "core cycles", "paper");
    v("return_cycles", l.return_cycles, "core cycles", "paper");
  }
  bool IsValid(std::string* error) const;
};

// TTA+ (plain, -p, -cr share these; the mode comes from the backend name).
struct TtaPlusParams {
  RtUnitParams unit;
  DatapathConfig Datapath(EarlyExitMode mode) const;
  template <class Self, class Visitor>
  static void Fields(Self& s, Visitor& v) { RtUnitParams::Fields(s.unit, v); }
};

// RoboCore: TTA+ plus the chained SACT units with CTRL early exit.
struct RoboCoreParams {
  RtUnitParams unit;
  int sact_pipeline_stages = 4;      // stages; paper
  double sact_latency_scale = 1.0;   // factor on the three SACT units' latencies; paper's x0.5..x2 sweep
  int ctrl_exit_cycles = 0;          // core cycles; assumption: overlaps the SACT unit's last stage
  int decode_config_cycles_per_layout = 1;  // core cycles; assumption: one layout register write per node kind

  // Always conditional return: RoboCore's RETURN and CTRL end the program.
  DatapathConfig Datapath() const;
  template <class Self, class Visitor>
  static void Fields(Self& s, Visitor& v) {
    RtUnitParams::Fields(s.unit, v);
    v("sact_pipeline_stages", s.sact_pipeline_stages, "stages", "paper: four-stage SACT pipelines");
    v("sact_latency_scale", s.sact_latency_scale, "factor", "sweep knob (paper: SACT latency x0.5 to x2); 1 = paper");
    v("ctrl_exit_cycles", s.ctrl_exit_cycles, "core cycles", "assumption: overlaps the last stage (artifact full test 194 = 14 + 6*12 + 9*12)");
    v("decode_config_cycles_per_layout", s.decode_config_cycles_per_layout, "core cycles", "assumption: one register write per node kind");
  }
  bool IsValid(std::string* error) const;
};

struct BackendParameters {
  GpuParams gpu;
  EnergyParams energy;
  SimtParams simt;
  TtaPlusParams ttaplus;
  RoboCoreParams robocore;
  bool IsValid(std::string* error) const;
};

// One row of the parameter table.
struct ParameterDescription {
  std::string key;    // "gpu.sms"
  std::string value;  // as printed
  std::string unit;
  std::string source;
};
std::vector<ParameterDescription> DescribeBackendParameters(const BackendParameters& p);
// Prints every parameter with its value, unit and source (`rcbench backends`).
void PrintBackendParameters(std::ostream& out, const BackendParameters& p);
// Defaults overridden by a JSON file (see the top of this header). Throws
// InputError (file, 0, key) for unreadable JSON, an unknown key, a wrong
// type or an invalid combination.
BackendParameters LoadBackendParameters(const std::string& path);
// The same, from JSON text; `file_name` names it in errors.
BackendParameters ParseBackendParameters(const std::string& json_text, const std::string& file_name);

}  // namespace rc
