#pragma once
// One parameter struct per modelled backend, plus the shared GPU and energy
// structs (gpu_params.h), gathered in BackendParameters.
//
// Each parameter is declared once (common/parameter_spec.h): type, name,
// default, unit, valid range, source. Its Fields() visitor serves
// PrintBackendParameters, LoadBackendParameters' JSON override file, the
// range checks (IsValid) and the sensitivity sweep. A JSON file names the
// struct, then the field, nested or dotted:
//   {"gpu": {"sms": 16, "l1_bytes": 131072},
//    "robocore": {"sact_latency_scale": 2.0},
//    "simt": {"precision": "fp32", "instructions_per_element": {"DOT": 2}}}
// A choice (simt.precision, simt.isa, simt.beam_leaf) is a JSON string.
// Unknown keys, wrong types and values out of range are InputErrors naming
// the file and the key.
#include <array>
#include <iosfwd>
#include <string>
#include <vector>

#include "backends/gpu_params.h"
#include "backends/simt_instruction_table.h"
#include "common/parameter_spec.h"
#include "robocore/datapath_params.h"
#include "robocore/micro_op.h"

namespace rc {

// The CUDA-core (SIMT) baseline. Instruction counts come from the compiled
// CUDA kernels (simt_instruction_table.h); the timing of each instruction
// class is the artifact's (gpgpusim.config, code/workloads/
// collision_detection: -ptx_opcode_latency_* and -ptx_opcode_initiation_*,
// "ADD,MAX,MUL,MAD,DIV"; REFERENCE.md section 2). A program with no compiled
// kernel (a ConfigRoboCore program) is counted by the per-op fallback: each
// micro-op becomes instructions_per_element[op] x width instructions (SACT
// micro-ops through their TTA+ expansion) of its class (arithmetic: FP of
// the precision; CMP and logic: other; PUSH: int; RCP: sfu; RETURN,
// RETURN_IF: branch), a LOAD one load plus instructions_per_load - 1 int
// (address), and each loop pass loop_branch_instructions branches.
#define RC_SIMT_PARAMETERS(X)                                                                                          \
  X(int, schedulers_per_sm, 4, "count", 1, 16, "artifact: -gpgpu_num_sched_per_core 4")                                \
  X(int, issue_per_scheduler_per_cycle, 1, "warp instructions", 1, 4, "artifact: -gpgpu_max_insn_issue_per_warp 1")    \
  X(SimtPrecision, precision, SimtPrecision::kHost, "host | fp32 | fp64", 0, 0,                                        \
    "host: the kernel that ran (ray casting, ball query, MoveBot/CarriBot collision: double; rcbench collide "         \
    "--precision float: float)")                                                                                       \
  X(SimtIsa, isa, SimtIsa::kPtx, "ptx | sass", 0, 0,                                                                   \
    "ptx: the artifact simulates PTX (-gpgpu_ptx_convert_to_ptxplus 0); sass: what sm_75 hardware issues")             \
  X(SimtBeamLeaf, beam_leaf, SimtBeamLeaf::kMaxLog, "maxlog | exact", 0, 0,                                            \
    "maxlog: programs/beam_leaf.asm, the leaf every RT backend prices; exact: the host's BeamLogDensity (exp, log)")   \
  X(int, fp32_latency_cycles, 4, "core cycles", 0, 1000, "artifact: -ptx_opcode_latency_fp 4,13,4,5,39 (ADD)")         \
  X(int, fp32_initiation_cycles, 2, "core cycles", 1, 1000, "artifact: -ptx_opcode_initiation_fp 2,2,2,2,4 (ADD)")     \
  X(int, fp64_latency_cycles, 8, "core cycles", 0, 1000, "artifact: -ptx_opcode_latency_dp 8,19,8,8,330 (ADD)")        \
  X(int, fp64_initiation_cycles, 4, "core cycles", 1, 1000, "artifact: -ptx_opcode_initiation_dp 4,4,4,4,130 (ADD)")   \
  X(int, int_latency_cycles, 4, "core cycles", 0, 1000, "artifact: -ptx_opcode_latency_int 4,13,4,5,145,32 (ADD)")     \
  X(int, int_initiation_cycles, 2, "core cycles", 1, 1000, "artifact: -ptx_opcode_initiation_int 2,2,2,2,8,4 (ADD)")   \
  X(int, fp32_div_latency_cycles, 39, "core cycles", 0, 5000, "artifact: -ptx_opcode_latency_fp (DIV 39)")             \
  X(int, fp32_div_initiation_cycles, 4, "core cycles", 1, 5000, "artifact: -ptx_opcode_initiation_fp (DIV 4)")         \
  X(int, fp64_div_latency_cycles, 330, "core cycles", 0, 5000, "artifact: -ptx_opcode_latency_dp (DIV 330)")           \
  X(int, fp64_div_initiation_cycles, 130, "core cycles", 1, 5000, "artifact: -ptx_opcode_initiation_dp (DIV 130)")     \
  X(int, int_div_latency_cycles, 145, "core cycles", 0, 5000, "artifact: -ptx_opcode_latency_int (DIV 145)")           \
  X(int, int_div_initiation_cycles, 8, "core cycles", 1, 5000, "artifact: -ptx_opcode_initiation_int (DIV 8)")         \
  X(int, sfu_latency_cycles, 100, "core cycles", 0, 5000,                                                              \
    "artifact: -ptx_opcode_latency_sfu 100 (rcp, sqrt, rsqrt, ex2, lg2, sin, cos)")                                    \
  X(int, sfu_initiation_cycles, 8, "core cycles", 1, 5000, "artifact: -ptx_opcode_initiation_sfu 8")                   \
  X(int, other_latency_cycles, 1, "core cycles", 0, 100,                                                               \
    "artifact: GPGPU-Sim's default latency 1 (mov, setp, selp, cvt, logic, branches)")                                 \
  X(int, other_initiation_cycles, 1, "core cycles", 1, 100, "artifact: GPGPU-Sim's default initiation 1")              \
  X(int, fp64_units_per_scheduler, 0, "count (0: on the SFU unit)", 0, 16,                                             \
    "artifact: -gpgpu_pipeline_widths DP 0, no -gpgpu_num_dp_units: DP ops issue to the SFU unit")                     \
  X(int, l1_sectors_per_cycle, 4, "sectors per SM", 1, 64, "assumption: one per L1 bank (artifact -gpgpu_l1_banks 4)") \
  X(int, registers_per_thread, 0, "registers (0: compiled)", 0, 255,                                                   \
    "ptxas -v of the compiled kernel (backends/simt_instruction_table.json)")                                          \
  X(int, fallback_registers_per_thread, 32, "registers", 1, 255,                                                       \
    "assumption (programs with no compiled kernel): a small traversal kernel")                                         \
  X(int, loop_branch_instructions, 2, "instructions per loop pass", 0, 64,                                             \
    "assumption (fallback): ISETP + BRA back edge")                                                                    \
  X(int, instructions_per_load, 6, "instructions per node fetch", 1, 64,                                               \
    "assumption (fallback): 2 FMUL, 2 F2I.FLOOR, IMAD, LDG")

struct SimtParams {
  RC_SIMT_PARAMETERS(RC_PARAMETER_MEMBER)
  // The fallback's instructions per vector element of each micro-op, by
  // opcode (SACT micro-ops through their TTA+ expansion, LOAD through
  // instructions_per_load).
  std::array<int, kOpcodeCount> instructions_per_element = DefaultInstructionsPerElement();

