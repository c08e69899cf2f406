#include "robocore/micro_op.h"

#include <array>
#include <cctype>
#include <stdexcept>
#include <string>

namespace rc {
namespace {

// clang-format off
constexpr std::array<OpcodeInfo, kOpcodeCount> kOpcodes = {{
  // opcode             mnemonic     unit                  n  operands          width    min def  sact   axis
  {Opcode::kAdd,      "ADD",       OpUnit::kAddSub,      3, "dst, a, b",       true,    1,  3,  false, -1},
  {Opcode::kSub,      "SUB",       OpUnit::kAddSub,      3, "dst, a, b",       true,    1,  3,  false, -1},
  {Opcode::kMin,      "MIN",       OpUnit::kMinMax,      3, "dst, a, b",       true,    1,  3,  false, -1},
  {Opcode::kMax,      "MAX",       OpUnit::kMaxMin,      3, "dst, a, b",       true,    1,  3,  false, -1},
  {Opcode::kCmp,      "CMP",       OpUnit::kCmp,         3, "dst, a, b",       true,    1,  3,  false, -1},
  {Opcode::kMul,      "MUL",       OpUnit::kMul,         3, "dst, a, b",       true,    1,  1,  false, -1},
  {Opcode::kRcp,      "RCP",       OpUnit::kRcp,         2, "dst, a",          true,    1,  1,  false, -1},
  {Opcode::kDot,      "DOT",       OpUnit::kBoxNormal,   3, "dst, a, b",       true,    1,  3,  false, -1},
  {Opcode::kCross,    "CROSS",     OpUnit::kEdgeEdge,    3, "dst, a, b",       true,    2,  3,  false, -1},
  {Opcode::kXform,    "XFORM",     OpUnit::kPreProcess,  3, "dst, rotation, v", true,   1,  3,  false, -1},
  {Opcode::kPre,      "PRE",       OpUnit::kPreProcess,  3, "dst, obb, box",   false,   3,  3,  true,  -1},
  {Opcode::kBox,      "BOX",       OpUnit::kBoxNormal,   3, "separated, frame, axis", false, 3, 3, true, 5},
  {Opcode::kEdge,     "EDGE",      OpUnit::kEdgeEdge,    3, "separated, frame, axis", false, 3, 3, true, 8},
  {Opcode::kAnd,      "AND",       OpUnit::kLogic,       3, "dst, a, b",       true,    1,  1,  false, -1},
  {Opcode::kOr,       "OR",        OpUnit::kLogic,       3, "dst, a, b",       true,    1,  1,  false, -1},
  {Opcode::kXor,      "XOR",       OpUnit::kLogic,       3, "dst, a, b",       true,    1,  1,  false, -1},
  {Opcode::kNot,      "NOT",       OpUnit::kLogic,       2, "dst, a",          true,    1,  1,  false, -1},
  {Opcode::kPush,     "PUSH",      OpUnit::kPush,        1, "value",           false,   1,  1,  false, -1},
  {Opcode::kReturn,   "RETURN",    OpUnit::kReturn,      0, "",                false,   1,  1,  false, -1},
  {Opcode::kReturnIf, "RETURN_IF", OpUnit::kReturn,      1, "predicate",       false,   1,  1,  false, -1},
  {Opcode::kLoad,     "LOAD",      OpUnit::kFetch,       2, "dst, address",    false,   1,  1,  false, -1},
}};
// clang-format on

constexpr std::array<const char*, kOpUnitCount> kUnitNames = {
    "ADDSUB",     "MINMAX",    "MAXMIN", "CMP",  "MUL",    "RCP",  "PRE_PROCESS",
    "BOX_NORMAL", "EDGE_EDGE", "LOGIC",  "PUSH", "RETURN", "FETCH"};

}  // namespace

const OpcodeInfo& InfoOf(Opcode op) {
  const OpcodeInfo& info = kOpcodes[static_cast<int>(op)];
  if (info.opcode != op) throw std::logic_error("micro-op table out of order");
  return info;
}

const char* MnemonicOf(Opcode op) { return InfoOf(op).mnemonic; }

const char* OpUnitName(OpUnit unit) { return kUnitNames[static_cast<int>(unit)]; }

std::optional<Opcode> ParseOpcode(std::string_view mnemonic) {
  std::string upper(mnemonic);
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const OpcodeInfo& info : kOpcodes)
    if (upper == info.mnemonic) return info.opcode;
  return std::nullopt;
}

const std::vector<ExpandedOp>& TtaPlusExpansion(Opcode op) {
  // Paper, "SACT on TTA+ (micro-ops per test)".
  static const std::vector<ExpandedOp> kPre = {
      {Opcode::kSub, 3}, {Opcode::kSub, 3}, {Opcode::kSub, 3}, {Opcode::kSub, 3}, {Opcode::kXform, 3}};
  static const std::vector<ExpandedOp> kBox = {
      {Opcode::kDot, 3}, {Opcode::kDot, 3}, {Opcode::kSub, 3}, {Opcode::kCmp, 3}};
  static const std::vector<ExpandedOp> kEdge = {{Opcode::kCross, 3}, {Opcode::kCmp, 3}};
  static const std::vector<ExpandedOp> kNone;
  switch (op) {
    case Opcode::kPre: return kPre;
    case Opcode::kBox: return kBox;
    case Opcode::kEdge: return kEdge;
    default: return kNone;
  }
}

ArithmeticContent ContentOf(Opcode op, int w) {
  ArithmeticContent c;
  switch (op) {
    case Opcode::kAdd:
    case Opcode::kSub:
    case Opcode::kMin:
    case Opcode::kMax:
    case Opcode::kCmp:
      c.fp_adds = w;  // an FP compare or min/max is an adder's worth of logic
      break;
    case Opcode::kMul: c.fp_muls = w; break;
    case Opcode::kRcp: c.reciprocals = w; break;
    case Opcode::kDot:
      c.fp_muls = w;
      c.fp_adds = w - 1;
      break;
    case Opcode::kCross:
      // 3D: three 2x2 determinants; 2D: the scalar a.x*b.y - a.y*b.x.
      c.fp_muls = w == 3 ? 6 : 2;
      c.fp_adds = w == 3 ? 3 : 1;
      break;
    case Opcode::kXform:  // w x w matrix times a w-vector
      c.fp_muls = w * w;
      c.fp_adds = w * (w - 1);
      break;
    case Opcode::kPre:
    case Opcode::kBox:
    case Opcode::kEdge:
      for (const ExpandedOp& e : TtaPlusExpansion(op)) c += ContentOf(e.opcode, e.width);
      break;
    case Opcode::kAnd:
    case Opcode::kOr:
    case Opcode::kXor:
    case Opcode::kNot: c.int_ops = w; break;
    case Opcode::kPush:
    case Opcode::kReturn:
    case Opcode::kReturnIf: c.int_ops = 1; break;
    case Opcode::kLoad: break;  // priced as a memory access
  }
  return c;
}

}  // namespace rc
