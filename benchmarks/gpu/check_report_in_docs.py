#!/usr/bin/python3
"""ctest gpu_check_report_matches_docs: docs/gpu_check.md shows what
report.py makes of the committed files of the GPU check.

  check_report_in_docs.py SOURCE_DIR

Runs benchmarks/gpu/report.py on docs/gpu_check/h100/ (every table) and on
docs/gpu_check/h100_65536/ (the time and ranking tables, which are all the
page shows of that run), and checks that each table row it prints appears,
verbatim, in docs/gpu_check.md. Prints the
rows that do not and exits 1 if there are any.
"""
import os
import subprocess
import sys


def report_rows(source, args):
    out = subprocess.run([sys.executable, os.path.join(source, "benchmarks/gpu/report.py")] + args,
                         check=True, capture_output=True, text=True, cwd=source).stdout
    return [line for line in out.splitlines() if line.startswith("| ") and not line.startswith("|---")]


def main():
    source = sys.argv[1]
    h100, small = "docs/gpu_check/h100/", "docs/gpu_check/h100_65536/"
    rows = report_rows(source, ["--model", h100 + "model.csv", "--measured", h100 + "measured.csv",
                                "--profile", h100 + "profile.csv", "--sact-model", h100 + "sact_model.csv",
                                "--sact-measured", h100 + "sact_measured.csv",
                                "--sact-profile", h100 + "sact_profile.csv"])
    # At 65,536 rays the doc shows the time and ranking tables only: the
    # rows with a "(", which the answers and leaf tables do not have.
    small_rows = [r for r in report_rows(source, ["--model", small + "model.csv", "--measured", small + "measured.csv"])
                  if "x)" in r or "same" in r or "differs" in r]
    with open(os.path.join(source, "docs/gpu_check.md"), encoding="utf-8") as f:
        doc = set(f.read().splitlines())
    missing = [r for r in rows + small_rows if r not in doc]
    for r in missing:
        print("not in docs/gpu_check.md:", r)
    print(f"{len(rows) + len(small_rows)} report rows, {len(missing)} missing from docs/gpu_check.md")
    sys.exit(1 if missing else 0)


if __name__ == "__main__":
    main()
