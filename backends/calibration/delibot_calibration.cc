#include "backends/calibration/delibot_calibration.h"

#include <fmt/format.h>

#include <array>
#include <map>
#include <memory>

#include "backends/calibration/pricing_helpers.h"
#include "backends/calibration/why_sentences.h"
#include "robocore/shipped_programs.h"
#include "workloads/delibot/delibot_run.h"

namespace rc {
namespace {

// What one preset's pricing of a DeliBot workload measured.
struct DelibotColumn {
  SideEvidence simt{"the CUDA cores"}, tta{"TTA+"}, robo{"RoboCore"};
  LoopMix mix;                             // the step program's loop
  std::uint32_t cell_bytes = 1;            // bytes per fetched cell
  double robo_cycles = 0, tta_cycles = 0;  // small batch: computation cycles per ray
  double queries = 0, nodes = 0;
  long updates = 0, records = 0;
};

DelibotColumn PriceFirstUpdate(const CalibrationWorkloads& w, RayCastMethod method, const BackendPreset& preset) {
  const RayCastScene scene(w.ray_grid, method);
  std::vector<RayHit> hits;
  KernelRecord record;
  CastRayBatchRecorded(scene, w.first_update, hits, record, RecordOptionsFor(method, preset.kernel));
  const auto cost = PriceByName({"simt", "ttaplus", "robocore"}, record, preset.backend);
  DelibotColumn c;
  c.simt.Add(cost.at("simt"));
  c.tta.Add(cost.at("ttaplus"));
  c.robo.Add(cost.at("robocore"));
  c.mix = LoopMixOf(*record.program);
  c.cell_bytes = record.node_bytes;
  c.tta_cycles = AverageComputationCycles(record, preset.backend.ttaplus.Datapath(EarlyExitMode::kNone));
  c.robo_cycles = AverageComputationCycles(record, preset.backend.robocore.Datapath());
  c.queries = double(record.query_count());
  c.nodes = double(record.total_nodes());
  c.updates = c.records = 1;
  return c;
}

DelibotSettings RunSettings(const CalibrationOptions& o, const RayKernelChoices& kernel,
                            const BackendParameters& params) {
  DelibotSettings s;
  s.ray_caster = RayCastMethod::kMarch;
  s.mcl.particle_count = o.run_particles;
  s.mcl.beams.beam_step = o.run_beam_step;
  s.mcl.record_choices = kernel;
  s.max_records = o.run_max_records;
  s.price_backends = true;
  s.backend_params = params;
  s.ledger.replay_sms = kReplaySms;  // as rcbench delibot: a sample of the memory replayed, the rest estimated
  s.ledger.replay_block_stride = kReplayBlockStride;
  return s;
}

// Where a record's address sample puts warps (AddressSample::SamePlacement):
// a record sampled for one placement cannot be replayed under another.
using Placement = std::array<int, 4>;
Placement PlacementOf(const GpuParams& gpu) { return {gpu.warp_size, gpu.warps_per_block, gpu.sms, gpu.sector_bytes}; }

// One filter run per placement among `variants` (the run's answers do not
// depend on the cost parameters, so every variant sees the same launches);
// each update's launches are priced on the three compared backends under
// every variant as they are recorded, sharing each launch's memory replays
// among the variants whose memory system agrees (PricingContext). An
// update's launches are summed before they reach a side, as the ledger
// sums them.
std::vector<DelibotColumn> PriceRunUnderVariants(const DelibotRunWorkload& run, const CalibrationOptions& o,
                                                 const RayKernelChoices& kernel,
                                                 const std::vector<BackendParameters>& variants) {
  std::vector<DelibotColumn> columns(variants.size());
  std::map<Placement, std::vector<std::size_t>> groups;
  for (std::size_t v = 0; v < variants.size(); ++v) groups[PlacementOf(variants[v].gpu)].push_back(v);
  static const char* const kSides[] = {"simt", "ttaplus", "robocore"};
  for (const auto& group : groups) {
    const std::vector<std::size_t>& members = group.second;  // a named reference: C++17 lambdas cannot capture bindings
    std::vector<std::unique_ptr<Backend>> backends;          // member-major, kSides order
    for (std::size_t v : members)
      for (const char* side : kSides) backends.push_back(Backend::Create(side, variants[v]));
    DelibotSettings s = RunSettings(o, kernel, variants[members.front()]);
    s.on_priced_launches = [&](const std::vector<const KernelRecord*>& launches) {
      std::vector<BatchCost> sums(backends.size());
      std::vector<char> started(backends.size(), 0);  // not vector<bool>: written by several threads
      double queries = 0, nodes = 0;
      for (const KernelRecord* record : launches) {
        if (record->query_count() == 0) continue;  // as BackendLedger::AddLaunch
        queries += double(record->query_count());
        nodes += double(record->total_nodes());
        PricingContext context(*record);
#pragma omp parallel for schedule(dynamic, 1)
        for (long b = 0; b < static_cast<long>(backends.size()); ++b) {
          BatchCost cost = backends[b]->Price(*record, context);
          if (!started[b])
            sums[b] = std::move(cost), started[b] = 1;
          else
            sums[b] += cost;
        }
      }
      if (queries == 0) return;
      for (std::size_t m = 0; m < members.size(); ++m) {
        DelibotColumn& c = columns[members[m]];
        ++c.updates;
        c.queries += queries;
        c.nodes += nodes;
        c.simt.Add(sums[3 * m]);
        c.tta.Add(sums[3 * m + 1]);
        c.robo.Add(sums[3 * m + 2]);
      }
    };
    const DelibotResult result = RunDelibot(run.grid, run.trace, nullptr, s);
    for (std::size_t v : members) columns[v].records = static_cast<long>(result.rows.size());
  }
  RecordOptions options = RecordOptionsFor(RayCastMethod::kMarch, kernel);
  for (DelibotColumn& c : columns) {
    c.mix = LoopMixOf(options.program ? *options.program : *ShippedStepProgram(StepProgramKind::kGridMarch));
    c.cell_bytes = options.layout.grid_cell_bytes;
  }
  return columns;
}

std::string ProgramClause(const DelibotColumn& c, const std::string& method) {
  return fmt::format("Our {} step runs {} micro-ops per cell ({} CMP) on {}-byte cells. ", method.c_str(),
                     c.mix.micro_ops, c.mix.compares, c.cell_bytes);
}

void AddPair(std::vector<CalibrationRow>& rows, const std::string& what, const std::string& method,
             CalibrationScale scale, const std::string& workload, const DelibotColumn& artifact,
             const DelibotColumn& ours) {
  auto vs_cuda = [&](const DelibotColumn& c) {
    return ColumnValue{Speedup(c.simt.seconds(), c.robo.seconds()),
                       ProgramClause(c, method) + CompareSides(c.robo, c.simt),
                       fmt::format("{} micro-ops per {}-byte cell; ", c.mix.micro_ops, c.cell_bytes) +
                           LimitTag(c.robo) + "; " + LimitTag(c.simt)};
  };
  auto vs_tta = [&](const DelibotColumn& c) {
    const std::string work =
        c.robo_cycles > 0
            ? fmt::format("{:.0f} computation cycles per ray against TTA+'s {:.0f}", c.robo_cycles, c.tta_cycles)
            : fmt::format("{:.3g} micro-ops executed against TTA+'s {:.3g}", c.robo.micro_ops(), c.tta.micro_ops());
    return ColumnValue{Speedup(c.tta.seconds(), c.robo.seconds()),
                       "A ray program has no SACT micro-ops, so RoboCore differs from plain TTA+ only by conditional "
                       "return, which ends just a ray's last pass while its RETURN_IFs run in every pass (" +
                           work + "). " + CompareSides(c.robo, c.tta),
                       LimitTag(c.robo) + "; " + LimitTag(c.tta)};
  };
  CalibrationRow cuda;
  cuda.result = what + ", RoboCore vs CUDA";
  cuda.scale = scale;
  cuda.workload = workload;
  cuda.paper = "1.10x faster";
  cuda.paper_value = 1.10;
  SetColumns(cuda, vs_cuda(artifact), vs_cuda(ours));
  rows.push_back(cuda);
  CalibrationRow tta;
  tta.result = what + ", RoboCore vs TTA+";
  tta.scale = scale;
  tta.workload = workload;
  tta.paper = "1.20x faster";
  tta.paper_value = 1.20;
  SetColumns(tta, vs_tta(artifact), vs_tta(ours));
  rows.push_back(tta);
}

void AddRunPair(std::vector<CalibrationRow>& rows, const std::string& run, const CalibrationOptions& o,
                const DelibotColumn& artifact, const DelibotColumn& ours) {
  const std::string workload =
      fmt::format("{} updates of {:.0f} rays x {:.1f} nodes ({} records, {} particles x {} beams)", ours.updates,
                  ours.queries / double(ours.updates), ours.nodes / ours.queries, ours.records, o.run_particles,
                  (180 + o.run_beam_step - 1) / o.run_beam_step);
  AddPair(rows, "DeliBot MCL, whole run (" + run + ", march)", "march", CalibrationScale::kPaperScale, workload,
          artifact, ours);
}

}  // namespace

std::vector<CalibrationRow> DelibotRows(const CalibrationWorkloads& w, const BackendPreset& artifact,
                                        const BackendPreset& ours, std::vector<std::string>* notes, bool include_runs) {
  std::vector<CalibrationRow> rows;
  if (include_runs) {
    for (const DelibotRunWorkload& run : w.runs) {
      const DelibotColumn o = PriceRunUnderVariants(run, w.options, ours.kernel, {ours.backend}).front();
      const DelibotColumn a =
          &artifact == &ours ? o : PriceRunUnderVariants(run, w.options, artifact.kernel, {artifact.backend}).front();
      AddRunPair(rows, run.name, w.options, a, o);
      if (notes)
        notes->push_back("DeliBot " + run.name + ": " + std::to_string(run.trace.scans.size()) +
                         " laser records, march ray caster, " + std::to_string(w.options.run_particles) +
                         " particles, every " + std::to_string(w.options.run_beam_step) +
                         "th beam, global localization; every update priced on every backend (" +
                         DescribeMemoryReplay(kReplaySms, kReplayBlockStride) + ").");
    }
  }
  for (RayCastMethod method : {RayCastMethod::kMarch, RayCastMethod::kDda, RayCastMethod::kRayMarching}) {
    const DelibotColumn o = PriceFirstUpdate(w, method, ours);
    const DelibotColumn a = &artifact == &ours ? o : PriceFirstUpdate(w, method, artifact);
    const std::string workload = fmt::format("1 update of {:.0f} rays x {:.1f} nodes", o.queries, o.nodes / o.queries);
    AddPair(rows, std::string("DeliBot MCL (") + ToString(method) + ")", ToString(method),
            CalibrationScale::kSmallBatch, workload, a, o);
  }
  return rows;
}

std::vector<std::vector<CalibrationRow>> DelibotRunRowsUnderVariants(const CalibrationWorkloads& w,
                                                                     const RayKernelChoices& kernel,
                                                                     const std::vector<BackendParameters>& variants) {
  std::vector<std::vector<CalibrationRow>> rows(variants.size());
  for (const DelibotRunWorkload& run : w.runs) {
    const std::vector<DelibotColumn> columns = PriceRunUnderVariants(run, w.options, kernel, variants);
    for (std::size_t v = 0; v < variants.size(); ++v) AddRunPair(rows[v], run.name, w.options, columns[v], columns[v]);
  }
  return rows;
}

}  // namespace rc
