#!/usr/bin/python3
"""Runs one study point (or one generated input): a single rcbench command in
its own folder, and records what happened in <folder>/point.json (inputs:
input.json), written last and atomically, so the file exists only for a
finished run. Then it writes <folder>/point.done (input.done), the file
Snakemake tracks. A folder that already holds a record is not run again:
the record is kept and the marker written (a run that finished just before
the study was stopped, before Snakemake saw it finish).

  run_point.py SPEC_JSON            (the Snakefile passes the spec)

The record holds the spec (workload, options, output files), the exact
command, status "ok" or "failed", the exit code, the error (rcbench's own
message where it printed one), the wall time, the host, the Slurm job id
(empty outside Slurm), the start time and the SHA-256 of the rcbench binary. stdout.log and stderr.log keep the run's
output.

A failed run is a result: the record is written and this script exits 0, so
the study goes on and the merged table shows the error. A run interrupted by
SIGINT, SIGTERM, SIGHUP or SIGKILL (Ctrl-C, a cluster's time limit) is not a
result: no record is written and this script exits nonzero, so the next run
of the study runs the point again. A point whose generated input failed is
recorded as failed, naming the input.
"""
import datetime
import hashlib
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from study_config import command_line  # noqa: E402

INTERRUPTIONS = {signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGKILL}


class PointFailure(Exception):
    """The point cannot run; the message is its recorded error."""


def sha256_of(path):
    h = hashlib.sha256()
    try:
        with open(path, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                h.update(block)
    except OSError as e:
        return f"unreadable: {e.strerror}"
    return h.hexdigest()


def first_pose(path):
    """The first pose of a ground-truth file (t x y theta) as rcbench's --initial-pose X,Y,THETA."""
    try:
        with open(path) as f:
            for line_no, line in enumerate(f, 1):
                fields = line.split()
                if not fields or fields[0].startswith("#"):
                    continue
                if len(fields) != 4:
                    raise PointFailure(f"{path}:{line_no}: {len(fields)} fields, expected 4 (t_s x_m y_m theta_rad)")
                try:
                    _, x, y, theta = (float(v) for v in fields)
                except ValueError:
                    raise PointFailure(f"{path}:{line_no}: a field is not a number") from None
                return f"{x!r},{y!r},{theta!r}"
    except OSError as e:
        raise PointFailure(f"{path}: {e.strerror} (needed for first_pose)") from None
    raise PointFailure(f"{path}: no pose (needed for first_pose)")


def resolve_functions(options):
    out = {}
    for k, v in options.items():
        if isinstance(v, dict):
            (fn, arg), = v.items()
            if fn != "first_pose":
                raise PointFailure(f"option '{k}': unknown function '{fn}'")
            out[k] = first_pose(arg)
        else:
            out[k] = v
    return out


def check_inputs(spec):
    """Raises PointFailure if a generated input this run depends on failed."""
    for iid, record in zip(spec.get("depends", []), spec.get("depends_records", [])):
        try:
            with open(record) as f:
                r = json.load(f)
        except (OSError, ValueError) as e:
            raise PointFailure(f"input {iid}: no record {record} ({e})") from None
        if r.get("status") != "ok":
            raise PointFailure(f"input {iid} failed: {r.get('error', '?')}")


def error_message(stderr_text, code):
    lines = [line.strip() for line in stderr_text.splitlines() if line.strip()]
    own = [line for line in lines if line.startswith("rcbench:")]
    text = " | ".join(own[-3:] or lines[-3:])
    return f"exit {code}: {text}" if text else f"exit {code} (no message on stderr)"


def run_forwarding_signals(cmd, out, err):
    """(exit code, whether this script was asked to stop). SIGINT, SIGTERM and
    SIGHUP sent to this script reach rcbench too, so stopping a study never
    leaves an rcbench running."""
    proc = subprocess.Popen(cmd, stdout=out, stderr=err, stdin=subprocess.DEVNULL)
    stopped = []

    def forward(signum, _frame):
        stopped.append(signum)
        proc.send_signal(signum)

    previous = {s: signal.signal(s, forward) for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)}
    try:
        code = proc.wait()
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
    return code, bool(stopped)


def write_json_atomic(path, obj):
    tmp = f"{path}.tmp-{os.getpid()}"
    with open(tmp, "w") as f:
        json.dump(obj, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(tmp, path)


def clean_folder(folder):
    """Removes what an interrupted earlier attempt left, so no stale file is read as this run's."""
    os.makedirs(folder, exist_ok=True)
    for name in os.listdir(folder):
        path = os.path.join(folder, name)
        if os.path.isdir(path) and not os.path.islink(path):
            shutil.rmtree(path)
        else:
            os.remove(path)


def finished_record(path):
    """The record at path if it is a complete one, else None."""
    try:
        with open(path) as f:
            record = json.load(f)
    except (OSError, ValueError):
        return None
    return record if record.get("status") in ("ok", "failed") else None


def mark_done(spec, status):
    with open(spec["done"], "w") as f:
        f.write(status + "\n")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: run_point.py SPEC_JSON")
    spec = json.loads(sys.argv[1])
    folder = spec["folder"]
    record_path = spec["record"]
    earlier = finished_record(record_path)
    if earlier is not None:
        print(f"{spec['id']}: {earlier['status']} (recorded {earlier.get('started_utc', '?')}; not run again)",
              file=sys.stderr)
        mark_done(spec, earlier["status"])
        return 0
    clean_folder(folder)
    record = dict(spec)
    started = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")
    record.update({"host": socket.gethostname(), "slurm_job_id": os.environ.get("SLURM_JOB_ID", ""),
                   "started_utc": started, "rcbench_sha256": sha256_of(spec["rcbench"]),
                   "wall_s": 0.0, "exit_code": None, "error": "", "command": []})
    try:
        check_inputs(spec)
        options = resolve_functions(spec["options"])
        cmd = command_line(spec, options)
        record["command"] = cmd
        record["resolved_options"] = options
        if not (os.path.isfile(spec["rcbench"]) and os.access(spec["rcbench"], os.X_OK)):
            raise PointFailure(f"rcbench not found or not executable at '{spec['rcbench']}'")
        start = time.monotonic()
        with open(os.path.join(folder, "stdout.log"), "w") as out, \
                open(os.path.join(folder, "stderr.log"), "w+") as err:
            code, interrupted = run_forwarding_signals(cmd, out, err)
            err.seek(0)
            stderr_text = err.read()
        record["wall_s"] = round(time.monotonic() - start, 6)
        record["exit_code"] = code
        if interrupted or (code < 0 and -code in INTERRUPTIONS):
            print(f"run_point: {spec['id']} interrupted (rcbench exit {code}); not recorded, it runs again next "
                  f"time", file=sys.stderr)
            return 1
        if code not in spec["ok_exit_codes"]:
            raise PointFailure(error_message(stderr_text, code) if code >= 0 else
                               f"killed by signal {-code} ({signal.Signals(-code).name})")
        record["status"] = "ok"
    except PointFailure as e:
        record["status"] = "failed"
        record["error"] = str(e)
    record["missing_outputs"] = sorted(k for k, p in (spec.get("outputs") or spec.get("files") or {}).items()
                                       if not os.path.exists(p))
    write_json_atomic(record_path, record)
    mark_done(spec, record["status"])
    print(f"{spec['id']}: {record['status']}{' (' + record['error'] + ')' if record['error'] else ''}",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
