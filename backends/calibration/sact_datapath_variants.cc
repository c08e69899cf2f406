#include "backends/calibration/sact_datapath_variants.h"

#include <array>
#include <stdexcept>

#include "backends/calibration/sact_kernel_record.h"
#include "robocore/collision/sact.h"
#include "robocore/micro_program.h"

namespace rc {
namespace {

bool IsBoxNormalAxis(int axis) { return axis < kSactBoxNormalAxes; }

// The axis -> round table; throws if an axis is missing or repeated.
std::array<std::uint8_t, kSactAxisCount> RoundOfAxis(const SactDatapathVariant& variant) {
  std::array<std::uint8_t, kSactAxisCount> round{};
  round.fill(kNoExit);
  for (std::size_t r = 0; r < variant.rounds.size(); ++r)
    for (int axis : variant.rounds[r]) {
      if (axis < 0 || axis >= kSactAxisCount || round[axis] != kNoExit)
        throw std::invalid_argument("SACT variant '" + variant.name + "': axis " + std::to_string(axis) +
                                    " is out of range or in two rounds");
      round[axis] = static_cast<std::uint8_t>(r);
    }
  for (int axis = 0; axis < kSactAxisCount; ++axis)
    if (round[axis] == kNoExit)
      throw std::invalid_argument("SACT variant '" + variant.name + "': axis " + std::to_string(axis) +
                                  " is never tested");
  return round;
}

}  // namespace

SactDatapathVariant FullyParallelSact() {
  SactDatapathVariant v;
  v.name = "fully parallel SACT (6 Box-Normal + 9 Edge x Edge units)";
  v.rounds.emplace_back();
  for (int axis = 0; axis < kSactAxisCount; ++axis) v.rounds.back().push_back(axis);
  return v;
}

SactDatapathVariant SactUnitCopies(int copies) {
  if (copies < 1) throw std::invalid_argument("SactUnitCopies: copies must be >= 1");
  SactDatapathVariant v;
  v.name = std::to_string(copies) + " of each SACT unit";
  auto group = [&](int first, int end) {
    for (int axis = first; axis < end; axis += copies) {
      v.rounds.emplace_back();
      for (int k = axis; k < std::min(end, axis + copies); ++k) v.rounds.back().push_back(k);
    }
  };
  group(0, kSactBoxNormalAxes);
  group(kSactBoxNormalAxes, kSactAxisCount);
  return v;
}

std::shared_ptr<const MicroProgram> VariantProgram(const SactDatapathVariant& variant,
                                                   const OpUnitLatencies& latencies) {
  RoundOfAxis(variant);  // validates
  std::string text = "# " + variant.name +
                     " (backends/calibration/sact_datapath_variants.h)\n"
                     "loop:\n  LOAD box, node\n  PRE frame, obb, box\n";
  for (std::size_t r = 0; r < variant.rounds.size(); ++r) {
    bool any_edge = false, any_box = false;
    for (int axis : variant.rounds[r]) (IsBoxNormalAxis(axis) ? any_box : any_edge) = true;
    // The round lasts as long as its slowest unit kind.
    const bool edge = any_edge && (!any_box || latencies.edge_edge_cycles >= latencies.box_normal_cycles);
    text += edge ? "  EDGE sep, frame, 0\n" : "  BOX sep, frame, 0\n";
    text += "  RETURN_IF sep  # round " + std::to_string(r) + "\n";
  }
  text += "  PUSH overlapping\n";
  return std::make_shared<const MicroProgram>(ParseMicroProgram(text, variant.name));
}

KernelRecord VariantRecord(const KernelRecord& shipped_sact_record, const SactDatapathVariant& variant,
                           const OpUnitLatencies& latencies) {
  if (shipped_sact_record.step_kind != StepProgramKind::kSactTest)
    throw std::invalid_argument("VariantRecord: the record is not a SACT traversal");
  const auto round = RoundOfAxis(variant);
  return WithProgram(shipped_sact_record, VariantProgram(variant, latencies),
                     [&](std::uint8_t exit) { return exit == kNoExit ? kNoExit : round.at(exit); });
}

}  // namespace rc
