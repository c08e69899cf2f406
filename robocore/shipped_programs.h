#pragma once
// The micro-op programs shipped under robocore/programs/.
//
// They are embedded into the library at build time (robocore/CMakeLists.txt
// reads every .asm into a generated embedded_programs.cc), so a binary
// finds them from any working directory and after installation. The source
// directory is also compiled in as RC_PROGRAM_DIR for tools that want to
// show or diff the files; the embedded copy is what the models use. CMake
// re-runs its configure step when a .asm file changes, so the two agree in
// every build (a test checks it).
#include <memory>
#include <string>
#include <vector>

#include "robocore/kernel_record.h"
#include "robocore/micro_program.h"

namespace rc {

struct EmbeddedProgram {
  const char* file_name;  // e.g. "dda_step.asm"
  const char* text;
};
// Defined in the generated embedded_programs.cc.
const std::vector<EmbeddedProgram>& EmbeddedPrograms();

// The source directory of the shipped programs (RC_PROGRAM_DIR).
std::string ShippedProgramDirectory();

// Parses (once, thread-safely) and returns a shipped program by file name.
// Throws std::invalid_argument for a name that is not shipped.
std::shared_ptr<const MicroProgram> ShippedProgram(const std::string& file_name);

std::shared_ptr<const MicroProgram> ShippedStepProgram(StepProgramKind kind);
// True if `program` is a shipped cost description of kind's kernel: its
// shipped step program, or a shipped variant of it that describes the same
// functional kernel for the RT units (grid_march_artifact.asm for march).
// A CUDA-core model prices every such record by the kind's compiled kernel.
bool IsShippedProgramOf(StepProgramKind kind, const std::shared_ptr<const MicroProgram>& program);
// Null for LeafProgramKind::kNone.
std::shared_ptr<const MicroProgram> ShippedLeafProgram(LeafProgramKind kind);

}  // namespace rc
