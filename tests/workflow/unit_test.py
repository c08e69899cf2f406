#!/usr/bin/python3
"""Unit tests of the study engine's pieces (scripts/workflow/): the
configuration's expansion and its errors, every study shipped in
scripts/workflow/studies/, the option-unit column names, the metric
flattening, and the merge of point records (tidy table, failed points,
per-point tables concatenated).
Usage: unit_test.py [PATH_TO_RCBENCH]   (with rcbench: the units its --help states)
"""
import glob
import json
import os
import shutil
import sys
import tempfile
import unittest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "scripts", "workflow"))
import merge  # noqa: E402
import option_units  # noqa: E402
import point_metrics  # noqa: E402
from study_config import Study, StudyError, command_line, load_yaml  # noqa: E402

RCBENCH = sys.argv.pop(1) if len(sys.argv) > 1 else None


def base(**over):
    config = {
        "study": "t", "out": "/tmp/out_t", "rcbench": "/bin/rcbench",
        "inputs": {"office": {"command": "make-map", "files": {"output": "office.yaml"}},
                   "trace": {"command": "simulate", "options": {"map": "{map}", "seed": "{seed}"},
                             "files": {"output": "t.log", "ground-truth": "t.gt"}}},
        "points": {"workload": "delibot",
                   "options": {"trace": "{trace.output}", "ground-truth": "{trace.ground-truth}", "quiet": True},
                   "grid": {"map": {"office": "{office.output}", "wean": "/data/wean.dat"},
                            "seed": {"range": [1, 3]},
                            "mode": {"global": {"particles": 5000},
                                     "tracking": {"particles": 500,
                                                  "initial-pose": {"first_pose": "{trace.ground-truth}"}}}}},
    }
    config.update(over)
    return config