  static std::array<int, kOpcodeCount> DefaultInstructionsPerElement();
  // Resident warps per SM for a kernel of `registers` registers per thread.
  int ResidentWarps(const GpuParams& gpu, int registers) const;
  bool IsValid(std::string* error) const;

  template <class Self, class Visitor>
  static void Fields(Self& s, Visitor& v) {
    RC_SIMT_PARAMETERS(RC_PARAMETER_FIELD)
    for (int i = 0; i < kOpcodeCount; ++i) {
      const Opcode op = static_cast<Opcode>(i);
      if (InfoOf(op).sact || op == Opcode::kLoad) continue;
      v(std::string("instructions_per_element.") + MnemonicOf(op), s.instructions_per_element[i],
        ParameterSpec{"instructions", 0, 64, "assumption (fallback): SASS per element (see backend_params.h)"});
    }
  }
};

// The named values of the SIMT choices, as written in JSON and printed.
const char* ToString(SimtPrecision p);    // "host", "fp32", "fp64"
const char* ToString(SimtIsa isa);        // "ptx", "sass"
const char* ToString(SimtBeamLeaf leaf);  // "none", "maxlog", "exact"
bool ParseChoice(const std::string& text, SimtPrecision* out);
bool ParseChoice(const std::string& text, SimtIsa* out);
bool ParseChoice(const std::string& text, SimtBeamLeaf* out);  // maxlog | exact

// The ray-tracing-unit side shared by TTA+ and RoboCore: one unit per SM.
#define RC_RT_UNIT_PARAMETERS(X)                                                                                   \
  X(int, warp_buffer_warps, 4, "warps", 1, 64, "paper; artifact -gpgpu_rt_max_warps 4")                            \
  X(int, intersection_unit_sets, 4, "count", 1, 64, "paper; artifact -gpgpu_rt_func_units 4")                      \
  X(int, op_units_per_kind_per_set, 1, "count", 1, 32,                                                             \
    "artifact: -gpgpu_rt_n_func_units 32,1,1,...: one OP unit of each kind (32 decode) per intersection unit set") \
  X(int, threads_accepted_per_cycle_per_set, 2, "threads", 1, 32, "artifact: -gpgpu_rt_func_bw 2")                 \
  X(int, sector_requests_per_cycle, 1, "32-byte requests", 1, 32, "artifact, as read (REFERENCE.md section 2)")    \
  X(int, interconnect_hop_cycles, 1, "core cycles", 0, 64, "artifact: -gpgpu_rt_interconnect 1,1")                 \
  X(int, predicated_op_cycles, 1, "core cycles", 1, 64,                                                            \
    "artifact: rt_op_unit::cycle, predicated-off threads take 1 cycle")                                            \
  X(int, program_config_cycles_per_micro_op, 1, "core cycles", 0, 64,                                              \
    "assumption: one micro-op per cycle into every unit's program store, at every launch")

struct RtUnitParams {
  RC_RT_UNIT_PARAMETERS(RC_PARAMETER_MEMBER)
  OpUnitLatencies latencies;  // robocore/datapath_params.h

