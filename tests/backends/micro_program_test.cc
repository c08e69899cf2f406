// The micro-op assembly parser: accepted syntax, every error with its file,
// line and field, and the shipped programs (parse, embedded copy equals the
// file on disk, the counts the docs state).
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "common/input_error.h"
#include "robocore/micro_program.h"
#include "robocore/shipped_programs.h"
#include "support/input_error_expectations.h"

namespace rc {
namespace {

InputError ParseError(const std::string& text) {
  return test::InputErrorFrom([&] { ParseMicroProgram(text, "prog.asm"); }, text);
}

TEST(MicroProgramParser, ParsesSectionsWidthsAxesAndComments) {
  const MicroProgram p = ParseMicroProgram(
      "# header\n"
      "prologue:\n"
      "  rcp.2 inv_d, d   # lower case works\n"
      "loop:\n"
      "  LOAD cell, p\n"
      "  SUB.2 rel, p.x, o\n"
      "  BOX sep, frame, 5\n"
      "  RETURN_IF sep\n"
      "epilogue:\n"
      "  RETURN\n",
      "dir/my_prog.asm");
  EXPECT_EQ(p.name(), "my_prog");
  ASSERT_EQ(p.section(ProgramSection::kPrologue).size(), 1u);
  EXPECT_EQ(p.section(ProgramSection::kPrologue)[0].opcode, Opcode::kRcp);
  EXPECT_EQ(p.section(ProgramSection::kPrologue)[0].width, 2);
  const auto& loop = p.section(ProgramSection::kLoop);
  ASSERT_EQ(loop.size(), 4u);
  EXPECT_EQ(loop[1].width, 2);
  EXPECT_EQ(loop[1].operands[1], "p.x");
  EXPECT_EQ(loop[1].line, 6);
  EXPECT_EQ(loop[2].axis, 5);
  EXPECT_EQ(InfoOf(Opcode::kSub).default_width, 3);  // the paper's vec3
  EXPECT_EQ(p.ReturnIfCount(ProgramSection::kLoop), 1);
  EXPECT_EQ(p.MicroOpCount(), 6u);
}

TEST(MicroProgramParser, BadOpcodeNamesLineAndField) {
  const InputError e = ParseError("loop:\n  LOAD c, p\n  FROB a, b, c\n");
  EXPECT_EQ(e.file(), "prog.asm");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.field(), "opcode");
  EXPECT_NE(std::string(e.what()).find("FROB"), std::string::npos);
}

TEST(MicroProgramParser, MissingOperand) {
  const InputError e = ParseError("loop:\n  LOAD c, p\n  SUB.2 d, a\n");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.field(), "operand 3");
  EXPECT_NE(std::string(e.what()).find("missing operand"), std::string::npos);
  const InputError empty = ParseError("loop:\n  LOAD c, p\n  ADD d, , b\n");
  EXPECT_EQ(empty.field(), "operand 2");
}

TEST(MicroProgramParser, ExtraOperandAndBadToken) {
  EXPECT_EQ(ParseError("loop:\n  LOAD c, p\n  NOT a, b, c\n").field(), "operand 3");
  EXPECT_EQ(ParseError("loop:\n  LOAD c, p\n  ADD a, b, c+1\n").field(), "operand 3");
}

TEST(MicroProgramParser, UnknownRepeatedAndOutOfOrderLabels) {
  const InputError unknown = ParseError("prologue:\n  RCP a, b\nbody:\n");
  EXPECT_EQ(unknown.line(), 3);
  EXPECT_EQ(unknown.field(), "label");
  EXPECT_NE(std::string(unknown.what()).find("body"), std::string::npos);
  EXPECT_EQ(ParseError("loop:\n  LOAD c, p\nloop:\n").field(), "label");
  EXPECT_EQ(ParseError("epilogue:\n  RETURN\nloop:\n  LOAD c, p\n").line(), 3);
}