class Expansion(unittest.TestCase):
    def test_grid_is_the_cross_product(self):
        s = Study(base())
        self.assertEqual(len(s.points), 2 * 3 * 2)
        self.assertEqual(len(s.order), len(set(s.order)))

    def test_one_input_instance_per_combination_of_the_axes_it_uses(self):
        s = Study(base())
        traces = [i for i in s.inputs.values() if i["name"] == "trace"]
        offices = [i for i in s.inputs.values() if i["name"] == "office"]
        self.assertEqual(len(traces), 2 * 3)   # map x seed, shared by both modes
        self.assertEqual(len(offices), 1)
        office_trace = next(t for t in traces if t["axes"]["seed"] == 2 and "office" in t["id"])
        self.assertEqual(office_trace["options"]["map"], offices[0]["files"]["output"])
        self.assertEqual(office_trace["depends"], [offices[0]["id"]])

    def test_points_name_their_inputs_and_labels(self):
        s = Study(base())
        p = next(p for p in s.points.values() if p["labels"] == {"map_label": "wean", "mode": "tracking"}
                 and p["options"]["seed"] == 3)
        self.assertEqual(p["options"]["map"], "/data/wean.dat")
        self.assertEqual(p["options"]["particles"], 500)
        self.assertEqual(p["options"]["initial-pose"], {"first_pose": p["options"]["ground-truth"]})
        self.assertTrue(p["options"]["trace"].startswith("/tmp/out_t/inputs/trace-"))
        self.assertEqual(len(p["depends"]), 1)
        self.assertEqual(p["options"]["threads"], 1)   # delibot gets the point's core count
        self.assertTrue(p["outputs"]["summary"].endswith(f"points/{p['id']}/summary.json"))

    def test_ids_do_not_depend_on_order_or_location(self):
        a = Study(base())
        config = base(out="/elsewhere/out")
        grid = config["points"]["grid"]
        config["points"]["grid"] = {k: grid[k] for k in reversed(list(grid))}
        config["points"]["grid"]["seed"] = {"range": [1, 3]}
        b = Study(config)
        self.assertEqual(sorted(a.points), sorted(b.points))

    def test_a_changed_option_is_a_new_point(self):
        a = Study(base())
        config = base()
        config["points"]["options"]["beam-step"] = 3
        b = Study(config)
        self.assertFalse(set(a.points) & set(b.points))

    def test_a_config_override_merged_by_snakemake(self):
        # `--config 'points={options: {hypothesis-floor: 20}, grid: {seed: {range: [1, 2]}}}'`:
        # Snakemake parses the value with YAML's BaseLoader (strings only) and
        # merges it key by key into the file's configuration.
        from snakemake.utils import update_config
        import yaml
        config = base()
        update_config(config, {"study": "t_floor",
                               "points": yaml.load("{options: {hypothesis-floor: 20}, grid: {seed: {range: [1, 2]}}}",
                                                   Loader=yaml.BaseLoader)})
        s = Study(config)
        self.assertEqual(len(s.points), 2 * 2 * 2)
        self.assertEqual({p["options"]["seed"] for p in s.points.values()}, {1, 2})
        self.assertTrue(all(p["options"]["hypothesis-floor"] == "20" for p in s.points.values()))
        self.assertTrue(all(p["options"]["quiet"] is True for p in s.points.values()))  # the file's options stay
        self.assertFalse(set(s.points) & set(Study(base()).points))  # new options: new points
        update_config(config, {"points": yaml.load("{options: {claim-audit: true}}", Loader=yaml.BaseLoader)})
        flagged = Study(config).points.values()
        self.assertTrue(all(p["options"]["claim-audit"] is True for p in flagged))  # "true": a flag
        self.assertTrue(all("--claim-audit" in command_line(p) and "true" not in command_line(p) for p in flagged))
        variant = base()
        update_config(variant, {"points": yaml.load("{grid: {mode: {global: {particles: 5000, quiet: false}}}}",
                                                    Loader=yaml.BaseLoader)})
        in_global = [p for p in Study(variant).points.values() if p["labels"]["mode"] == "global"]
        self.assertTrue(in_global and all(p["options"]["quiet"] is False for p in in_global))  # a variant too
        update_config(config, {"points": yaml.load("{options: {quiet: null}}", Loader=yaml.BaseLoader)})
        self.assertTrue(all("quiet" not in p["options"] for p in Study(config).points.values()))  # null: left out
        without = base()
        del without["points"]["options"]["quiet"]
        nulled = base()
        nulled["points"]["options"]["quiet"] = None
        self.assertEqual(sorted(Study(without).points), sorted(Study(nulled).points))  # and not in the id
        config["points"]["grid"]["seed"] = {"range": ["1", "x"]}
        with self.assertRaisesRegex(StudyError, "range"):
            Study(config)

    def test_list_and_groups(self):
        config = base(points=[{"name": "a", "workload": "movebot", "list": [{"seed": 1}, {"seed": 2, "nn": "p-ray"}]},
                              {"name": "b", "workload": "carribot", "options": {"map": "m.map"},
                               "grid": {"weight": [1, 2]}, "outputs": {"plot": "path.png"}}])
        s = Study(config)
        self.assertEqual(len(s.points), 4)
        movebot = [p for p in s.points.values() if p["workload"] == "movebot"]
        self.assertEqual(movebot[0]["ok_exit_codes"], [0, 3])  # 3: no exact path, outputs written
        self.assertNotIn("threads", movebot[0]["options"])
        carribot = next(p for p in s.points.values() if p["workload"] == "carribot")
        self.assertTrue(carribot["outputs"]["plot"].endswith("path.png"))

    def test_group_vars_reach_templates_but_not_the_command(self):
        config = base()
        config["inputs"]["trace"]["options"] = {"map": "/m.yaml", "seed": "{traceseed}"}
        config["points"] = [{"name": g, "workload": "delibot", "vars": {"traceseed": k},
                             "options": {"trace": "{trace.output}"}, "grid": {"seed": [1, 2]}}
                            for g, k in (("a", 7), ("b", 8))]
        s = Study(config)
        self.assertEqual(sorted(i["options"]["seed"] for i in s.inputs.values()), ["7", "8"])
        for p in s.points.values():
            self.assertNotIn("traceseed", p["options"])

    def test_command_line(self):
        spec = {"rcbench": "rc", "workload": "delibot", "options": {"quiet": True, "no-pricing": False,
                                                                    "particles": 10, "x": None},
                "outputs": {"summary": "s.json"}}
        self.assertEqual(command_line(spec), ["rc", "delibot", "--quiet", "--particles", "10", "--summary", "s.json"])


