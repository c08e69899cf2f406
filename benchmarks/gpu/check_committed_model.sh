#!/bin/sh
# ctest gpu_check_model_matches_docs: the model column of docs/gpu_check.md
# is what the SIMT model computes today. Regenerates model.csv with
# gpu_ray_cast_export and compares it with the committed one; a change to
# the model that moves a number fails here until the GPU check's report is
# regenerated (docs/gpu_check.md says how). Skips (77) without the Wean map.
#   check_committed_model.sh EXPORTER SOURCE_DIR SHARED_DATA_DIR
exporter=$1
source_dir=$2
shared=$3
if [ ! -f "$shared/wean/wean.dat" ]; then
  echo "skipped: $shared/wean/wean.dat is absent (the committed model.csv was priced on Wean)"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$exporter" --out "$tmp" --preset "$source_dir/backends/presets/h100.json" --shared-data "$shared" >/dev/null || exit 1
diff "$source_dir/docs/gpu_check/ray_cast/model.csv" "$tmp/model.csv"