TEST(MicroProgramParser, WidthAxisAndLoadRules) {
  EXPECT_EQ(ParseError("loop:\n  LOAD c, p\n  ADD.4 a, b, c\n").field(), "width");
  EXPECT_EQ(ParseError("loop:\n  LOAD c, p\n  PUSH.2 a\n").field(), "width");
  EXPECT_EQ(ParseError("loop:\n  LOAD c, p\n  CROSS.1 a, b, c\n").field(), "width");
  EXPECT_EQ(ParseError("loop:\n  LOAD c, p\n  BOX s, f, 6\n").field(), "axis");
  EXPECT_EQ(ParseError("loop:\n  LOAD c, p\n  EDGE s, f, x\n").field(), "axis");
  // An axis too long for a long (a tests/fuzz finding: std::stol threw
  // std::out_of_range past the parser).
  EXPECT_EQ(ParseError("loop:\n  LOAD c, p\n  BOX s, f, 99999999999999999999\n").field(), "axis");
  EXPECT_EQ(ParseError("  ADD a, b, c\n").field(), "opcode");  // before any label
  EXPECT_EQ(ParseError("prologue:\n  LOAD c, p\nloop:\n  LOAD c, p\n").line(), 2);
  EXPECT_EQ(ParseError("loop:\n  ADD a, b, c\n").field(), "loop");                 // no LOAD
  EXPECT_EQ(ParseError("loop:\n  ADD a, b, c\n  LOAD c, p\n").field(), "opcode");  // not first
  EXPECT_EQ(ParseError("loop:\n  LOAD c, p\n  LOAD d, q\n").field(), "loop");
}

TEST(MicroProgramParser, LoadFileErrorsNameTheFile) {
  EXPECT_EQ(test::InputErrorFrom([] { LoadMicroProgram("/nonexistent/x.asm"); }).file(), "/nonexistent/x.asm");
}

TEST(ShippedPrograms, EveryEmbeddedProgramEqualsItsFileAndParses) {
  ASSERT_FALSE(EmbeddedPrograms().empty());
  for (const EmbeddedProgram& p : EmbeddedPrograms()) {
    std::ifstream in(ShippedProgramDirectory() + "/" + p.file_name);
    ASSERT_TRUE(in) << p.file_name;
    std::ostringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), p.text) << p.file_name << ": rebuild to re-embed";
    EXPECT_NO_THROW(ShippedProgram(p.file_name));
  }
  EXPECT_THROW(ShippedProgram("nope.asm"), std::invalid_argument);
}

TEST(ShippedPrograms, RayProgramsKeepTheExitContractAndTheLeafHas14MicroOps) {
  for (StepProgramKind k : {StepProgramKind::kGridMarch, StepProgramKind::kDdaStep, StepProgramKind::kRmStep}) {
    const auto p = ShippedStepProgram(k);
    EXPECT_EQ(p->ReturnIfCount(ProgramSection::kLoop), 2) << p->name();
    // RETURN_IF #0 is the hit test right after the fetch and its compare.
    const auto& loop = p->section(ProgramSection::kLoop);
    EXPECT_EQ(loop[0].opcode, Opcode::kLoad);
    EXPECT_EQ(loop[3].opcode, Opcode::kReturnIf) << p->name();
    EXPECT_EQ(loop.back().opcode, Opcode::kReturnIf) << p->name();
  }
  const auto leaf = ShippedLeafProgram(LeafProgramKind::kBeamModel);
  EXPECT_FALSE(leaf->has_loop());
  EXPECT_EQ(leaf->section(ProgramSection::kEpilogue).size(), 14u);  // the artifact's count
  EXPECT_EQ(ShippedLeafProgram(LeafProgramKind::kNone), nullptr);
}

TEST(ShippedPrograms, SactTestIs47TtaPlusMicroOpsAnd15Exits) {
  const auto p = ShippedStepProgram(StepProgramKind::kSactTest);
  int tta_ops = 0;
  for (const MicroOp& op : p->section(ProgramSection::kLoop))
    if (InfoOf(op.opcode).sact) tta_ops += static_cast<int>(TtaPlusExpansion(op.opcode).size());
  EXPECT_EQ(tta_ops, 47);  // paper: "Full test: 47 micro-ops on TTA+"
  EXPECT_EQ(p->ReturnIfCount(ProgramSection::kLoop), 15);
}

}  // namespace
}  // namespace rc
