#!/usr/bin/python3
"""A 4-point study runs through Slurm: a single-node cluster on this machine
(local_slurm.py: munged, slurmctld, slurmd, loopback only), the study's
Slurm profile (scripts/workflow/profiles/slurm, Snakemake's built-in Slurm
support), every point one sbatch job. Checks that each point ran as a Slurm
job, and the merged CSV. The daemons are stopped on exit, whatever happened.
Skips, saying why, when the cluster cannot start (no slurm-wlm or munge, not
root, a daemon that exits).
Usage: slurm_test.py PATH_TO_RCBENCH
"""
import glob
import os
import re
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_test_support as sts  # noqa: E402
from local_slurm import LocalSlurm, SlurmUnavailable  # noqa: E402

POINTS = 4
STUDY_TIMEOUT_S = 240


def main():
    rcbench = sts.rcbench_from_argv()
    sts.require_engine()
    import pandas as pd
    checks = sts.Checks()
    work = sts.scratch("rc_slurm_")
    config = sts.tiny_study(work, rcbench, name="onslurm", grid={"particles": [200, 300], "seed": [1, 2]})
    out = os.path.join(work, "onslurm")
    try:
        with LocalSlurm(work) as cluster:
            cmd = sts.snakemake_command(config, cores=None, profile=sts.SLURM_PROFILE,
                                        extra=["--default-resources", "runtime=10", "mem_mb=200",
                                               "--latency-wait", "5"])
            result = sts.run(cmd, cwd=work, timeout=STUDY_TIMEOUT_S, env=cluster.env)
            log = result.stdout
    except SlurmUnavailable as e:
        shutil.rmtree(work, ignore_errors=True)
        sts.skip(f"a local Slurm cluster cannot start here: {e}")
    checks.check(result.returncode == 0, f"the study ran through Slurm (exit {result.returncode})")
    submitted = re.findall(r"has been submitted with SLURM jobid (\d+)", log)
    checks.check(len(submitted) == POINTS + 2,
                 f"{len(submitted)} Slurm jobs submitted (expected {POINTS} points + 2 generated inputs)")
    slurm_logs = glob.glob(os.path.join(work, ".snakemake", "slurm_logs", "rule_point", "*.log"))
    checks.check(len(slurm_logs) == POINTS, f"{len(slurm_logs)} Slurm job logs of the point rule (expected {POINTS})")
    merged = os.path.join(out, "onslurm.csv")
    if checks.check(os.path.exists(merged), "merged CSV written"):
        table = pd.read_csv(merged)
        checks.check(len(table) == POINTS, f"merged CSV has {len(table)} rows (expected {POINTS})")
        checks.check((table["status"] == "ok").all(), "every point ok")
        checks.check(table["accuracy.median_err_xy_m"].notna().all(), "every point has its metrics")
        checks.check(sorted(table["particles"]) == [200, 200, 300, 300], "the grid's particle counts")
        jobs = set(str(int(j)) for j in table["slurm_job_id"].dropna())
        checks.check(len(jobs) == POINTS and jobs <= set(submitted),
                     f"each point ran inside its own Slurm job (SLURM_JOB_ID {sorted(jobs)})")
    checks.check(os.path.exists(os.path.join(out, "report.html")), "report written")
    if checks.failures:
        print(log[-6000:])
        print(f"kept {work}")
    else:
        shutil.rmtree(work)
    checks.exit()


if __name__ == "__main__":
    main()
