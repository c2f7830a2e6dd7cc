#!/usr/bin/env bash
# Fuzzes linkbox's readers with libFuzzer (clang from Debian: clang, libclang-rt-14-dev).
#
#   tests/fuzz/run.sh [--minutes N] [--build DIR] [--jobs J] [--seed] [TARGET ...]
#
# Targets (tests/fuzz/targets.cpp): case_toml expression check_json minibex cuik; default all,
# one after the other, N minutes each (default 5). For each target it
#   1. fuzzes from tests/fuzz/corpus/<target>/ (plus a dictionary, <target>.dict, if present),
#      new inputs going to a scratch folder in the build directory;
#   2. merges corpus + new inputs into a minimal set (libFuzzer -merge=1 into an empty folder)
#      that replaces corpus/<target>/, so the corpus stays small;
#   3. copies each crash, timeout (> 5 s), out-of-memory or leak input into
#      tests/fuzz/regressions/<target>/: the ctest "fuzz inputs: ..." replays those through the
#      normal build, so it fails until the defect is fixed;
#   4. appends the figures (execs, corpus size, findings) to tests/fuzz/runs.csv.
# --seed first (re)adds the bundled inputs (cases/, tests/data/, seeds/) to the corpora.
# Exit status: 1 when any target found something.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
minutes=5
build=/tmp/linkbox-build-fuzz
jobs=2
seed=0
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --minutes) minutes="$2"; shift 2 ;;
    --build) build="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --seed) seed=1; shift ;;
    -h|--help) sed -n '2,18p' "$0"; exit 0 ;;
    -*) echo "unknown option $1" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
[ ${#targets[@]} -gt 0 ] || targets=(case_toml expression check_json minibex cuik)

command -v clang++ >/dev/null || { echo "run.sh needs clang and libFuzzer: bash .ci/install --fuzz" >&2; exit 2; }
# -O1 -g with assertions (Eigen's bounds checks) on; the rounding flags come from CMakeLists.txt.
cmake -S "$root" -B "$build" -DLINKBOX_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" >/dev/null
cmake --build "$build" -j"$jobs" --target $(printf 'fuzz_%s ' "${targets[@]}") >/dev/null

if [ "$seed" = 1 ]; then
  python3 "$here/seed.py" --linkbox-build "$build" "${targets[@]}"
fi

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
export OPENBLAS_NUM_THREADS=1
status=0
summary=()
for t in "${targets[@]}"; do
  corpus="$here/corpus/$t"
  regressions="$here/regressions/$t"
  scratch="$build/fuzz-work/$t"
  rm -rf "$scratch" && mkdir -p "$scratch/new" "$scratch/merged" "$scratch/findings" "$corpus"
  dict=()
  [ -f "$here/$t.dict" ] && dict=(-dict="$here/$t.dict")
  log="$scratch/fuzz.log"
  echo "== $t: fuzzing for $minutes min (log: $log)"
  set +e
  "$build/tests/fuzz/fuzz_$t" "$scratch/new" "$corpus" "${dict[@]}" \
    -max_total_time=$((minutes * 60)) -timeout=5 -rss_limit_mb=2048 -max_len=16384 \
    -print_final_stats=1 -artifact_prefix="$scratch/findings/" >"$log" 2>&1
  rc=$?
  set -e
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  [ -n "$execs" ] || execs=$(sed -n 's/^Done \([0-9]*\) runs.*/\1/p' "$log" | tail -1)
  [ -n "$execs" ] || execs=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#')
  # Minimal corpus: the old corpus and the new inputs, merged into an empty folder.
  "$build/tests/fuzz/fuzz_$t" -merge=1 -timeout=5 -rss_limit_mb=2048 -max_len=16384 \
    "$scratch/merged" "$corpus" "$scratch/new" >"$scratch/merge.log" 2>&1 || true
  if [ -n "$(ls -A "$scratch/merged")" ]; then
    rm -f "$corpus"/*
    cp "$scratch/merged"/* "$corpus"/
  fi
  size=$(ls "$corpus" | wc -l)
  findings=0
  for f in "$scratch/findings"/*; do
    [ -e "$f" ] || continue
    mkdir -p "$regressions"
    cp "$f" "$regressions/"
    findings=$((findings + 1))
    echo "   FINDING: $(basename "$f") -> tests/fuzz/regressions/$t/ (fix it; the ctest replays it)"
  done
  if [ $findings -gt 0 ] || [ $rc -ne 0 ]; then
    status=1
    grep -m1 -E "ERROR: (AddressSanitizer|libFuzzer|LeakSanitizer)|runtime error|terminate called|==ERROR" "$log" || true
  fi
  echo "$(date -u +%Y-%m-%dT%H:%MZ),$t,$minutes,${execs:-0},$size,$findings" >>"$here/runs.csv"
  summary+=("$(printf '%-11s %4s min  %10s execs  corpus %4s  findings %s' "$t" "$minutes" "${execs:-?}" "$size" "$findings")")
done
echo "== summary (also appended to tests/fuzz/runs.csv)"
printf '%s\n' "${summary[@]}"
exit $status
