#!/usr/bin/env bash
# The whole test suite: set-up (packages, configure, build) then ctest. Called by .ci/run.
#   bash scripts/test.sh [CTEST ARGS...]              Release build in build/ (TWINSLAM_BUILD_DIR), every test
#   bash scripts/test.sh --sanitize [CTEST ARGS...]   clang ASan + UBSan build in build-sanitize/ (TWINSLAM_SANITIZE_DIR,
#                                                     shared with scripts/fuzz.sh), the unit tests (label `unit`) but
#                                                     the scenario-length ones of tests/sanitizers/slow_tests.txt; any
#                                                     sanitizer report fails
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# Two gtest cases with one name in different executables become one CTest test (the other never runs, and labels
# mix: an integration case once ran in the sanitized unit pass). Refuse such a build before running anything.
refuse_duplicate_names() {
  local dups
  dups=$(ctest -N | sed -n 's/^ *Test *#[0-9]*: //p' | sort | uniq -d)
  if [[ -n "$dups" ]]; then
    echo "test.sh: CTest test names defined twice (rename one gtest suite): $(echo $dups)" >&2
    exit 1
  fi
}
if [[ "${1:-}" == "--sanitize" ]]; then
  shift
  # The tree (clang, options and reasons in scripts/sanitize-options.sh) also holds the libFuzzer targets, which
  # scripts/fuzz.sh runs without building again; here their committed corpora replay as fuzz_corpus_* tests.
  source "$root/scripts/sanitize-options.sh"
  build=$sanitize_build_dir
  sanitize_prepare_build_dir
  TWINSLAM_BUILD_DIR=$build bash "$root/scripts/setup.sh" "${sanitize_cmake_args[@]}"
  # new_delete_type_mismatch=0: Fast DDS 2.9 itself deletes its readers with a mismatched size
  # (RTPSReader::~RTPSReader via DataReaderImpl::stop, in libfastrtps.so.2.9, not our code); ASan has no per-library
  # suppression for that check.
  export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:detect_stack_use_after_return=0:new_delete_type_mismatch=0:suppressions=$root/tests/sanitizers/asan.supp${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
  export LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$root/tests/sanitizers/ubsan.supp${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
  # Scenario-length unit tests are left out (tests/sanitizers/slow_tests.txt says why).
  slow=$(grep -v '^#' "$root/tests/sanitizers/slow_tests.txt" | sed 's/\./\\./g' | paste -sd'|')
  cd "$build"
  refuse_duplicate_names
  exec ctest -j2 --output-on-failure --timeout 900 -L unit -E "^($slow)\$" "$@"
fi
build=${TWINSLAM_BUILD_DIR:-$root/build}
bash "$root/scripts/setup.sh"
cd "$build"
refuse_duplicate_names
ctest -j2 --output-on-failure --timeout 600 "$@"
