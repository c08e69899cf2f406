#include "robocore/robocore_api.h"

#include <stdexcept>
#include <string>

#include "robocore/collision/sact_kernel_record.h"
#include "robocore/shipped_programs.h"

namespace rc {
namespace {

bool HasSactMicroOps(const MicroProgram& program) {
  for (int s = 0; s < kSectionCount; ++s)
    for (const MicroOp& op : program.section(static_cast<ProgramSection>(s)))
      if (InfoOf(op.opcode).sact) return true;
  return false;
}

}  // namespace

void RoboCoreContext::ConfigRoboCore(std::shared_ptr<const MicroProgram> program,
                                     std::shared_ptr<const MicroProgram> leaf) {
  if (!program || !program->has_loop())
    throw std::invalid_argument("ConfigRoboCore: the program needs a loop: section");
  if (program->ReturnIfCount(ProgramSection::kLoop) <= kRayEndReturn)
    throw std::invalid_argument("ConfigRoboCore: program '" + program->name() +
                                "' needs RETURN_IF #0 (hit) and #1 (end) in its loop");
  std::string why;
  if (HasSactMicroOps(*program) && !KeepsSactExitContract(*program, &why))
    throw std::invalid_argument("ConfigRoboCore: " + why);
  if (leaf && (leaf->has_loop() || !leaf->section(ProgramSection::kPrologue).empty()))
    throw std::invalid_argument("ConfigRoboCore: leaf '" + leaf->name() + "' must hold only an epilogue: section");
  program_ = std::move(program);
  leaf_ = std::move(leaf);
  leaf_configured_ = true;
}

void RoboCoreContext::ConfigDecode(std::vector<NodeLayout> layouts) {
  for (const NodeLayout& l : layouts)
    if (l.element_bytes == 0) throw std::invalid_argument("ConfigDecode: a node has 0 bytes");
  layouts_ = std::move(layouts);
}

void RoboCoreContext::CheckLayout(const MemoryRegion& region) const {
  if (layouts_.empty()) return;
  const NodeLayout* layout = nullptr;
  for (const NodeLayout& l : layouts_)
    if (l.kind == region.kind) layout = &l;
  if (!layout) throw std::invalid_argument("ConfigDecode: no layout for the " + region.name + "'s nodes");
  if (layout->element_bytes != region.element_bytes)
    throw std::invalid_argument("ConfigDecode: the " + region.name + " stores " + std::to_string(region.element_bytes) +
                                "-byte nodes, the layout says " + std::to_string(layout->element_bytes));
}

void RoboCoreContext::ExecuteRoboCore(const RayBatch& queries, const RayCastScene& scene, std::vector<RayHit>& results,
                                      KernelRecord& record) const {
  if (program_ && HasSactMicroOps(*program_))
    throw std::invalid_argument("ExecuteRoboCore: program '" + program_->name() +
                                "' is a collision (SACT) program; run it with CheckCollisions");
  RecordOptions options;
  options.program = program_;
  for (const MemoryRegion& region : RayCastRegions(scene, options.layout)) CheckLayout(region);
  CastRayBatchRecorded(scene, queries, results, record, options);
  if (leaf_configured_) {
    record.leaf = leaf_;
    record.leaf_kind = leaf_ ? LeafProgramKind::kCustom : LeafProgramKind::kNone;
  }
}

template <typename Scalar>
void RoboCoreContext::CheckCollisions(const std::vector<Obb<Scalar>>& obbs, const FlatBoxTree<Scalar>& tree,
                                      std::vector<CollisionResult>& results, KernelRecord& record,
                                      const CollisionOptions<Scalar>& options, CollisionBatch* visits) const {
  std::string why;
  if (program_ && !KeepsSactExitContract(*program_, &why))
    throw std::invalid_argument("CheckCollisions: ConfigRoboCore's " + why);
  if (!options.sact.IsValid(&why)) throw std::invalid_argument("CheckCollisions: SACT options: " + why);
  if (options.sact.sphere_pretests)
    throw std::invalid_argument("CheckCollisions: sphere pre-tests have no section in the SACT program");
  // The layout check needs only the region, so a bad decode fails before
  // the kernel runs.
  CollisionBatch shape;
  shape.node_bytes = tree.node_bytes();
  shape.node_count = tree.nodes().size();
  CheckLayout(TreeNodeRegion(shape));

  CollisionBatch batch = CollideBatch(tree, obbs, options);
  KernelRecord out = SactKernelRecord(batch, program_);
  if (leaf_configured_) {
    out.leaf = leaf_;
    out.leaf_kind = leaf_ ? LeafProgramKind::kCustom : LeafProgramKind::kNone;
  }
  results.resize(batch.query_count());
  for (std::size_t i = 0; i < batch.query_count(); ++i) results[i] = ResultOf(batch.outcomes[i]);
  record = std::move(out);
  if (visits) *visits = std::move(batch);
}

template void RoboCoreContext::CheckCollisions(const std::vector<Obb<float>>&, const FlatBoxTree<float>&,
                                               std::vector<CollisionResult>&, KernelRecord&,
                                               const CollisionOptions<float>&, CollisionBatch*) const;
template void RoboCoreContext::CheckCollisions(const std::vector<Obb<double>>&, const FlatBoxTree<double>&,
                                               std::vector<CollisionResult>&, KernelRecord&,
                                               const CollisionOptions<double>&, CollisionBatch*) const;

}  // namespace rc
