#include "robocore/collision/sact_kernel_record.h"

#include <stdexcept>
#include <vector>

#include "robocore/shipped_programs.h"

namespace rc {
namespace {

bool Fail(std::string* why, const std::string& reason) {
  if (why) *why = reason;
  return false;
}

// One query's visits as fetch addresses and exits (exit_of maps a visit).
template <typename ExitOf>
KernelRecord BuildRecord(const CollisionBatch& batch, std::shared_ptr<const MicroProgram> program,
                         StepProgramKind kind, ExitOf&& exit_of) {
  KernelRecordBuilder builder(std::move(program), kind, TreeNodeRegion(batch));
  std::vector<std::uint64_t> addresses;
  std::vector<std::uint8_t> exits;
  for (std::size_t q = 0; q < batch.query_count(); ++q) {
    addresses.clear();
    exits.clear();
    for (std::uint64_t k = batch.visit_offsets[q]; k < batch.visit_offsets[q + 1]; ++k) {
      const NodeVisit& v = batch.visits[k];
      addresses.push_back(batch.Address(v));
      exits.push_back(exit_of(v));
    }
    builder.AddQuery(addresses, exits);
  }
  KernelRecord record = builder.Build();
  record.scalar_bytes = batch.scalar_bytes;
  record.Validate();
  return record;
}

}  // namespace

MemoryRegion TreeNodeRegion(const CollisionBatch& batch) {
  MemoryRegion region;
  region.name = "box tree nodes";
  region.kind = FetchKind::kTreeNode;
  region.base = batch.base_address;
  region.element_bytes = batch.node_bytes;
  region.elements = batch.node_count;
  return region;
}

bool KeepsSactExitContract(const MicroProgram& program, std::string* why) {
  const std::vector<MicroOp>& loop = program.section(ProgramSection::kLoop);
  if (loop.empty()) return Fail(why, "program '" + program.name() + "' has no loop: section");
  bool any_sact = false;
  for (const MicroOp& op : loop) any_sact = any_sact || InfoOf(op.opcode).sact;
  if (!any_sact)
    return Fail(why, "program '" + program.name() + "' has no SACT section (no PRE, BOX or EDGE micro-op in its loop)");
  bool pre_seen = false;
  int next_axis = 0;           // the axis whose test must come next
  int axis_tested = -1;        // the highest axis tested so far, in order
  int return_ifs = 0;
  for (const MicroOp& op : loop) {
    const std::string where = "program '" + program.name() + "' line " + std::to_string(op.line) + ": ";
    if (op.opcode == Opcode::kPre) pre_seen = true;
    if (op.opcode == Opcode::kBox || op.opcode == Opcode::kEdge) {
      const int axis = op.opcode == Opcode::kBox ? op.axis : kSactBoxNormalAxes + op.axis;
      if (!pre_seen) return Fail(why, where + "an axis test before the PRE pre-process");
      if (axis != next_axis)
        return Fail(why, where + "tests SACT axis " + std::to_string(axis) + " where axis " +
                             std::to_string(next_axis) + " (sact.h stage order) is due");
      axis_tested = axis;
      ++next_axis;
    }
    if (op.opcode == Opcode::kReturnIf) {
      if (return_ifs >= kSactAxisCount)
        return Fail(why, where + "more than " + std::to_string(kSactAxisCount) + " RETURN_IFs");
      if (axis_tested < return_ifs)
        return Fail(why, where + "RETURN_IF #" + std::to_string(return_ifs) + " comes before axis " +
                             std::to_string(return_ifs) + " is tested");
      ++return_ifs;
    }
  }
  if (next_axis != kSactAxisCount || return_ifs != kSactAxisCount)
    return Fail(why, "program '" + program.name() + "' has no SACT section: its loop tests " +
                         std::to_string(next_axis) + " of the 15 axes (PRE, BOX 0..5, EDGE 0..8) with " +
                         std::to_string(return_ifs) + " RETURN_IFs");
  return true;
}

KernelRecord SactKernelRecord(const CollisionBatch& batch, std::shared_ptr<const MicroProgram> program) {
  if (batch.robot_model != CollisionRobotModel::kObb)
    throw std::invalid_argument("SactKernelRecord: a sphere-robot batch is priced by SphereKernelRecord");
  if (batch.sphere_pretests)
    throw std::invalid_argument("SactKernelRecord: the SACT program has no sphere pre-test section");
  if (!program) program = ShippedStepProgram(StepProgramKind::kSactTest);
  std::string why;
  if (!KeepsSactExitContract(*program, &why)) throw std::invalid_argument("SactKernelRecord: " + why);
  return BuildRecord(batch, std::move(program), StepProgramKind::kSactTest, [](const NodeVisit& v) {
    return v.exit >= 0 ? static_cast<std::uint8_t>(v.exit) : kNoExit;
  });
}

bool KeepsSphereExitContract(const MicroProgram& program, std::string* why) {
  if (!program.has_loop()) return Fail(why, "program '" + program.name() + "' has no loop: section");
  for (int s = 0; s < kSectionCount; ++s)
    for (const MicroOp& op : program.section(static_cast<ProgramSection>(s)))
      if (InfoOf(op.opcode).sact)
        return Fail(why, "program '" + program.name() + "' line " + std::to_string(op.line) +
                             ": a SACT micro-op in a sphere program");
  if (program.ReturnIfCount(ProgramSection::kLoop) != 1)
    return Fail(why, "program '" + program.name() + "' needs exactly one loop RETURN_IF (#0: the sphere misses)");
  return true;
}

KernelRecord SphereKernelRecord(const CollisionBatch& batch, std::shared_ptr<const MicroProgram> program) {
  if (batch.robot_model != CollisionRobotModel::kSpheres)
    throw std::invalid_argument("SphereKernelRecord: an OBB batch is priced by SactKernelRecord");
  if (!program) program = ShippedStepProgram(StepProgramKind::kSphereTest);
  std::string why;
  if (!KeepsSphereExitContract(*program, &why)) throw std::invalid_argument("SphereKernelRecord: " + why);
  return BuildRecord(batch, std::move(program), StepProgramKind::kSphereTest, [](const NodeVisit& v) {
    return v.overlaps() ? kNoExit : std::uint8_t{0};
  });
}

}  // namespace rc