class Errors(unittest.TestCase):
    def assertStudyError(self, config, *fragments):
        with self.assertRaises(StudyError) as e:
            Study(config)
        for f in fragments:
            self.assertIn(f, str(e.exception))

    def test_unknown_keys(self):
        self.assertStudyError(base(sweep=1), "unknown top-level key", "sweep")
        config = base()
        config["points"]["gird"] = {}
        self.assertStudyError(config, "unknown key", "gird")

    def test_bad_templates(self):
        config = base()
        config["points"]["options"]["trace"] = "{nosuch.output}"
        self.assertStudyError(config, "option 'trace'", "nosuch")
        config = base()
        config["points"]["options"]["trace"] = "{trace.nofile}"
        self.assertStudyError(config, "no file 'nofile'")
        config = base()
        config["points"]["options"]["x"] = "{undefined}"
        self.assertStudyError(config, "'{undefined}'", "neither an axis")

    def test_bad_values(self):
        config = base()
        config["points"]["grid"]["seed"] = {"range": [3, 1]}
        self.assertStudyError(config, "range")
        config = base()
        config["points"]["grid"]["seed"] = []
        self.assertStudyError(config, "no values")
        self.assertStudyError(base(study="a b"), "'study'")
        config = base()
        config["points"]["options"]["summary"] = "mine.json"
        self.assertStudyError(config, "'summary' is an output")

    def test_an_input_cannot_depend_on_itself(self):
        config = base()
        config["inputs"]["office"]["options"] = {"x": "{office.output}"}
        self.assertStudyError(config, "depends on itself")


class ShippedStudies(unittest.TestCase):
    def test_every_study_expands(self):
        paths = sorted(glob.glob(os.path.join(REPO, "scripts", "workflow", "studies", "*.yaml")))
        self.assertGreaterEqual(len(paths), 6)
        for path in paths:
            with self.subTest(path=os.path.basename(path)):
                s = Study(load_yaml(path))
                self.assertEqual(s.name, os.path.splitext(os.path.basename(path))[0])
                self.assertGreater(len(s.points), 0)
                for script in s.analysis:
                    self.assertTrue(os.path.isfile(os.path.join(REPO, "scripts", script)), script)


HELP = """Options:
  -h,--help                   Print this help message and exit
  --map TEXT REQUIRED         Map file
  --particles UINT [2000]     Particle count (count)
  --initial-sigma-xy FLOAT [0.25]
                              Spread of the initial particles (m) around
                              --initial-pose
  --hypothesis-window FLOAT [6]
                              Window (nats; 0 = off)
  --resolution,--map-resolution FLOAT
                              Cell size (m) for MovingAI maps
"""


class Units(unittest.TestCase):
    def test_parse_help(self):
        units = option_units.parse_help(HELP)
        self.assertEqual(units["particles"], "")
        self.assertEqual(units["initial-sigma-xy"], "m")
        self.assertEqual(units["hypothesis-window"], "nats")
        self.assertEqual(units["map"], "")
        self.assertEqual(units["map-resolution"], "m")

    @unittest.skipIf(RCBENCH is None, "no rcbench given")
    def test_units_from_rcbench(self):
        u = option_units.OptionUnits(RCBENCH)
        self.assertEqual(u.column("delibot", "initial-sigma-xy"), "initial_sigma_xy_m")
        self.assertEqual(u.column("delibot", "particles"), "particles")
        self.assertEqual(u.column("delibot", "map"), "map")
        self.assertEqual(u.column("movebot", "time"), "time_s")


class Metrics(unittest.TestCase):
    def test_flatten(self):
        flat = point_metrics.flatten({"a": {"b_m": 1.5, "c": {"d": True}}, "e": [1, 2], "f": [{"g": 1}]})
        self.assertEqual(flat, {"a.b_m": 1.5, "a.c.d": 1, "e": "1;2", "f": '[{"g": 1}]'})


