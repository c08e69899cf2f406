#pragma once
// The micro-op ISA of the RoboCore / TTA+ intersection datapath (RoboGPU
// paper, "RoboCore micro-ops" table; REFERENCE.md section 1).
//
// A micro-op names an operation and the OP unit that runs it. Latencies are
// not here: they are parameters (robocore/datapath_params.h), so that a
// sensitivity sweep can change them without touching the ISA.
//
// Vector micro-ops (ADD, SUB, MIN, MAX, CMP, MUL, DOT, CROSS, XFORM, logic)
// carry a width of 1 to 3 elements. On the RoboCore/TTA+ datapath a vec3 unit
// runs any width in one pass, so the width changes nothing there; it matters
// to the SIMT backend (one scalar instruction per element) and to energy
// (arithmetic per element). The paper defines ADD/SUB/CMP on FP32 vec3, so 3
// is the default; the 2D ray-cast programs write `.2`.
//
// The SACT micro-ops PRE, BOX and EDGE run natively on RoboCore's chained
// SACT units. TTA+ has no SACT units and runs each of them as the micro-op
// sequence of the paper's "SACT on TTA+" table (see TtaPlusExpansion).
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace rc {

enum class Opcode : std::uint8_t {
  kAdd,
  kSub,
  kMin,  // MIN(a, b): the MINMAX unit with its MAX input tied off
  kMax,  // MAX(a, b): the MAXMIN unit with its MIN input tied off
  kCmp,
  kMul,
  kRcp,  // reciprocal; not in the paper's table, in the artifact (RT_RCP)
  kDot,
  kCross,
  kXform,  // ray/box transform by a 3x3 rotation (TTA+'s R-XFORM)
  kPre,    // SACT pre-process: relative frame of an OBB/AABB pair
  kBox,    // SACT box-normal axis test (axis 0..5)
  kEdge,   // SACT edge x edge axis test (axis 0..8)
  kAnd,
  kOr,
  kXor,
  kNot,
  kPush,      // push to the warp buffer / traversal stack; counts nodes visited
  kReturn,    // unconditional end of the program
  kReturnIf,  // conditional return: the early-exit marker (see EarlyExitMode)
  kLoad,      // node fetch through the memory hierarchy (not an OP unit)
};
inline constexpr int kOpcodeCount = 21;

enum class OpUnit : std::uint8_t {
  kAddSub,
  kMinMax,
  kMaxMin,
  kCmp,
  kMul,
  kRcp,
  kPreProcess,  // TTA+: ray transform; RoboCore: + SACT pre-process
  kBoxNormal,   // TTA+: DOT; RoboCore: + SACT box-normal axes
  kEdgeEdge,    // TTA+: CROSS; RoboCore: + SACT edge x edge axes
  kLogic,
  kPush,
  kReturn,
  kFetch,  // the node-fetch path to L1; its latency comes from the caches
};
inline constexpr int kOpUnitCount = 13;

// Arithmetic one execution of a micro-op performs, used for energy: FP32
// adds (add, subtract, compare, min/max), FP32 multiplies, reciprocals and
// 32-bit integer/logic operations.
struct ArithmeticContent {
  int fp_adds = 0;
  int fp_muls = 0;
  int reciprocals = 0;
  int int_ops = 0;
  ArithmeticContent& operator+=(const ArithmeticContent& o) {
    fp_adds += o.fp_adds;
    fp_muls += o.fp_muls;
    reciprocals += o.reciprocals;
    int_ops += o.int_ops;
    return *this;
  }
};

struct OpcodeInfo {
  Opcode opcode;
  const char* mnemonic;
  OpUnit unit;
  int operand_count;          // operands written in assembly (destination first)
  const char* operand_names;  // for error messages, e.g. "dst, a, b"
  bool has_width;             // accepts a .1/.2/.3 suffix
  int min_width;
  int default_width;
  bool sact;     // PRE, BOX, EDGE
  int max_axis;  // BOX/EDGE: highest axis immediate; else -1
};

const OpcodeInfo& InfoOf(Opcode op);
const char* MnemonicOf(Opcode op);
const char* OpUnitName(OpUnit unit);
// Case-insensitive; nullopt for an unknown mnemonic.
std::optional<Opcode> ParseOpcode(std::string_view mnemonic);

// One micro-op of a TTA+ expansion.
struct ExpandedOp {
  Opcode opcode;
  int width;
};
// The TTA+ micro-ops that stand for one SACT micro-op (paper, "SACT on
// TTA+"): PRE = 4 VEC3-SUB + 1 R-XFORM; BOX = 2 DOT + 1 VEC3-SUB +
// 1 VEC3-CMP; EDGE = 1 CROSS + 1 VEC3-CMP. Empty for a non-SACT opcode.
const std::vector<ExpandedOp>& TtaPlusExpansion(Opcode op);

// Arithmetic of one execution at the given width. SACT micro-ops count the
// arithmetic of their TTA+ expansion: RoboCore's units do the same math.
ArithmeticContent ContentOf(Opcode op, int width);

}  // namespace rc
