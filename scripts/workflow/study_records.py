"""The records a study leaves behind, and what the engine does with them
between the points and the report: forgetting failed runs on request,
running the study's analysis scripts, and the final verdict.

Run by the Snakefile as: study_records.py analysis|verdict OUT/study_config.json

A point's record is <out>/points/<id>/point.json (run_point.py); an input's
is <out>/inputs/<id>/input.json; point.done and input.done beside them are
the files Snakemake tracks. The analysis step writes
<out>/analysis/analysis.json: per script, its command, exit code, the files
it wrote, and its stderr when it failed.
"""
import json
import os
import subprocess
import sys


def read_record(path):
    with open(path) as f:
        return json.load(f)


def downstream_outputs(study):
    """What the engine makes from the point records: the merged CSV, the analysis, the report, the verdict."""
    return [study.merged_csv(), os.path.join(study.out, "analysis", "analysis.json"),
            os.path.join(study.out, "report.html"), os.path.join(study.out, "study.ok")]


def forget_failed(study):
    """Removes the records of failed points and inputs (retry_failed=true), so they run again,
    and what was made from them: Snakemake does not remake a missing record whose
    merged table is up to date."""
    removed = []
    records = ([(study.point_record(p), study.point_done(p)) for p in study.order]
               + [(study.input_record(i), study.input_done(i)) for i in study.inputs])
    for record, done in records:
        try:
            if read_record(record).get("status") != "failed":
                continue
        except (OSError, ValueError):
            continue
        for path in (record, done):
            if os.path.exists(path):
                os.remove(path)
        removed.append(record)
    if removed:
        for path in downstream_outputs(study):
            if os.path.exists(path):
                os.remove(path)
    return removed


def run_analysis(study, scripts_dir, python, merged_csv, out_dir):
    """Runs each analysis script as `SCRIPT MERGED_CSV OUT_DIR`. A failing script
    is recorded (the verdict fails the study) and the others still run."""
    os.makedirs(out_dir, exist_ok=True)
    for name in os.listdir(out_dir):
        path = os.path.join(out_dir, name)
        if os.path.isfile(path):
            os.remove(path)
    results = []
    for script in study.analysis:
        path = script if os.path.isabs(script) else os.path.join(scripts_dir, script)
        cmd = [python, path, merged_csv, out_dir]
        before = set(os.listdir(out_dir))
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        written = sorted(set(os.listdir(out_dir)) - before)
        results.append({"script": script, "command": cmd, "exit_code": proc.returncode, "files": written,
                        "stdout": proc.stdout[-20000:], "stderr": proc.stderr[-20000:]})
        print(f"analysis {script}: exit {proc.returncode}, wrote {', '.join(written) or 'nothing'}",
              file=sys.stderr)
        if proc.returncode != 0:
            sys.stderr.write(proc.stderr[-4000:])
    tmp = os.path.join(out_dir, ".analysis.json.tmp")
    with open(tmp, "w") as f:
        json.dump({"scripts": results}, f, indent=1)
    os.replace(tmp, os.path.join(out_dir, "analysis.json"))


def verdict(study, merged_csv, analysis_json, ok_path):
    """Writes ok_path when every point and analysis script succeeded; otherwise
    raises with the list of failures (Snakemake then exits nonzero, after
    every other job has finished)."""
    import pandas as pd
    table = pd.read_csv(merged_csv)
    failed = table[table["status"] != "ok"]
    problems = [f"point {r.point}: {r.error}" for r in failed.itertuples()]
    with open(analysis_json) as f:
        for s in json.load(f)["scripts"]:
            if s["exit_code"] != 0:
                last = (s["stderr"].strip().splitlines() or ["(no stderr)"])[-1]
                problems.append(f"analysis {s['script']}: exit {s['exit_code']}: {last}")
    if problems:
        shown = problems[:20] + ([f"... and {len(problems) - 20} more"] if len(problems) > 20 else [])
        raise RuntimeError(f"study '{study.name}': {len(failed)} of {len(table)} point(s) failed"
                           f"{' and an analysis script failed' if len(problems) > len(failed) else ''}; "
                           f"the merged table {merged_csv} and the report have every point, errors included:\n  "
                           + "\n  ".join(shown))
    with open(ok_path, "w") as f:
        f.write(f"{len(table)} points, all ok\n")


def main():
    usage = "usage: study_records.py analysis|verdict OUT/study_config.json   (the Snakefile runs it)"
    if len(sys.argv) != 3 or sys.argv[1] not in ("analysis", "verdict"):
        sys.exit(usage)
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from study_config import load_snapshot
    study, _ = load_snapshot(sys.argv[2])
    analysis_dir = os.path.join(study.out, "analysis")
    if sys.argv[1] == "analysis":
        scripts_dir = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
        run_analysis(study, scripts_dir, sys.executable, study.merged_csv(), analysis_dir)
        return
    try:
        verdict(study, study.merged_csv(), os.path.join(analysis_dir, "analysis.json"),
                os.path.join(study.out, "study.ok"))
    except RuntimeError as e:
        sys.exit(str(e))


if __name__ == "__main__":
    main()
