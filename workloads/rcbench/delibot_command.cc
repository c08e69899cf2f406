// `rcbench delibot`: Monte Carlo Localization on a map and a laser trace.
// With neither --map nor --trace it runs the built-in demo: the generated
// office map and a simulated trace with ground truth, written to out/demo/.
#include <filesystem>
#include <iostream>
#include <omp.h>

#include <fmt/format.h>

#include "backends/backend.h"
#include "backends/backend_params.h"
#include "backends/scheduler/scheduler_cli.h"
#include "common/atomic_file.h"
#include "common/exit_codes.h"
#include "common/input_error.h"
#include "common/memory_cap.h"
#include "maps/map_loader.h"
#include "maps/mrpt/mrpt_map_dispatch.h"
#include "maps/office_map_generator.h"
#include "maps/ros_map_io.h"
#include "traces/cmu_log_writer.h"
#include "traces/ground_truth_io.h"
#include "traces/mrpt/mrpt_trace_dispatch.h"
#include "traces/trace_reader.h"
#include "workloads/delibot/delibot_defaults.h"
#include "workloads/delibot/delibot_memory.h"
#include "workloads/delibot/delibot_report.h"
#include "workloads/delibot/delibot_run.h"
#include "workloads/delibot/mrpt/delibot_engine.h"
#include "workloads/delibot/returns_beyond_reach.h"
#include "workloads/delibot/trace_simulator.h"
#include "workloads/rcbench/commands.h"
#include "workloads/rcbench/demo_inputs.h"
#include "workloads/rcbench/map_options.h"
#include "workloads/rcbench/number_checks.h"
#include "workloads/rcbench/progress_bar.h"
#include "workloads/rcbench/trace_lines.h"

