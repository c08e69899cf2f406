#pragma once
// A micro-op program for the RoboCore / TTA+ datapath and its assembly text.
//
// A program describes what one query (one thread) does, in three sections:
//   prologue:  once per query, before the traversal (ray setup);
//   loop:      once per node the query visits (one LOAD = one node fetch);
//   epilogue:  once per query, after the traversal (the leaf, e.g. the
//              beam model).
// The functional answer always comes from the C++ kernels (robocore/
// ray_cast.h); a program is the cost description of the same work. Its
// operands document the dataflow and are syntax-checked, and one of them is
// used by the timing model: a RETURN_IF whose predicate is the result of the
// SACT micro-op just before it is folded into RoboCore's CTRL block.
//
// Assembly format (files under robocore/programs/):
//   # comment                      anything after '#' is ignored
//   loop:                          a section label: prologue, loop or epilogue,
//                                  each at most once and in that order
//   SUB.2  d, target, origin       MNEMONIC[.width] operand, operand, ...
//   RETURN_IF hit                  conditional return (the early-exit marker)
//   BOX    sep, frame, 3           SACT axis micro-ops take an axis immediate
// Mnemonics are case-insensitive. Operands are identifiers
// ([A-Za-z_][A-Za-z0-9_]*, optionally with a component .x, .y or .z) or
// integers. The width suffix (.1, .2, .3) is
// allowed on vector micro-ops only. A loop, if present, must start with
// its one LOAD (a pass begins with its node fetch); no other section may
// hold a LOAD. A leaf program (the beam
// model) has only an epilogue.
//
// RETURN_IF is numbered 0, 1, ... within its section. A kernel record says,
// for every node, which RETURN_IF fired in that node's loop pass (if any);
// the early-exit mode of a backend decides what that costs:
//   none (plain TTA+)       every micro-op runs; the return only selects the result
//   predication (TTA+-p)    later micro-ops still travel and take one slot each
//   conditional return      the program ends at the RETURN_IF (TTA+-cr, RoboCore)
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "robocore/micro_op.h"

namespace rc {

enum class ProgramSection : std::uint8_t { kPrologue = 0, kLoop = 1, kEpilogue = 2 };
inline constexpr int kSectionCount = 3;
const char* SectionName(ProgramSection s);

struct MicroOp {
  Opcode opcode = Opcode::kAdd;
  std::uint8_t width = 1;
  std::vector<std::string> operands;  // as written, destination first
  int axis = -1;                      // BOX/EDGE axis immediate, else -1
  long line = 0;                      // 1-based source line
};

class MicroProgram {
 public:
  MicroProgram() = default;
  MicroProgram(std::string name, std::array<std::vector<MicroOp>, kSectionCount> sections);

  const std::string& name() const { return name_; }
  const std::vector<MicroOp>& section(ProgramSection s) const { return sections_[static_cast<int>(s)]; }
  int ReturnIfCount(ProgramSection s) const;
  bool has_loop() const { return !section(ProgramSection::kLoop).empty(); }
  std::size_t MicroOpCount() const;  // all sections

 private:
  std::string name_;
  std::array<std::vector<MicroOp>, kSectionCount> sections_;
};

// Parses assembly text. `file_name` names the source in errors. Throws
// InputError (file, line, field) for: an unknown mnemonic ("opcode"), a
// missing or extra operand ("operand N"), a bad operand token, a bad width
// ("width"), an axis out of range ("axis"), an unknown, repeated or
// out-of-order label ("label"), a micro-op before any label, and a loop
// without exactly one LOAD.
MicroProgram ParseMicroProgram(std::string_view text, const std::string& file_name);

// Reads and parses a program file; the program is named after the file's
// stem. Throws InputError if the file cannot be read.
MicroProgram LoadMicroProgram(const std::string& path);

}  // namespace rc
