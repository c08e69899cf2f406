#pragma once
// Parameters of the RoboCore / TTA+ intersection datapath: OP-unit
// latencies, the interconnect, the early-exit mode and the SACT pipelines.
// The backends' parameter structs (backends/backend_params.h) hold these,
// print them with units and sources, and override them from a file.
#include <cstdint>

#include "common/parameter_spec.h"
#include "robocore/micro_op.h"

namespace rc {

// Latency of one micro-op in its OP unit, cycles at the core clock (1365 MHz),
// declared once each (common/parameter_spec.h). Every non-SACT unit but the
// RCP unit takes a new micro-op every cycle.
#define RC_OP_UNIT_LATENCIES(X)                                                                     \
  X(int, addsub_cycles, 3, "core cycles", 1, 64, "paper: RoboCore micro-op table (ADDSUB)")         \
  X(int, minmax_cycles, 2, "core cycles", 1, 64, "paper (MINMAX)")                                  \
  X(int, maxmin_cycles, 2, "core cycles", 1, 64, "paper (MAXMIN)")                                  \
  X(int, cmp_cycles, 1, "core cycles", 1, 64, "paper (CMP)")                                        \
  X(int, mul_cycles, 5, "core cycles", 1, 64, "paper (MUL)")                                        \
  X(int, rcp_cycles, 4, "core cycles", 1, 64, "artifact: -gpgpu_rt_intersection_latency (rcp 4)")   \
  X(int, rcp_initiation_cycles, 3, "core cycles", 1, 64, "artifact: -gpgpu_rt_init_cycles (rcp 3)") \
  X(int, pre_process_cycles, 14, "core cycles", 1, 256, "paper (Pre-Process: PRE, XFORM)")          \
  X(int, box_normal_cycles, 12, "core cycles", 1, 256, "paper (Box-Normal: BOX, DOT)")              \
  X(int, edge_edge_cycles, 12, "core cycles", 1, 256, "paper (Edge x Edge: EDGE, CROSS)")           \
  X(int, logic_cycles, 1, "core cycles", 1, 64, "paper (LOGIC)")                                    \
  X(int, push_cycles, 1, "core cycles", 1, 64, "paper (PUSH)")                                      \
  X(int, return_cycles, 1, "core cycles", 1, 64, "paper (RETURN)")

struct OpUnitLatencies {
  RC_OP_UNIT_LATENCIES(RC_PARAMETER_MEMBER)
  template <class Self, class Visitor>
  static void Fields(Self& s, Visitor& v) {
    RC_OP_UNIT_LATENCIES(RC_PARAMETER_FIELD)
  }
};

// Latency of `unit` (kFetch has none here: the caches decide it).
int LatencyOf(OpUnit unit, const OpUnitLatencies& latencies);

enum class DatapathKind : std::uint8_t {
  kTtaPlus,   // OP units only; SACT micro-ops run as their TTA+ expansion
  kRoboCore,  // + chained SACT units with CTRL early exit
};

enum class EarlyExitMode : std::uint8_t {
  kNone,               // plain TTA+: RETURN_IF markers are dropped, every micro-op runs
  kPredication,        // TTA+-p: after a fired RETURN_IF, micro-ops travel predicated off
  kConditionalReturn,  // TTA+-cr and RoboCore: a fired RETURN_IF ends the program
};

const char* ToString(EarlyExitMode mode);

struct DatapathConfig {
  DatapathKind kind = DatapathKind::kTtaPlus;
  EarlyExitMode exit_mode = EarlyExitMode::kNone;
  OpUnitLatencies latencies;
  // Paid whenever consecutive micro-ops of a thread run on different units
  // (a micro-op that stays on its unit skips the interconnect): artifact,
  // -gpgpu_rt_interconnect 1,1 and rt_func_unit::cycle.
  int interconnect_hop_cycles = 1;
  // Cycles a predicated-off micro-op occupies its unit: artifact,
  // rt_op_unit::cycle ("Predicated off threads take 1 cycle").
  int predicated_op_cycles = 1;
  // RoboCore only: cycles before each SACT unit takes its next packet.
  int pre_process_initiation_cycles = 4;
  int box_normal_initiation_cycles = 3;
  int edge_edge_initiation_cycles = 3;
  // RoboCore only. Cycles CTRL adds when its check after a SACT unit fires
  // ("separating axis: exit"); a check that does not fire adds none.
  // Assumption: 0, the check overlaps the unit's last stage (the artifact's
  // 194-cycle full test is exactly 14 + 6*12 + 9*12); the artifact preset
  // charges 1, its RETURN op.
  int ctrl_exit_cycles = 0;
};

}  // namespace rc
