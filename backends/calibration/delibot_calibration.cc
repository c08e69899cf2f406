#include "backends/calibration/delibot_calibration.h"


#include "backends/calibration/pricing_helpers.h"

namespace rc {
namespace {

// The artifact's DeliBot cell transaction (REFERENCE.md section 2): SUB,
// RCP, DOT, CMP, OR, CMP, OR.
constexpr int kArtifactMicroOpsPerCell = 7;

}  // namespace

std::vector<CalibrationRow> DelibotRows(const CalibrationWorkloads& workloads, const BackendParameters& params) {
  std::vector<CalibrationRow> rows;
  for (const RayCasterRecord& r : workloads.rays) {
    const auto cost = PriceByName({"simt", "ttaplus", "robocore"}, r.record, params);
    const BatchCost& simt = cost.at("simt");
    const BatchCost& tta = cost.at("ttaplus");
    const BatchCost& robo = cost.at("robocore");
    const LoopMix mix = LoopMixOf(*r.record.program);
    const std::string method = ToString(r.method);

    CalibrationRow vs_cuda;
    vs_cuda.result = "DeliBot MCL (" + method + "), RoboCore vs CUDA";
    vs_cuda.paper = "1.10x faster";
    vs_cuda.paper_value = 1.10;
    vs_cuda.ours = Speedup(simt.seconds, robo.seconds);
    vs_cuda.why = FormatSentence(
        "Our %s step runs %d micro-ops per cell (%d CMP) against the artifact's %d, and one OP unit per kind per "
        "set gives the RT unit 4 per cycle against an SM's 4 warp instructions, so RoboCore's busiest unit is "
        "bound by %s while SIMT (efficiency %.2f) is bound by %s.",
        method.c_str(), mix.micro_ops, mix.compares, kArtifactMicroOpsPerCell, robo.bound.c_str(),
        simt.simt_efficiency, simt.bound.c_str());
    rows.push_back(vs_cuda);

    CalibrationRow vs_tta;
    vs_tta.result = "DeliBot MCL (" + method + "), RoboCore vs TTA+";
    vs_tta.paper = "1.20x faster";
    vs_tta.paper_value = 1.20;
    vs_tta.ours = Speedup(tta.seconds, robo.seconds);
    // Computation cycles per ray from the same section tables the backends
    // price with (node fetch latency excluded).
    const double tta_cycles = AverageComputationCycles(r.record, params.ttaplus.Datapath(EarlyExitMode::kNone));
    const double robo_cycles = AverageComputationCycles(r.record, params.robocore.Datapath());
    vs_tta.why = FormatSentence(
        "A ray program has no SACT micro-ops, so RoboCore differs from TTA+ only by conditional return, which can "
        "end just a ray's last pass while its RETURN_IFs run as micro-ops in every pass (%.0f computation cycles "
        "per ray against TTA+'s %.0f; busiest units bound by %s and %s), and our plain TTA+ lacks the artifact's "
        "optimistic RETURN predication.",
        robo_cycles, tta_cycles, robo.bound.c_str(), tta.bound.c_str());
    rows.push_back(vs_tta);
  }
  return rows;
}

}  // namespace rc