class Merge(unittest.TestCase):
    """Point records written by hand (as run_point.py writes them), merged."""

    def setUp(self):
        self.work = tempfile.mkdtemp(prefix="rc_merge_test_")

    def tearDown(self):
        shutil.rmtree(self.work)

    def test_tidy_table_with_a_failed_point_and_per_point_tables(self):
        config = {"study": "m", "out": self.work, "rcbench": "/nonexistent/rcbench",
                  "points": {"workload": "collide", "options": {"scene": "shelf"},
                             "grid": {"traversal": ["dfs", "bfs"], "variant": {"a": {}, "b": {"epsilon": 0.1}}}},
                  "tables": ["extra.csv"]}
        study = Study(config)
        for k, pid in enumerate(study.order):
            spec = study.points[pid]
            os.makedirs(spec["folder"])
            failed = k == 1
            record = {**spec, "status": "failed" if failed else "ok", "exit_code": 1 if failed else 0,
                      "error": "exit 1: rcbench: error: x" if failed else "", "wall_s": 0.5, "host": "h",
                      "started_utc": "t", "rcbench_sha256": "s", "slurm_job_id": ""}
            with open(spec["record"], "w") as f:
                json.dump(record, f)
            if not failed:
                with open(spec["outputs"]["timeline"], "w") as f:
                    f.write(f"section,key,value\nsummary,queries,{10 + k}\nsummary,backend,robocore\n")
                with open(os.path.join(spec["folder"], "extra.csv"), "w") as f:
                    f.write(f"ratio,value\nr1,{k}\nr2,{k + 0.5}\n")
        table = merge.merge_study(study, study.merged_csv())
        self.assertEqual(list(table["point"]), study.order)
        self.assertEqual(list(table["status"]), ["ok", "failed", "ok", "ok"])
        self.assertEqual(list(table["summary.queries"].fillna(-1)), [10, -1, 12, 13])
        self.assertEqual(table["error"].iloc[1], "exit 1: rcbench: error: x")
        self.assertEqual(list(table["traversal"]), ["dfs", "dfs", "bfs", "bfs"])
        self.assertEqual(list(table["variant"]), ["a", "b", "a", "b"])
        import pandas as pd
        extra = pd.read_csv(os.path.join(self.work, "m_extra.csv"))
        self.assertEqual(len(extra), 6)   # two rows from each of the three ok points
        self.assertEqual(list(extra.columns[:3]), ["point", "group", "workload"])
        self.assertIn("traversal", extra.columns)
        self.assertEqual(list(extra["value"]), [0, 0.5, 2, 2.5, 3, 3.5])


class SensitivityAnalysis(unittest.TestCase):
    """scripts/sensitivity_study.py on one point's sweep: the ranges, and a
    flip exactly where a variant crosses 1x."""

    def test_ranges_and_flips(self):
        import subprocess
        import pandas as pd
        work = tempfile.mkdtemp(prefix="rc_sensitivity_test_")
        self.addCleanup(shutil.rmtree, work)
        folder = os.path.join(work, "p1")
        os.makedirs(folder)
        with open(os.path.join(folder, "calibration.csv"), "w") as f:
            f.write("result,unit,paper_value,ours\nA vs B,x faster,1.1,1.5\nC vs D,x faster,2,3\nE,cycles,,7\n")
        with open(os.path.join(folder, "sensitivity.csv"), "w") as f:
            f.write("ratio,parameter,value,result\nA vs B,,,1.5\nC vs D,,,3\nE,,,7\n"
                    "A vs B,p.x,0.5,0.8\nA vs B,p.x,2,2.5\nA vs B,p.y,0.5,1.4\nA vs B,p.y,2,\n"
                    "C vs D,p.x,0.5,2\nC vs D,p.x,2,4\nE,p.x,0.5,3\n")
        merged = os.path.join(work, "m.csv")
        pd.DataFrame([{"point": "p1", "group": "g", "workload": "calibrate", "status": "ok", "folder": folder,
                       "particles": 500}]).to_csv(merged, index=False)
        out = os.path.join(work, "analysis")
        script = os.path.join(REPO, "scripts", "sensitivity_study.py")
        p = subprocess.run([sys.executable, script, merged, out], capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stderr)
        ranges = pd.read_csv(os.path.join(out, "sensitivity_ranges.csv"))
        self.assertEqual(sorted(zip(ranges["result"], ranges["parameter"])),
                         [("A vs B", "p.x"), ("A vs B", "p.y"), ("C vs D", "p.x")])  # E is not a speedup
        ab = ranges[(ranges["result"] == "A vs B") & (ranges["parameter"] == "p.x")].iloc[0]
        self.assertEqual((ab["low_x"], ab["high_x"], bool(ab["flips"])), (0.8, 2.5, True))
        self.assertFalse(ranges[ranges["parameter"] == "p.y"]["flips"].any())   # 1.4-1.5: same side
        self.assertFalse(ranges[ranges["result"] == "C vs D"]["flips"].any())  # 2-4: same side
        self.assertTrue(os.path.getsize(os.path.join(out, "sensitivity.png")) > 0)
        with open(os.path.join(out, "sensitivity_flips.md")) as f:
            self.assertIn("| A vs B | p.x |", f.read())


