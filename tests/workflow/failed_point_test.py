#!/usr/bin/python3
"""A point that fails (a map path that does not exist) is in the merged table
with its error, the other points finish, the report is written, and the
study exits nonzero at the end. retry_failed=true runs that point (and only
that point) again.
Usage: failed_point_test.py PATH_TO_RCBENCH
"""
import os
import shutil
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_test_support as sts  # noqa: E402

BAD_MAP = "/nonexistent/rcbench-test/no_such_map.yaml"


def main():
    rcbench = sts.rcbench_from_argv()
    sts.require_engine()
    import pandas as pd
    checks = sts.Checks()
    work = sts.scratch("rc_failed_point_")
    bad_group = {"name": "bad", "workload": "delibot",
                 "options": {"trace": "{trace.output}", "max-records": 5, "quiet": True, "no-pricing": True},
                 "list": [{"map": BAD_MAP, "particles": 100}]}
    config = sts.tiny_study(work, rcbench, name="withfailure", grid={"particles": [100, 200, 300]},
                            extra_groups=[bad_group])
    out = os.path.join(work, "withfailure")
    cmd = sts.snakemake_command(config, cores=2)
    result = sts.run(cmd, cwd=work)
    checks.check(result.returncode != 0, f"the study exits nonzero (exit {result.returncode})")
    checks.check("1 of 4 point(s) failed" in result.stdout, "Snakemake's log names the failure count")
    merged = os.path.join(out, "withfailure.csv")
    if not checks.check(os.path.exists(merged), "merged CSV written despite the failure"):
        print(result.stdout[-4000:])
        checks.exit()
    table = pd.read_csv(merged)
    checks.check(len(table) == 4, f"merged CSV has {len(table)} rows (expected 4: 3 good points and the bad one)")
    bad = table[table["group"] == "bad"]
    good = table[table["group"] != "bad"]
    checks.check(len(bad) == 1 and bad["status"].iloc[0] == "failed", "the bad point's status is 'failed'")
    error = str(bad["error"].iloc[0]) if len(bad) else ""
    checks.check(BAD_MAP in error, f"its error names the missing map: {error!r}")
    checks.check(error.startswith("exit 1:"), "its error gives rcbench's exit code (1: bad input)")
    checks.check(len(good) == 3 and (good["status"] == "ok").all(), "the other three points finished ok")
    checks.check(good["accuracy.median_err_xy_m"].notna().all(), "the good points have their metrics")
    checks.check(bad["accuracy.median_err_xy_m"].isna().all(), "the bad point has no metrics")
    checks.check(os.path.exists(os.path.join(out, "report.html")), "the report is written")
    with open(os.path.join(out, "report.html")) as f:
        checks.check(BAD_MAP in f.read(), "the report lists the failed point with its error")
    checks.check(not os.path.exists(os.path.join(out, "study.ok")), "no study.ok verdict")

    records = {p: os.stat(p).st_mtime_ns for p in sts.point_records(out)}
    again = sts.run(cmd, cwd=work)
    checks.check(again.returncode != 0, "a plain re-run still exits nonzero")
    checks.check(records == {p: os.stat(p).st_mtime_ns for p in sts.point_records(out)},
                 "a plain re-run runs no point again (a failed point is a result)")
    start_ns = time.time_ns()
    retry = sts.run(cmd + ["--config", "retry_failed=true"], cwd=work)
    rerun = [p for p in sts.point_records(out) if os.stat(p).st_mtime_ns >= start_ns]
    checks.check(retry.returncode != 0 and len(rerun) == 1 and "/bad_" in rerun[0],
                 f"retry_failed=true runs the failed point alone again ({len(rerun)} ran)")
    if checks.failures == 0:
        shutil.rmtree(work)
    else:
        print(result.stdout[-4000:])
        print(f"kept {work}")
    checks.exit()


if __name__ == "__main__":
    main()
