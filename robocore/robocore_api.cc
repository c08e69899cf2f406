#include "robocore/robocore_api.h"

#include <stdexcept>
#include <string>

#include "robocore/shipped_programs.h"

namespace rc {

void RoboCoreContext::ConfigRoboCore(std::shared_ptr<const MicroProgram> program,
                                     std::shared_ptr<const MicroProgram> leaf) {
  if (!program || !program->has_loop())
    throw std::invalid_argument("ConfigRoboCore: the program needs a loop: section");
  if (program->ReturnIfCount(ProgramSection::kLoop) <= kRayEndReturn)
    throw std::invalid_argument("ConfigRoboCore: program '" + program->name() +
                                "' needs RETURN_IF #0 (hit) and #1 (end) in its loop");
  if (leaf && (leaf->has_loop() || !leaf->section(ProgramSection::kPrologue).empty()))
    throw std::invalid_argument("ConfigRoboCore: leaf '" + leaf->name() +
                                "' must hold only an epilogue: section");
  program_ = std::move(program);
  leaf_ = std::move(leaf);
  leaf_configured_ = true;
}

void RoboCoreContext::ConfigDecode(std::vector<NodeLayout> layouts) {
  for (const NodeLayout& l : layouts)
    if (l.element_bytes == 0) throw std::invalid_argument("ConfigDecode: a node has 0 bytes");
  layouts_ = std::move(layouts);
}

void RoboCoreContext::ExecuteRoboCore(const RayBatch& queries, const RayCastScene& scene,
                                      std::vector<RayHit>& results, KernelRecord& record) const {
  RecordOptions options;
  options.program = program_;
  if (!layouts_.empty()) {
    for (const MemoryRegion& region : RayCastRegions(scene, options.layout)) {
      const NodeLayout* layout = nullptr;
      for (const NodeLayout& l : layouts_)
        if (l.kind == region.kind) layout = &l;
      if (!layout)
        throw std::invalid_argument("ConfigDecode: no layout for the " + region.name + "'s nodes");
      if (layout->element_bytes != region.element_bytes)
        throw std::invalid_argument("ConfigDecode: the " + region.name + " stores " +
                                    std::to_string(region.element_bytes) +
                                    "-byte nodes, the layout says " +
                                    std::to_string(layout->element_bytes));
    }
  }
  CastRayBatchRecorded(scene, queries, results, record, options);
  if (leaf_configured_) {
    record.leaf = leaf_;
    record.leaf_kind = leaf_ ? LeafProgramKind::kCustom : LeafProgramKind::kNone;
  }
}

}  // namespace rc
