"""Shared by the study-engine tests: a tiny DeliBot study in a temporary
folder (a generated map, a short simulated trace, points of a few hundred
particles over a few records), and the Snakemake command that runs it the
way docs/studies.md says, from a scratch working directory."""
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SNAKEFILE = os.path.join(REPO, "scripts", "workflow", "Snakefile")
LOCAL_PROFILE = os.path.join(REPO, "scripts", "workflow", "profiles", "local")
SLURM_PROFILE = os.path.join(REPO, "scripts", "workflow", "profiles", "slurm")


def skip(reason):
    print(f"SKIP: {reason}")
    sys.exit(0)


def require_engine():
    """Skips the test (with the reason) when Snakemake or pandas is not installed."""
    if shutil.which("snakemake") is None:
        skip("snakemake not installed (scripts/setup installs Debian's snakemake)")
    try:
        import pandas  # noqa: F401
    except ImportError:
        skip("python3-pandas not installed (scripts/setup installs it)")


def rcbench_from_argv():
    if len(sys.argv) < 2 or not os.access(sys.argv[1], os.X_OK):
        sys.exit(f"usage: {sys.argv[0]} PATH_TO_RCBENCH")
    return os.path.abspath(sys.argv[1])


def tiny_study(work, rcbench, name="tiny", grid=None, extra_groups=(), records=40, max_records=30, pricing=False):
    """Writes WORK/NAME.yaml and returns its path; the study's outputs go to WORK/NAME."""
    import yaml
    options = {"map": "{office.output}", "trace": "{trace.output}", "ground-truth": "{trace.ground-truth}",
               "initial-pose": {"first_pose": "{trace.ground-truth}"}, "max-records": max_records,
               "beam-step": 6, "quiet": True}
    if not pricing:
        options["no-pricing"] = True
    config = {
        "study": name, "description": f"test study {name}", "rcbench": rcbench, "out": os.path.join(work, name),
        "inputs": {
            "office": {"command": "make-map", "files": {"output": "office.yaml"}},
            "trace": {"command": "simulate", "options": {"map": "{office.output}", "records": records, "seed": 1},
                      "files": {"output": "trace.log", "ground-truth": "trace.gt"}},
        },
        "points": [{"name": "tiny", "workload": "delibot", "options": options,
                    "grid": grid or {"particles": [200, 300, 400], "seed": [1, 2]}}] + list(extra_groups),
    }
    path = os.path.join(work, f"{name}.yaml")
    with open(path, "w") as f:
        yaml.safe_dump(config, f, sort_keys=False)
    return path


def snakemake_command(config_path, cores=1, profile=LOCAL_PROFILE, extra=()):
    cmd = ["snakemake", "--profile", profile, "--snakefile", SNAKEFILE, "--configfile", config_path]
    if cores:
        cmd += ["--cores", str(cores)]
    return cmd + list(extra)


def run(cmd, cwd, timeout=300, env=None):
    return subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=timeout, env=env)


def point_records(out):
    return sorted(glob.glob(os.path.join(out, "points", "*", "point.json")))


def read_json(path):
    with open(path) as f:
        return json.load(f)


def scratch(prefix):
    return tempfile.mkdtemp(prefix=prefix)


class Checks:
    """Collects failed checks, prints them, and gives the exit code."""

    def __init__(self):
        self.failures = 0

    def check(self, condition, message):
        print(("ok   " if condition else "FAIL ") + message)
        if not condition:
            self.failures += 1
        return condition

    def exit(self):
        print(f"{self.failures} failed check(s)" if self.failures else "all checks passed")
        sys.exit(1 if self.failures else 0)