def run_analysis(test, work, points, name):
    """Runs scripts/<name>.py on `points` as a merged study table in `work`;
    returns the <name>.md it wrote (the test fails if the script does)."""
    import subprocess
    import pandas as pd
    merged = os.path.join(work, "m.csv")
    pd.DataFrame(points).to_csv(merged, index=False)
    out = os.path.join(work, "analysis")
    p = subprocess.run([sys.executable, os.path.join(REPO, "scripts", name + ".py"), merged, out],
                       capture_output=True, text=True)
    test.assertEqual(p.returncode, 0, p.stderr)
    with open(os.path.join(out, name + ".md")) as f:
        return f.read()


class ClaimAuditAnalysis(unittest.TestCase):
    """scripts/claim_audit_study.py: a claim graded held or wrong from its
    timeline, a run that never claimed, and a held claim the audit lost."""

    def test_claims_graded_and_lost_claims_named(self):
        work = tempfile.mkdtemp(prefix="rc_claim_audit_test_")
        self.addCleanup(shutil.rmtree, work)
        points = []

        def point(name, seed, run, claim, errors, refused, host_s):
            folder = os.path.join(work, f"{name}_{seed}_{run}")
            os.makedirs(folder)
            with open(os.path.join(folder, "timeline.csv"), "w") as f:
                f.write("iteration,err_xy_m\n" + "".join(f"{i},{e}\n" for i, e in enumerate(errors)))
            points.append({"point": os.path.basename(folder), "group": "g", "workload": "delibot", "status": "ok",
                           "folder": folder, "map_label": name, "seed": seed, "run": run,
                           "accuracy.convergence_iteration_without_ground_truth": claim,
                           "accuracy.claims_refused_by_audit": refused, "totals.wall_s": host_s})

        # Seed 1: both claim at 2 and hold. Seed 2: the unaudited run claims at 0 a
        # place 5 m off (wrong); the audit never claims. Seed 3: the
        # unaudited claim holds, the audit's comes at 8 with only 1 of 2
        # records within 1 m (wrong), so that held claim is lost.
        near, far = [0.1] * 10, [5.0] * 10
        point("maze", 1, "unaudited", 2, near, 0, 10.0)
        point("maze", 1, "audit", 2, near, 0, 12.0)
        point("maze", 2, "unaudited", 0, far, 0, 20.0)
        point("maze", 2, "audit", -1, far, 7, 60.0)
        point("maze", 3, "unaudited", 1, near, 0, 30.0)
        point("maze", 3, "audit", 8, near[:8] + [0.1, 3.0], 2, 40.0)
        md = run_analysis(self, work, points, "claim_audit_study")
        self.assertIn("| maze | unaudited | 3 | 3 / 2 / 1 / 0 | 0, 1, 2 | 0 | 20.0 |", md)
        self.assertIn("| maze | audit | 3 | 2 / 1 / 1 / 1 | 2, 8 | 9 | 40.0 |", md)
        self.assertIn("Held claims lost with audits: maze seed 3 (claim at record 1 without audits).", md)
        with open(os.path.join(work, "analysis", "claim_audit_study.csv")) as f:
            self.assertEqual(len(f.read().splitlines()), 1 + 6)  # a header, a row per point


