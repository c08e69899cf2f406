#!/usr/bin/env bash
# The device half of the GPU check (docs/gpu_check.md). Run from the
# repository root on a machine with an NVIDIA GPU and the CUDA toolkit:
#
#   benchmarks/gpu/run_on_gpu.sh IN_DIR OUT_DIR
#
# IN_DIR holds queries.bin and, optionally, leaf.bin (gpu_ray_cast_export),
# and optionally sact_*.bin (gpu_sact_export). OUT_DIR receives
#   gpu.txt             nvidia-smi's clocks before, during and after, nvcc's version
#   measured.csv        ray_cast_on_gpu: timings and answer checks per launch
#   sact_measured.csv   sact_on_gpu: the same for the collision kernel
#   memcheck.txt, sact_memcheck.txt
#                       compute-sanitizer memcheck over one launch of each (if present)
#   profile.csv, sact_profile.csv
#                       Nsight Compute counters of each launch (if ncu is present)
# Exit status: 3 when an FP64 answer differs from the host's, 9 when
# compute-sanitizer finds an error, else the first harness failure's.
set -euo pipefail
in_dir=$1
out_dir=$2
mkdir -p "$out_dir"
nvcc=${NVCC:-$(command -v nvcc || echo /usr/local/cuda/bin/nvcc)}
smi_fields=name,driver_version,clocks.sm,clocks.max.sm,clocks.mem,clocks.max.mem,power.draw
{
  echo "# before"
  nvidia-smi --query-gpu=$smi_fields --format=csv
  "$nvcc" --version | tail -2
} >"$out_dir/gpu.txt"

bin_dir=$(mktemp -d)
# -fmad=false: the host build has no FMA contraction, so the FP64 kernels
# must give the host's answers bit for bit.
for harness in ray_cast_on_gpu sact_on_gpu; do
  "$nvcc" -O3 -arch=native -fmad=false -std=c++17 -I. "benchmarks/gpu/$harness.cu" -o "$bin_dir/$harness"
done
leaf=()
[ -f "$in_dir/leaf.bin" ] && leaf=("$in_dir/leaf.bin")
shopt -s nullglob
sact_files=("$in_dir"/sact_*.bin)
shopt -u nullglob

status=0
record() { if [ "$status" -eq 0 ]; then status=$1; fi; }
nvidia-smi --query-gpu=clocks.sm,clocks.mem --format=csv,noheader -lms 20 >"$bin_dir/clocks.txt" &
sampler=$!
"$bin_dir/ray_cast_on_gpu" "$in_dir/queries.bin" "$out_dir/measured.csv" "${leaf[@]}" || record $?
if [ ${#sact_files[@]} -gt 0 ]; then
  "$bin_dir/sact_on_gpu" "$out_dir/sact_measured.csv" "${sact_files[@]}" || record $?
fi
kill "$sampler" || true
{
  echo "# during the timed runs (clocks.sm, clocks.mem every 20 ms): distinct readings and their counts"
  sort "$bin_dir/clocks.txt" | uniq -c
  echo "# after"
  nvidia-smi --query-gpu=$smi_fields --format=csv
} >>"$out_dir/gpu.txt"

if command -v compute-sanitizer >/dev/null; then
  compute-sanitizer --tool memcheck --error-exitcode 9 "$bin_dir/ray_cast_on_gpu" "$in_dir/queries.bin" \
    "$bin_dir/memcheck.csv" --profile "${leaf[@]}" >"$out_dir/memcheck.txt" 2>&1 || record $?
  if [ ${#sact_files[@]} -gt 0 ]; then
    compute-sanitizer --tool memcheck --error-exitcode 9 "$bin_dir/sact_on_gpu" "$bin_dir/sact_memcheck.csv" \
      --profile "${sact_files[@]}" >"$out_dir/sact_memcheck.txt" 2>&1 || record $?
  fi
fi
if command -v ncu >/dev/null; then
  metrics=gpu__time_duration.sum,sm__cycles_elapsed.max,sm__cycles_elapsed.avg.per_second
  metrics+=,smsp__inst_executed.sum,smsp__thread_inst_executed.sum
  metrics+=,smsp__thread_inst_executed_per_inst_executed.ratio
  metrics+=,l1tex__t_sectors_pipe_lsu_mem_global_op_ld.sum,l1tex__t_sector_hit_rate.pct,lts__t_sector_hit_rate.pct
  metrics+=,sm__warps_active.avg.pct_of_peak_sustained_active,launch__registers_per_thread
  ncu --clock-control none --csv --metrics "$metrics" "$bin_dir/ray_cast_on_gpu" "$in_dir/queries.bin" \
    "$bin_dir/profile_run.csv" --profile "${leaf[@]}" >"$out_dir/profile.csv" 2>"$bin_dir/ncu.err" ||
    { echo "# ncu failed on ray_cast_on_gpu:"; tail -n 5 "$bin_dir/ncu.err"; } >>"$out_dir/gpu.txt"
  if [ ${#sact_files[@]} -gt 0 ]; then
    ncu --clock-control none --csv --metrics "$metrics" "$bin_dir/sact_on_gpu" "$bin_dir/sact_profile_run.csv" \
      --profile "${sact_files[@]}" >"$out_dir/sact_profile.csv" 2>"$bin_dir/ncu.err" ||
      { echo "# ncu failed on sact_on_gpu:"; tail -n 5 "$bin_dir/ncu.err"; } >>"$out_dir/gpu.txt"
  fi
fi
exit $status
