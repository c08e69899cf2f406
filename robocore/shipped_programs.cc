#include "robocore/shipped_programs.h"

#include <map>
#include <mutex>
#include <stdexcept>

namespace rc {

std::string ShippedProgramDirectory() { return RC_PROGRAM_DIR; }

std::shared_ptr<const MicroProgram> ShippedProgram(const std::string& file_name) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const MicroProgram>> parsed;
  std::lock_guard<std::mutex> lock(mutex);
  if (auto it = parsed.find(file_name); it != parsed.end()) return it->second;
  for (const EmbeddedProgram& p : EmbeddedPrograms()) {
    if (file_name != p.file_name) continue;
    // Errors name the source file, so a broken shipped program points at it.
    auto program =
        std::make_shared<const MicroProgram>(ParseMicroProgram(p.text, ShippedProgramDirectory() + "/" + file_name));
    parsed.emplace(file_name, program);
    return program;
  }
  throw std::invalid_argument("no shipped micro-op program named '" + file_name + "'");
}

std::shared_ptr<const MicroProgram> ShippedStepProgram(StepProgramKind kind) {
  switch (kind) {
    case StepProgramKind::kGridMarch: return ShippedProgram("grid_march.asm");
    case StepProgramKind::kDdaStep: return ShippedProgram("dda_step.asm");
    case StepProgramKind::kRmStep: return ShippedProgram("rm_step.asm");
    case StepProgramKind::kSactTest: return ShippedProgram("sact_obb_aabb.asm");
    case StepProgramKind::kSphereTest: return ShippedProgram("sphere_aabb.asm");
    case StepProgramKind::kBallQueryPRay: return ShippedProgram("ball_query_pray.asm");
    case StepProgramKind::kBallQueryPSphere: return ShippedProgram("ball_query_psphere.asm");
  }
  throw std::logic_error("unhandled step program kind");
}

bool IsShippedProgramOf(StepProgramKind kind, const std::shared_ptr<const MicroProgram>& program) {
  if (!program) return false;
  if (program == ShippedStepProgram(kind)) return true;
  return kind == StepProgramKind::kGridMarch && program == ShippedProgram("grid_march_artifact.asm");
}

std::shared_ptr<const MicroProgram> ShippedLeafProgram(LeafProgramKind kind) {
  switch (kind) {
    case LeafProgramKind::kNone: return nullptr;
    case LeafProgramKind::kBeamModel: return ShippedProgram("beam_leaf.asm");
    case LeafProgramKind::kCustom: break;
  }
  throw std::invalid_argument("a custom leaf program is not shipped");
}

}  // namespace rc
