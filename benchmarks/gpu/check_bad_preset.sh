#!/bin/sh
# ctest gpu_check_exporters_refuse_a_bad_preset: each exporter given a preset
# with a value outside its declared range exits 1 (common/exit_codes.h) with
# the file and the key named, and writes nothing.
#   check_bad_preset.sh EXPORTER...
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '{"gpu": {"sms": 0}}\n' >"$tmp/bad.json"
status=0
for exporter in "$@"; do
  "$exporter" --out "$tmp/out" --preset "$tmp/bad.json" 2>"$tmp/err"
  code=$?
  if [ "$code" -ne 1 ] || ! grep -q "bad.json: gpu.sms = 0 is outside its range" "$tmp/err" || [ -e "$tmp/out" ]; then
    echo "$exporter: exit $code, stderr: $(cat "$tmp/err"), output folder present: $([ -e "$tmp/out" ] && echo yes || echo no)"
    status=1
  fi
done
exit $status