class AccuracyAnalysis(unittest.TestCase):
    """scripts/accuracy_study.py: global localization's own claims counted as
    made / held / wrong / never, with the median claim record."""

    def test_claims_made_held_wrong_never(self):
        work = tempfile.mkdtemp(prefix="rc_accuracy_test_")
        self.addCleanup(shutil.rmtree, work)
        points = []

        def point(seed, mode, claim, errors):
            folder = os.path.join(work, f"{seed}_{mode}")
            os.makedirs(folder)
            with open(os.path.join(folder, "timeline.csv"), "w") as f:
                f.write("iteration,err_xy_m\n" + "".join(f"{i},{e}\n" for i, e in enumerate(errors)))
            points.append({"point": os.path.basename(folder), "status": "ok", "folder": folder, "map_label": "m",
                           "mode": mode, "seed": seed, "accuracy.convergence_iteration": 0,
                           "accuracy.converged_at_end": True, "accuracy.median_err_xy_m": errors[-1],
                           "accuracy.final_err_xy_m": errors[-1], "accuracy.jumps_after_convergence": 0,
                           "totals.wall_per_update_s": 0.01,
                           "accuracy.convergence_iteration_without_ground_truth": claim,
                           "accuracy.standing_claim_iteration": claim})

        # Seed 1 claims at 2 and holds, seed 2 claims at 4 a place 5 m off,
        # seed 3 never claims.
        near, far = [0.1] * 10, [5.0] * 10
        for seed, claim, errors in ((1, 2, near), (2, 4, far), (3, -1, near)):
            point(seed, "global", claim, errors)
            point(seed, "tracking", -1, near)
        md = run_analysis(self, work, points, "accuracy_study")
        self.assertIn("| 2 / 1 / 1 / 1 | 3.0 | 1/3 |", md)


class MoveBotCostAnalysis(unittest.TestCase):
    """scripts/movebot_cost_study.py: the distribution per budget and
    structure, and the seeds where the structures disagree (a cost apart,
    or one exact where another is not); a failed point's seed is not
    compared."""

    def test_distribution_and_disagreements(self):
        work = tempfile.mkdtemp(prefix="rc_movebot_cost_test_")
        self.addCleanup(shutil.rmtree, work)
        points = []

        def point(iterations, nn, seed, exact, cost, status="ok"):
            points.append({"point": f"{iterations}_{nn}_{seed}", "status": status, "folder": work,
                           "workload": "movebot", "iterations": iterations, "nn": nn, "seed": seed,
                           "result.exact_path": exact, "anytime.best_cost_rad": cost})

        for nn in ("gnat", "p-ray", "p-sphere"):
            point(2000, nn, 1, 0, 11.0)                                   # no exact path anywhere: agree
            point(2000, nn, 2, 1, 9.0 + (1e-6 if nn == "p-ray" else 0))  # p-ray's cost apart
            point(2000, nn, 3, 1 if nn != "gnat" else 0, 8.0)             # gnat not exact
            point(5000, nn, 1, 1, 7.5, status="failed" if nn == "gnat" else "ok")
            point(5000, nn, 2, 1, 7.0)
            point(5000, nn, 3, 1, 8.0)
        md = run_analysis(self, work, points, "movebot_cost_study")
        self.assertIn("| 2000 | p-ray | 2/3 | 8.0 | 8.25 | 8.5 | 8.75 | 9.0 |", md)
        self.assertIn("| 2000 | gnat | 1/3 | 9.0 | 9.0 | 9.0 | 9.0 | 9.0 |", md)
        self.assertIn("| 5000 | gnat | 2/2 |", md)
        self.assertIn("- 2000 iterations: structures disagree on 2 of 3 seeds (2, 3)", md)
        self.assertIn("- 5000 iterations: structures disagree on 0 of 2 seeds (none)", md)


if __name__ == "__main__":
    unittest.main(verbosity=1)
