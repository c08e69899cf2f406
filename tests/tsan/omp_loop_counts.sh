#!/usr/bin/env bash
# How often the TSan stage's tests (run_tsan.sh) enter each OpenMP construct
# of the libraries: builds the same two tests with GCC's --coverage, runs
# them as run_tsan.sh does (4 threads), and prints, for every '#pragma omp'
# line outside tests/, the execution count of the first line after it that
# holds code. A count of 0 is a construct the TSan stage never ran; the
# script then exits 1. (docs/robustness.md, "ThreadSanitizer".)
# Usage (from the repository root): omp_loop_counts.sh <build folder> [jobs]
set -euo pipefail
BUILD="$1"
JOBS="${2:-2}"
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS="--coverage" -DBUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$BUILD" -j"$JOBS" --target openmp_loops_test collision_test >/dev/null
find "$BUILD" -name '*.gcda' -delete
export OMP_NUM_THREADS=4
"$BUILD/tests/tsan/openmp_loops_test" >/dev/null
"$BUILD/tests/collision/collision_test" --gtest_filter='SactPropertyArtifact.*' >/dev/null
python3 - "$BUILD" <<'PY'
import pathlib, re, subprocess, sys
build = pathlib.Path(sys.argv[1]).resolve()
root = pathlib.Path.cwd()
sources = [p for p in sorted(root.rglob("*.cc"))
           if not {"tests", "build"} & set(p.relative_to(root).parts[:1]) and not p.relative_to(root).parts[0].startswith("build")
           and "#pragma omp" in p.read_text()]
unreached = 0
print(f"{'construct':<62} {'body runs':>10}")
for source in sources:
    rel = source.relative_to(root)
    gcda = list(build.rglob(source.name + ".gcda"))
    counts = {}
    if gcda:
        out = subprocess.run(["gcov", "-t", "-o", str(gcda[0].parent), str(source)], capture_output=True,
                             text=True, cwd=gcda[0].parent).stdout
        current = None
        for line in out.splitlines():
            m = re.match(r"\s*([0-9]+\*?|#####|=====|-):\s*([0-9]+):", line)
            if m:
                count, number = m.group(1), int(m.group(2))
                if number == 0:
                    continue
                counts.setdefault(number, count)
    lines = source.read_text().splitlines()
    for i, text in enumerate(lines, start=1):
        if "#pragma omp" not in text:
            continue
        pragma = text.strip()[len("#pragma omp "):]
        runs = "no data"
        for j in range(i + 1, min(i + 6, len(lines) + 1)):
            c = counts.get(j)
            if c is None or c == "-":
                continue
            runs = "0" if c in ("#####", "=====") else c.rstrip("*")
            break
        if runs in ("0", "no data"):
            unreached += 1
        print(f"{str(rel) + ':' + str(i) + ' ' + pragma:<62.62} {runs:>10}")
sys.exit(1 if unreached else 0)
PY
