#!/usr/bin/python3
"""A 6-point study runs locally, is stopped after 2 points have finished,
and is run again: exactly the 4 missing points run, the 2 finished ones are
not touched, and the merged CSV has 6 rows.

Two ways to stop it, each on a fresh study:
  ctrl-c     SIGINT to the study's whole process group (what a terminal sends);
  power-cut  SIGKILL to the whole group: nothing cleans up; the re-run first
             clears Snakemake's stale lock (`snakemake --unlock`, as
             docs/studies.md says), then resumes.
Usage: resume_test.py PATH_TO_RCBENCH
"""
import os
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_test_support as sts  # noqa: E402

POINTS = 6
STOP_AFTER = 2


def wait_for_records(out, count, proc, timeout_s=240):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if len(sts.point_records(out)) >= count or proc.poll() is not None:
            return
        time.sleep(0.02)


def finish_after_stop(proc, stop_signal, still_running):
    """Waits for the stopped study; (its log, how many stop signals it took).
    A SIGINT was once seen not to stop Snakemake (in a CI run:
    the study ran on to its end); a user then presses Ctrl-C again, and so
    does this, every 2 s. Each SIGINT also interrupts the point then running,
    so no point finishes in between."""
    sent = 1 if still_running else 0
    deadline = time.monotonic() + 120
    while True:
        try:
            # A retried communicate() returns all the output, none lost.
            return proc.communicate(timeout=2)[0] or "", sent
        except subprocess.TimeoutExpired:
            if time.monotonic() > deadline:
                raise
            if stop_signal == signal.SIGINT and proc.poll() is None:
                os.killpg(proc.pid, signal.SIGINT)
                sent += 1


def scenario(checks, rcbench, name, stop_signal):
    failures_before = checks.failures
    work = sts.scratch(f"rc_resume_{name}_")
    config = sts.tiny_study(work, rcbench, name=name, records=120, max_records=100)
    out = os.path.join(work, name)
    # Target the merged table: what this test checks (the report has its own test).
    cmd = sts.snakemake_command(config, cores=1, extra=["merge"])
    proc = subprocess.Popen(cmd, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            start_new_session=True)
    wait_for_records(out, STOP_AFTER, proc)
    still_running = proc.poll() is None
    if still_running:
        os.killpg(proc.pid, signal.SIGSTOP)  # freeze the group: the count below cannot move on
    finished = sts.point_records(out)
    if still_running:
        os.killpg(proc.pid, stop_signal)
        os.killpg(proc.pid, signal.SIGCONT)
    log, signals_sent = finish_after_stop(proc, stop_signal, still_running)
    checks.check(still_running, f"{name}: the study was still running when {STOP_AFTER} points had finished")
    checks.check(len(finished) == STOP_AFTER,
                 f"{name}: {len(finished)} point(s) finished when it was stopped (expected {STOP_AFTER})")
    before = {p: (os.stat(p).st_mtime_ns, sts.read_json(p)["started_utc"]) for p in finished}

    if stop_signal == signal.SIGKILL:
        unlock = sts.run(cmd + ["--unlock"], cwd=work)
        checks.check(unlock.returncode == 0,
                     f"{name}: snakemake --unlock after the power cut (exit {unlock.returncode})")
    # Snakemake plans a job for every point it did not see finish. A point whose
    # record was written just before the stop can be among them: its job reuses
    # the record (run_point.py: "not run again") and runs no rcbench.
    dry = sts.run(cmd + ["--dry-run", "--quiet"], cwd=work)
    planned = [line.split() for line in dry.stdout.splitlines() if line.strip().startswith("point ")]
    planned_points = int(planned[0][1]) if planned else 0
    missing = POINTS - len(finished)
    if signals_sent > 1:
        print(f"{name}: the study needed {signals_sent} SIGINTs to stop")
    if not checks.check(missing <= planned_points <= POINTS,
                        f"{name}: the re-run plans {planned_points} point job(s) ({missing} missing, "
                        f"{planned_points - missing} finished but not seen finishing by Snakemake)"):
        print(f"{name}: the stopped study's log, last 3000 characters:\n{log[-3000:]}")

    rerun_start_ns = time.time_ns()
    rerun = sts.run(cmd, cwd=work)
    checks.check(rerun.returncode == 0, f"{name}: the re-run succeeded (exit {rerun.returncode})")
    if rerun.returncode != 0:
        print(log[-3000:], rerun.stdout[-3000:])
    records = sts.point_records(out)
    fresh = [p for p in records if os.stat(p).st_mtime_ns >= rerun_start_ns]
    untouched = all(os.stat(p).st_mtime_ns == before[p][0] and sts.read_json(p)["started_utc"] == before[p][1]
                    for p in before)
    checks.check(len(records) == POINTS, f"{name}: {len(records)} point records after the re-run (expected {POINTS})")
    checks.check(len(fresh) == POINTS - len(finished),
                 f"{name}: {len(fresh)} point(s) ran in the re-run (expected exactly the "
                 f"{POINTS - len(finished)} missing)")
    checks.check(untouched, f"{name}: the {len(before)} points finished before the stop were not run again")
    checks.check(set(fresh).isdisjoint(before), f"{name}: no point ran twice")
    reused = rerun.stdout.count("not run again)")
    checks.check(reused == planned_points - missing,
                 f"{name}: {reused} planned job(s) reused a record written before the stop "
                 f"(expected {planned_points - missing})")
    import pandas as pd
    merged = os.path.join(out, f"{name}.csv")
    if checks.check(os.path.exists(merged), f"{name}: merged CSV written"):
        table = pd.read_csv(merged)
        checks.check(len(table) == POINTS, f"{name}: merged CSV has {len(table)} rows (expected {POINTS})")
        checks.check((table["status"] == "ok").all(), f"{name}: every point ok")
        checks.check(table["point"].nunique() == POINTS, f"{name}: one row per point")
    again = sts.run(cmd + ["--dry-run", "--quiet"], cwd=work)
    checks.check("Nothing to be done" in again.stdout or "point" not in again.stdout,
                 f"{name}: a third run has nothing to do")
    if checks.failures == failures_before:
        shutil.rmtree(work)
    else:
        print(f"{name}: kept {work} for inspection")


def main():
    rcbench = sts.rcbench_from_argv()
    sts.require_engine()
    checks = sts.Checks()
    scenario(checks, rcbench, "ctrl_c", signal.SIGINT)
    scenario(checks, rcbench, "power_cut", signal.SIGKILL)
    checks.exit()


if __name__ == "__main__":
    main()