namespace rc {
namespace {

struct DelibotCli {
  std::string map_path, map_format = "auto", map_convention;
  double map_resolution_m = 0.0;
  MapLoadOptions map_options;    // thresholds
  double laser_offset_m = -1.0;  // negative: measured from the trace
  std::string trace_path, trace_format = "auto", ground_truth_path;
  std::string sensor_model = "beam", ray_caster = "rm";
  std::string lf_distance = "unsigned";
  std::string lf_unknown = "miss";
  std::string lf_combine = "product";
  std::string beam_combine = "product";
  std::string first_set_model = "global";
  std::vector<double> initial_pose;
  std::string timeline_path, summary_path;
  int threads = 0;
  bool quiet = false;
  SchedulerCli scheduler;
  std::string engine = "ours";
  std::string initial_particles = "auto";
  DelibotSettings settings = DefaultDelibotSettings();
  GivenDelibotOptions given;
};

// --initial-particles: "auto" (kAutoInitialParticles) or a count.
int ParseInitialParticles(const std::string& value) {
  if (value == "auto") return kAutoInitialParticles;
  try {
    std::size_t used = 0;
    const long n = std::stol(value, &used);
    if (used == value.size() && n >= 0 && n <= 10000000) return static_cast<int>(n);
  } catch (const std::exception&) {
  }
  throw UsageError("--initial-particles: '" + value + "' is neither auto nor a count in [0, 10^7]");
}

void Run(DelibotCli& cli) {
  DelibotSettings& s = cli.settings;
  s.sensor_model = ParseSensorModelKind(cli.sensor_model);
  s.ray_caster = ParseRayCastMethod(cli.ray_caster);
  s.likelihood.signed_distance = cli.lf_distance == "signed";
  s.likelihood.unknown_is_edge = cli.lf_unknown == "edge";
  s.likelihood.combination = ParseBeamCombination(cli.lf_combine);
  s.beam.combination = ParseBeamCombination(cli.beam_combine);
  s.first_set_scoring = ParseFirstSetScoring(cli.first_set_model);
  if (s.first_set_scoring != FirstSetScoring::kGlobal && s.sensor_model != SensorModelKind::kLikelihoodThenBeam)
    throw UsageError("--first-set-model " + cli.first_set_model +
                     " needs --sensor-model likelihood-then-beam (a one-stage model scores the first set itself)");
  if (!cli.initial_pose.empty()) s.initial_pose = Pose2{cli.initial_pose[0], cli.initial_pose[1], cli.initial_pose[2]};
  if (cli.threads > 0) omp_set_num_threads(cli.threads);
  const DelibotEngine engine = ParseDelibotEngine(cli.engine);
  s.mcl.initial_particle_count = ParseInitialParticles(cli.initial_particles);
  std::cout << FitDefaultsToGivenOptions(s, cli.given, engine == DelibotEngine::kMrpt);
  // MRPT casts its own rays: there is no kernel record to price.
  s.price_backends = !cli.scheduler.no_pricing && engine == DelibotEngine::kOurs;
  s.ledger = ToLedgerOptions(cli.scheduler);
  const BackendPreset preset = BackendPresetOf(cli.scheduler);
  s.backend_params = preset.backend;
  s.mcl.record_choices = preset.kernel;  // how the priced ray kernel stores the grid, which march program
  if (s.price_backends && !CastsRays(s.sensor_model))
    std::cout << "note: the likelihood-field model casts no rays; backend pricing is off for this run\n";
  std::string error;
  if (!s.mcl.IsValid(&error)) throw UsageError(error);
  if (!s.beam.IsValid(&error)) throw UsageError("beam model: " + error);
  if (!s.likelihood.IsValid(&error)) throw UsageError("likelihood field: " + error);
  if (cli.map_path.empty() != cli.trace_path.empty())
    throw UsageError("give both --map and --trace, or neither for the built-in demo");
  if (cli.map_path.empty() && !cli.ground_truth_path.empty())
    throw UsageError("--ground-truth needs --map and --trace");

  DelibotProvenance provenance;
  provenance.threads = omp_get_max_threads();
  OccupancyGrid grid;
  // The laser records: streamed from the trace file (read once first to
  // validate it), so memory does not grow with the trace's length.
  std::unique_ptr<ScanSource> scans;
  std::vector<Pose2> truth;
  bool have_truth = false;
  if (cli.map_path.empty()) {
    const DemoInputs demo = MakeDemoInputs("out/demo");
    std::cout << "demo: generated office map and simulated trace written to out/demo/ (" << demo.trace.scans.size()
              << " laser records)\n";
    grid = demo.grid;
    scans = std::make_unique<OwningScanSource>(demo.trace);
    for (const auto& p : demo.ground_truth) truth.push_back(p.pose);
    have_truth = true;
    provenance = {demo.map_path,     "ros", "generated office map (occupied 0, free 254, unknown 205)",
                  demo.trace_path,   "cmu", demo.ground_truth_path,
                  provenance.threads};
    if (cli.timeline_path.empty()) cli.timeline_path = "out/demo/delibot_timeline.csv";
    if (cli.summary_path.empty()) cli.summary_path = "out/demo/delibot_summary.json";
  } else {
    MapLoadOptions map_options = cli.map_options;
    map_options.format = cli.map_format;
    if (!cli.map_convention.empty()) map_options.convention = ParseValueConvention(cli.map_convention);
    if (cli.map_resolution_m > 0) map_options.resolution_m = cli.map_resolution_m;
    LoadedMap loaded = LoadMapWithMrpt(cli.map_path, map_options).map;
    PrintMapLines(std::cout, cli.map_path, loaded);
    grid = std::move(loaded.grid);
    if (grid.CountCells(CellState::kFree) == 0)
      throw InputError(cli.map_path, 0, "", "the map has no free cell: there is nowhere to localize");
    TraceReadOptions trace_options;
    trace_options.format = cli.trace_format;
    if (cli.laser_offset_m >= 0.0) trace_options.laser_offset_forward_m = cli.laser_offset_m;
    TraceReadStats trace_stats;
    scans = OpenTraceStreamWithRawlog(cli.trace_path, trace_options, {}, &trace_stats);
    PrintTraceLines(std::cout, std::cerr, *scans, trace_stats, cli.laser_offset_m >= 0.0);
    provenance.map_path = cli.map_path;
    provenance.map_format = loaded.format;
    provenance.map_convention = loaded.value_convention;
    provenance.trace_path = cli.trace_path;
    provenance.trace_format = scans->format();
    if (!cli.ground_truth_path.empty()) {
      const GroundTruth gt = ReadGroundTruth(cli.ground_truth_path);
      CheckGroundTruthMatches(*scans, gt);
      for (const auto& p : gt.poses) truth.push_back(p.pose);
      have_truth = true;
      provenance.ground_truth_path = cli.ground_truth_path;
    }
  }

  if (s.initial_pose) {
    const Pose2& p = *s.initial_pose;
    if (!(p.x >= 0.0 && p.x < grid.extent_x_m() && p.y >= 0.0 && p.y < grid.extent_y_m()))
      throw UsageError(fmt::format("--initial-pose {:g},{:g} m is off the map, which spans [0, {:g}) x [0, {:g}) m",
                                   p.x, p.y, grid.extent_x_m(), grid.extent_y_m()));
  }
  // Before anything reads the reach; the summary records the fitted one.
  std::cout << FitReachToTrace(s.beam.max_range_m, CountReturnsBeyondReach(*scans, s.beam.max_range_m),
                               cli.given.max_range);
  // "auto" resolved here, so that the summary records the count drawn.
  const double free_area_m2 =
      static_cast<double>(grid.CountCells(CellState::kFree)) * grid.resolution_m() * grid.resolution_m();
  if (!s.initial_pose && s.mcl.initial_particle_count == kAutoInitialParticles)
    s.mcl.initial_particle_count = static_cast<int>(InitialParticleCount(s.mcl, free_area_m2));
  const bool dense_start = !s.initial_pose && s.mcl.initial_particle_count > s.mcl.particle_count;
  std::cout << "filter: " << (engine == DelibotEngine::kMrpt ? "MRPT CMonteCarloLocalization2D, " : "")
            << s.mcl.particle_count << " particles"
            << (dense_start ? " (" + std::to_string(s.mcl.initial_particle_count) + " for the first update)" : "")
            << ", " << ToString(s.sensor_model) << " model, " << ToString(s.ray_caster) << " ray caster, every "
            << s.mcl.beams.beam_step << " beam(s), " << (s.initial_pose ? "tracking" : "global localization")
            << (s.audit_claims ? ", claims audited" : "") << ", seed " << s.mcl.seed << ", " << provenance.threads
            << " thread(s)\n";
  const LaserGeometry& geometry = scans->geometry();
  const std::uint64_t need = DelibotMemoryLowerBound(s, geometry.beam_count);
  if (need > MemoryCapBytes())
    throw UsageError("--particles " + std::to_string(s.mcl.particle_count) + " with " +
                     std::to_string(s.mcl.beams.Count(geometry.beam_count)) + " beams: the filter " +
                     DescribeOverCap(need));
  if (s.mcl.beams.beam_step > geometry.beam_count)
    throw UsageError("--beam-step " + std::to_string(s.mcl.beams.beam_step) + " exceeds the trace's " +
                     std::to_string(geometry.beam_count) + " beams");
  // An output path that cannot be written, or a folder that cannot be made,
  // fails now, not after the run.
  CheckOutputPaths({cli.timeline_path, cli.summary_path});
  if (!cli.summary_path.empty()) CreateParentFolders(cli.summary_path);
  // The timeline streams, one flushed row per record, under its incomplete
  // marker until the run completes; the summary is written only after.
  std::unique_ptr<DelibotTimeline> timeline;
  if (!cli.timeline_path.empty())
    timeline = std::make_unique<DelibotTimeline>(cli.timeline_path, engine == DelibotEngine::kOurs);
  DelibotResult result;
  {
    ProgressBar bar("delibot", !cli.quiet);
    result = RunDelibotEngine(
        engine, grid, *scans, have_truth ? &truth : nullptr, s,
        [&](std::size_t done, std::size_t total) { bar.Update(done, total); },
        [&](const DelibotRow& row) {
          if (timeline) timeline->Add(row);
        });
  }
  if (timeline) timeline->Finish(result);
  if (!cli.summary_path.empty())
    WriteJsonFile(cli.summary_path, DelibotEngineSummaryJson(engine, result, s, provenance));
  PrintDelibotSummary(std::cout, result, s);
  if (!cli.timeline_path.empty()) std::cout << "timeline                " << cli.timeline_path << "\n";
  if (!cli.summary_path.empty()) std::cout << "summary                 " << cli.summary_path << "\n";
}

}  // namespace

void AddDelibotCommand(CLI::App& app) {
  auto cli = std::make_shared<DelibotCli>();
  DelibotSettings& s = cli->settings;
  // The string options show the defaults of DefaultDelibotSettings().
  cli->sensor_model = ToString(s.sensor_model);
  cli->lf_unknown = s.likelihood.unknown_is_edge ? "edge" : "miss";
  cli->lf_combine = ToString(s.likelihood.combination);
  cli->beam_combine = ToString(s.beam.combination);
  cli->first_set_model = ToString(s.first_set_scoring);
  CLI::App* cmd =
      app.add_subcommand("delibot",
                         "Monte Carlo Localization with laser ray casting (DeliBot). Without --map and --trace: the "
                         "built-in demo (generated office map, simulated trace with ground truth, out/demo/).");
  CLI::Option* map = cmd->add_option(
      "--map", cli->map_path,
      "Map file: CMU .dat, RoWild .dat, ROS .yaml, MovingAI .map, an image, or MRPT .gridmap/.simplemap[.gz]");
  // The options that describe --map mean nothing without it.
  cmd->add_option("--map-format", cli->map_format, "auto | cmu | rowild | ros | movingai | image | gridmap | simplemap")
      ->needs(map)
      ->capture_default_str();
  cmd->add_option("--map-convention", cli->map_convention,
                  "CMU/RoWild .dat values mean P(free) ('free', the default: what wean.dat holds) or P(occupied) "
                  "('occupied')")
      ->needs(map);
  cmd->add_option(
         "--map-resolution", cli->map_resolution_m,
         "Cell size (m) for MovingAI maps (default 1), images (required) and grids built from an MRPT .simplemap")
      ->needs(map)
      ->check(FinitePositive());
  cmd->add_option("--trace", cli->trace_path,
                  "Laser trace: CMU robotdata .log, RoWild .txt, CARMEN .clf, or MRPT .rawlog[.gz]");
  cmd->add_option("--trace-format", cli->trace_format, "auto | cmu | rowild | carmen | rawlog")->capture_default_str();
  AddMapThresholdOptions(*cmd, cli->map_options);
  cmd->add_option("--laser-offset", cli->laser_offset_m,
                  "Laser mount: metres ahead of the robot centre on its heading axis (m, 0 to 10); without it: "
                  "measured from the trace's own laser poses (CMU, CARMEN, rawlog); 0.25 m, the Wean robot's, "
                  "for RoWild logs, which carry none");
  cmd->add_option("--ground-truth", cli->ground_truth_path,
                  "Ground truth, one 't x_m y_m theta_rad' line per laser record (s, m, m, rad)");
  cmd->add_option("--particles", s.mcl.particle_count, "Number of particles (count, 1 to 1e7)")->capture_default_str();
  cmd->add_option_function<std::string>(
         "--initial-particles",
         [cli](const std::string& v) {
           cli->initial_particles = v;
           cli->given.initial_particles = true;
         },
         "Global localization: uniform particles before the first sensor update, which resamples them down "
         "to --particles (count; 0 = --particles; auto = 4 expected within 0.15 m and 3 deg of any pose, "
         "3395 per m^2 of free space, at most 4e6)")
      ->default_str(cli->initial_particles);
  cmd->add_option("--beam-step", s.mcl.beams.beam_step, "Use every K-th beam (count, K >= 1; 6 of 180 gives 30 beams)")
      ->capture_default_str();
  cmd->add_option("--raycaster", cli->ray_caster, "march (fixed 1-cell step) | dda (exact) | rm (distance field)")
      ->capture_default_str();
  cmd->add_option("--sensor-model", cli->sensor_model,
                  "beam (ray casting) | likelihood (likelihood field) | likelihood-then-beam (the likelihood field "
                  "while rival hypotheses are alive, the beam model once one is left; docs/defaults.md)")
      ->check(CLI::IsMember({"beam", "likelihood", "likelihood-then-beam"}))
      ->each([cli](const std::string&) { cli->given.sensor_model = true; })
      ->capture_default_str();
  cmd->add_option("--first-set-model", cli->first_set_model,
                  "With likelihood-then-beam, what scores the dense first update's cut: global (the likelihood "
                  "field) | tracking (the beam model: one ray per particle and beam, 26-49 million on the demo's and "
                  "Wean's maps; it sees people as short readings but alone claims look-alikes on real Wean logs) | "
                  "mixture (both, the cut drawn half by each model's posterior; docs/defaults.md)")
      ->check(CLI::IsMember({"global", "tracking", "mixture"}))
      ->capture_default_str();
  CLI::Option* claim_audit =
      cmd->add_flag("--claim-audit", s.audit_claims,
                    "Audit each claim of being localized before making it (the default, but with --sensor-model beam "
                    "only when given): the claim's latest "
                    "scans must single out the claimed place among uniform poses near it, then over the whole "
                    "map (as many as the auto first set), by the rival window; a refused claim is not made "
                    "(docs/defaults.md, \"The claim audit\")")
          ->each([cli](const std::string&) { cli->given.claim_audit = true; });
  CLI::Option* no_claim_audit = cmd->add_flag_function(
                                       "--no-claim-audit",
                                       [cli](std::int64_t) {
                                         cli->settings.audit_claims = false;
                                         cli->given.claim_audit = true;
                                       },
                                       "Make each claim as it falls due, unaudited (the defaults before the "
                                       "audit; on held-out traces about one claim in three was then wrong)")
                                    ->excludes(claim_audit);
  cmd->add_option("--claim-audit-scans", s.claim_audit_scans,
                  "The latest sensor updates' scans a claim is audited on (count)")
      ->check(CLI::Range(1, 1000))
      ->excludes(no_claim_audit)
      ->capture_default_str();
  cmd->add_option("--seed", s.mcl.seed, "Random seed (unitless)")->capture_default_str();
  cmd->add_option("--max-records", s.max_records, "Process at most N laser records (count; 0 = all)")
      ->capture_default_str();
  cmd->add_option("--max-range", s.beam.max_range_m,
                  "Model max range (m); readings at or beyond are 'no return'. Not given: 10, widened to cover 95% "
                  "of the trace's returns when more than a quarter lie beyond it (docs/delibot.md, \"Max range\")")
      ->check(FinitePositive())
      ->each([cli](const std::string&) { cli->given.max_range = true; })
      ->capture_default_str();
  cmd->add_option("--sigma-hit", s.beam.sigma_hit_m, "Beam model hit sigma (m)")->capture_default_str();
  cmd->add_option("--z-hit", s.beam.z_hit, "Beam model hit weight (unitless)")->capture_default_str();
  cmd->add_option("--z-short", s.beam.z_short, "Beam model short weight (unitless)")->capture_default_str();
  cmd->add_option("--z-max", s.beam.z_max, "Beam model max-range weight (unitless)")->capture_default_str();
  cmd->add_option("--z-rand", s.beam.z_rand, "Beam model random weight (unitless)")->capture_default_str();
  cmd->add_option("--lambda-short", s.beam.lambda_short_per_m, "Beam model short-reading rate (1/m)")
      ->capture_default_str();
  cmd->add_option("--beam-combine", cli->beam_combine,
                  "Beam model, how a scan's beams combine: 'product' of the per-beam mixture densities (log "
                  "domain; Thrun et al., MRPT), or 'amcl-cube', nav2 AMCL's 1 + sum of cubed per-beam "
                  "probabilities (hit term without its normalizer; far flatter, as for --lf-combine). The "
                  "rays cast, and so the backends' costs, are the same")
      ->check(CLI::IsMember({"product", "amcl-cube"}))
      ->capture_default_str();
  cmd->add_option("--lf-sigma-hit", s.likelihood.sigma_hit_m, "Likelihood field sigma (m)")->capture_default_str();
  cmd->add_option("--lf-max-dist", s.likelihood.max_occ_dist_m, "Likelihood field distance cap (m)")
      ->capture_default_str();
  cmd->add_option(
         "--lf-distance", cli->lf_distance,
         "Likelihood field inside walls: 'unsigned' scores 0 there (AMCL's field; biased forward on "
         "maps that match the world), 'signed' scores an end point's depth below the wall face "
         "(unbiased, but worse on maps that draw open doors as walls; docs/delibot.md, \"Likelihood field, signed or "
         "not\")")
      ->check(CLI::IsMember({"signed", "unsigned"}))
      ->capture_default_str();
  cmd->add_option("--lf-unknown", cli->lf_unknown,
                  "Likelihood field, an end point at an unknown cell: 'miss' scores it at the distance cap; "
                  "'edge' takes the edge of mapped free space for a surface, as the ray casters and "
                  "'rcbench simulate' do (distances to occupied or unknown cells, depth inside unknown space)")
      ->check(CLI::IsMember({"miss", "edge"}))
      ->capture_default_str();
  cmd->add_option("--lf-combine", cli->lf_combine,
                  "Likelihood field, how a scan's beams combine: 'product' of the per-beam densities (log "
                  "domain, beams independent; MRPT), or 'amcl-cube', nav2 AMCL's and Beluga's 1 + sum of cubed "
                  "per-beam probabilities (far flatter: one scan of n beams changes a weight by at most a "
                  "factor 1 + n (z_hit + z_rand / max_range)^3)")
      ->check(CLI::IsMember({"product", "amcl-cube"}))
      ->capture_default_str();
  cmd->add_option("--alpha1", s.mcl.motion.alpha1, "Rotation noise from rotation (rad^2/rad^2)")->capture_default_str();
  cmd->add_option("--alpha2", s.mcl.motion.alpha2, "Rotation noise from translation (rad^2/m^2)")
      ->capture_default_str();
  cmd->add_option("--alpha3", s.mcl.motion.alpha3, "Translation noise from translation (m^2/m^2)")
      ->capture_default_str();
  cmd->add_option("--alpha4", s.mcl.motion.alpha4, "Translation noise from rotation (m^2/rad^2)")
      ->capture_default_str();
  cmd->add_option("--update-min-d", s.mcl.update_min_d_m, "Sensor update after this much travel (m)")
      ->capture_default_str();
  cmd->add_option("--update-min-a", s.mcl.update_min_a_rad, "Sensor update after this much rotation (rad)")
      ->capture_default_str();
  cmd->add_option("--resample-ess", s.mcl.resample_ess_fraction,
                  "Resample when ESS < F * particles (unitless fraction in (0, 1])")
      ->capture_default_str();
  cmd->add_option("--hypothesis-floor", s.mcl.hypothesis_floor.min_particles,
                  "Hypothesis-preserving resampling: a cluster of particles (1 m x 1 m x 30 deg bins, joined "
                  "when they touch) whose posterior mass is within --hypothesis-window of the heaviest keeps at "
                  "least this many particles, weighted so the belief is unchanged (count, 0 to --particles / 2; "
                  "0 = plain systematic resampling; by default at most --particles / 2)")
      ->each([cli](const std::string&) { cli->given.hypothesis_floor = true; })
      ->capture_default_str();
  cmd->add_option("--max-particles", s.mcl.max_particle_count,
                  "With --hypothesis-floor: while rivals are alive a resampling draws up to this many particles, "
                  "twice the floor per live hypothesis, so that every rival keeps its floor; the set shrinks "
                  "back to --particles as they fall out of the window (count; 0 = --particles, fixed size; by "
                  "default 0 without a floor)")
      ->each([cli](const std::string&) { cli->given.max_particles = true; })
      ->capture_default_str();
  cmd->add_option("--hypothesis-window", s.mcl.hypothesis_floor.window_nats,
                  "How far a kept hypothesis may trail the heaviest, as a log posterior ratio (nats); while a "
                  "second hypothesis is that close, the filter does not claim convergence. With amcl-cube "
                  "(--lf-combine or --beam-combine) the ratio is of the cube sum's weights, a far smaller scale (6 in "
                  "the cautious recipe, docs/real_logs_cautious_recipe.md)")
      ->capture_default_str();
  cmd->add_option("--recovery-alpha-slow", s.mcl.alpha_slow,
                  "Augmented MCL slow average rate (1/sensor update; 0 = no recovery)")
      ->capture_default_str();
  cmd->add_option("--recovery-alpha-fast", s.mcl.alpha_fast, "Augmented MCL fast average rate (1/sensor update)")
      ->capture_default_str();
  cmd->add_option(
         "--injection-check", s.mcl.injection_check_updates,
         "A random particle is injected only if it explains the scans of the last N sensor updates "
         "(replayed through the odometry) better than the particle it would replace (updates; 0 = augmented MCL as "
         "published)")
      ->capture_default_str();
  cmd->add_option("--initial-pose", cli->initial_pose,
                  "Track from X,Y,THETA (m, m, rad) instead of global localization; X,Y on the map")
      ->check(Finite())
      ->expected(3)
      ->delimiter(',');
  cmd->add_option("--initial-sigma-xy", s.initial_sigma_xy_m, "Tracking start spread (m)")->capture_default_str();
  cmd->add_option("--initial-sigma-theta", s.initial_sigma_theta_rad, "Tracking start spread (rad)")
      ->capture_default_str();
  cmd->add_option("--threads", cli->threads, "Worker threads (count; 0 = all cores); results do not depend on it")
      ->capture_default_str();
  cmd->add_option("--timeline", cli->timeline_path, "Write the per-record timeline CSV here");
  cmd->add_option("--summary", cli->summary_path, "Write the run summary JSON here");
  cmd->add_flag("--quiet", cli->quiet, "No progress bar");
  AddSchedulerOptions(*cmd, cli->scheduler, "nodes per ray");
  cmd->add_option("--engine", cli->engine,
                  "ours | mrpt: MRPT's CMonteCarloLocalization2D with our settings mapped onto its own "
                  "(workloads/delibot/mrpt/mrpt_localizer.h); no backend pricing")
      ->capture_default_str();
  cmd->footer(ExitCodeFooter(""));
  cmd->callback([cli] { Run(*cli); });
}

}  // namespace rc
