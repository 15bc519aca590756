#!/usr/bin/env bash
# Fuzzing (issue 15): bash scripts/fuzz.sh TARGET[,TARGET...]|all SECONDS [LIBFUZZER ARGS...]
# Builds the libFuzzer targets with clang (ASan + UBSan + coverage) in the sanitized tree build-sanitize/
# (TWINSLAM_SANITIZE_DIR; the one scripts/test.sh --sanitize builds, options in scripts/sanitize-options.sh) and runs
# TARGET (a name of tests/fuzz/targets/, or every one of them) for SECONDS each. The corpus grows in
# build-sanitize/corpus/TARGET, seeded from the committed tests/fuzz/corpus/TARGET (and the 3D Tiles samples of
# ../shared/data for the 3D Tiles targets). A crash, leak, sanitizer report, uncaught exception other than the
# contract's InputError, or an input slower than 10 s ends the run with exit 1 and the input in
# build-sanitize/crashes/TARGET/: fix the bug, then commit the input to tests/fuzz/corpus/TARGET/ as a regression
# test.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$root/scripts/sanitize-options.sh"
build=$sanitize_build_dir
if (( $# < 2 )) || ! [[ "$2" =~ ^[0-9]+$ ]]; then
  echo "usage: scripts/fuzz.sh TARGET[,TARGET...]|all SECONDS [LIBFUZZER ARGS...]" >&2
  exit 2
fi
target=$1 seconds=$2
shift 2
all=$(cd "$root/tests/fuzz/targets" && ls *.cpp | sed 's/\.cpp$//')
if [[ "$target" == all ]]; then targets=$all
else
  targets=${target//,/ }
  for t in $targets; do
    grep -qx "$t" <<< "$all" || { echo "fuzz.sh: unknown target '$t' (targets: $(echo $all))" >&2; exit 2; }
  done
fi

# Packages (clang and libclang-rt-dev are in scripts/packages.txt) without building the Release tree.
TWINSLAM_SETUP_PACKAGES_ONLY=1 bash "$root/scripts/setup.sh"
sanitize_prepare_build_dir
cmake -S "$root" -B "$build" -G Ninja "${sanitize_cmake_args[@]}" >/dev/null
cmake --build "$build" -j2 --target $(printf 'fuzz_%s ' $targets)

export ASAN_OPTIONS="detect_leaks=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export root build seconds
export FUZZ_EXTRA="$*"
# Progress: one line per finished target with how many are done and the time left (each target takes SECONDS).
jobs=${TWINSLAM_FUZZ_JOBS:-2}
total=$(printf '%s\n' $targets | wc -l)
progress=$build/progress.$$
rm -rf "$progress" && mkdir -p "$progress"
export progress total jobs
echo "fuzz.sh: $total targets x $seconds s, $jobs at a time: about $(( (total + jobs - 1) / jobs * seconds )) s"
# "[done/total, ETA s]" after one more target ended (a file per finished target: safe with parallel jobs).
progress_tag() {
  touch "$progress/$1"
  local done left
  done=$(ls "$progress" | wc -l)
  left=$(( (total - done + jobs - 1) / jobs * seconds ))
  echo "[$done/$total, ETA ${left} s]"
}
export -f progress_tag

# One target: its run's executions and coverage on success; exit 1 with the first line of the report otherwise.
run_one() {
  local t=$1 corpus=$build/corpus/$1 crashes=$build/crashes/$1/ log=$build/fuzz_$1.log
  mkdir -p "$corpus" "$crashes"
  local seeds=("$root/tests/fuzz/corpus/$t")
  case $t in b3dm|gltf|tile_content|tileset) [[ -d "$root/../shared/data/3dtiles" ]] && seeds+=("$root/../shared/data/3dtiles") ;; esac
  # shellcheck disable=SC2086  # FUZZ_EXTRA: the caller's extra libFuzzer flags, split on spaces
  if "$build/bin/fuzz_$t" "$corpus" "${seeds[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2560 \
       -print_final_stats=1 -artifact_prefix="$crashes" $FUZZ_EXTRA > "$log" 2>&1; then
    local execs cov
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1)
    echo "fuzz.sh: $(progress_tag "$t") $t ok: ${seconds} s, $execs executions, $cov, corpus $(ls "$corpus" | wc -l) inputs"
  else
    echo "fuzz.sh: $(progress_tag "$t") $t FAILED (log $log, input in $crashes): $(grep -m1 -E "ERROR: |runtime error|uncaught|terminate called|deadly signal|Timeout" "$log" || tail -1 "$log")" >&2
    return 1
  fi
}
export -f run_one
# Two targets at a time (TWINSLAM_FUZZ_JOBS): a 2-core machine; each libFuzzer process is single-threaded.
status=0
printf '%s\n' $targets | xargs -P "$jobs" -I{} bash -c 'run_one {}' || status=1
rm -rf "$progress"
exit $status