  template <class Self, class Visitor>
  static void Fields(Self& s, Visitor& v) {
    RC_RT_UNIT_PARAMETERS(RC_PARAMETER_FIELD)
    OpUnitLatencies::Fields(s.latencies, v);
  }
};

// TTA+ (plain, -p, -cr share these; the mode comes from the backend name).
struct TtaPlusParams {
  RtUnitParams unit;
  DatapathConfig Datapath(EarlyExitMode mode) const;
  template <class Self, class Visitor>
  static void Fields(Self& s, Visitor& v) {
    RtUnitParams::Fields(s.unit, v);
  }
};

// RoboCore: TTA+ plus the chained SACT units with CTRL early exit. The paper
// describes the SACT units as four-stage pipelines, so a unit takes a new
// packet every ceil(latency / 4) cycles: 4 for Pre-Process (14), 3 for
// Box-Normal and Edge x Edge (12). The artifact's clusters take one every
// cycle (-gpgpu_rt_init_cycles 1 for clusterA-C).
#define RC_ROBOCORE_PARAMETERS(X)                                                      \
  X(int, pre_process_initiation_cycles, 4, "core cycles", 1, 64,                       \
    "paper: four-stage pipelines, ceil(14 / 4); artifact: 1")                          \
  X(int, box_normal_initiation_cycles, 3, "core cycles", 1, 64,                        \
    "paper: four-stage pipelines, ceil(12 / 4); artifact: 1")                          \
  X(int, edge_edge_initiation_cycles, 3, "core cycles", 1, 64,                         \
    "paper: four-stage pipelines, ceil(12 / 4); artifact: 1")                          \
  X(double, sact_latency_scale, 1.0, "factor", 0.1, 10,                                \
    "sweep knob on the three SACT units' latencies (paper: x0.5 to x2); 1 = paper")    \
  X(int, ctrl_exit_cycles, 0, "core cycles", 0, 64,                                    \
    "assumption: overlaps the last stage (artifact full test 194 = 14 + 6*12 + 9*12)") \
  X(int, decode_config_cycles_per_layout, 1, "core cycles", 0, 1000,                   \
    "assumption: one layout register write per node kind, at every launch")

struct RoboCoreParams {
  RtUnitParams unit;
  RC_ROBOCORE_PARAMETERS(RC_PARAMETER_MEMBER)

  // Always conditional return: RoboCore's RETURN and CTRL end the program.
  DatapathConfig Datapath() const;
  template <class Self, class Visitor>
  static void Fields(Self& s, Visitor& v) {
    RtUnitParams::Fields(s.unit, v);
    RC_ROBOCORE_PARAMETERS(RC_PARAMETER_FIELD)
  }
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
  std::string range;  // "[min, max]"; empty for a choice
  std::string source;
};
std::vector<ParameterDescription> DescribeBackendParameters(const BackendParameters& p);
// Prints every parameter with its value, unit, range and source (`rcbench
// backends`). A value that differs from the default is sourced to
// `given_by` (the --backend-params file or preset), with the default and its
// source after it, so no printed source claims a value it did not give.
void PrintBackendParameters(std::ostream& out, const BackendParameters& p, const std::string& given_by = "");
// One parameter as a sensitivity sweep sees it: its key, its declaration,
// its value, and the values the sweep tries, as JSON text: a number is
// halved and doubled (integers rounded; clipped to its range; dropped when
// equal to the value), a choice takes each of its other values.
struct ParameterVariants {
  std::string key;  // "robocore.warp_buffer_warps"
  ParameterSpec spec;
  std::string value;
  std::vector<std::string> alternatives;
};
std::vector<ParameterVariants> SweepVariants(const BackendParameters& p);
// `p` with one parameter set to `json_value` (JSON text, as in the file),
// checked as the file loader checks: throws InputError naming `key` for an
// unknown key, a wrong type or an invalid result.
BackendParameters WithParameter(const BackendParameters& p, const std::string& key, const std::string& json_value);
// The value of one parameter as JSON text (for comparing presets).
std::string ParameterValue(const BackendParameters& p, const std::string& key);

// Defaults overridden by a JSON file (see the top of this header). Throws
// InputError (file, 0, key) for unreadable JSON, an unknown key, a wrong
// type or an invalid combination.
BackendParameters LoadBackendParameters(const std::string& path);
// The same, from JSON text; `file_name` names it in errors.
BackendParameters ParseBackendParameters(const std::string& json_text, const std::string& file_name);

}  // namespace rc
