# Sourced by scripts/test.sh --sanitize and scripts/fuzz.sh: the one sanitized tree both use (issue 15), so CI builds
# it once for the unit tests under ASan + UBSan and for the libFuzzer smoke.
#   sanitize_build_dir           build-sanitize/ (TWINSLAM_SANITIZE_DIR; TWINSLAM_FUZZ_DIR is the older name)
#   sanitize_cmake_args          clang, ASan + UBSan, libFuzzer's coverage instrumentation, fuzz targets
#   sanitize_prepare_build_dir   drops a tree an older version configured with gcc (CMake cannot switch compilers)
# -O1: sanitized code at -O3 builds slowly and reports no more; NDEBUG as in Release (the suite's own checks are
# gtest assertions). No benchmarks: they measure nothing under a sanitizer; no tests/integration: only `unit` runs.
# UBSan without null and alignment: the two emit one check on every pointer and reference use, which doubles the
# compile time of Eigen-heavy code (test_world_alignment.cpp: 44 s with them, 21 s without, 15 s unsanitized at -O1)
# and so most of CI's sanitized half; a null or misaligned access still ends the test (or the fuzz run) as ASan's
# SEGV report.
sanitize_build_dir=${TWINSLAM_SANITIZE_DIR:-${TWINSLAM_FUZZ_DIR:-$root/build-sanitize}}
sanitize_cmake_args=(-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" -DTWINSLAM_FUZZ=ON -DTWINSLAM_SANITIZE=address,undefined
  -DTWINSLAM_SANITIZE_EXCLUDE=null,alignment -DTWINSLAM_BUILD_BENCHMARKS=OFF -DTWINSLAM_BUILD_INTEGRATION_TESTS=OFF)

sanitize_prepare_build_dir() {
  local cache=$sanitize_build_dir/CMakeCache.txt
  if [[ -f "$cache" ]] && ! grep -q '^CMAKE_CXX_COMPILER:[A-Z]*=.*clang++' "$cache"; then
    echo "sanitize: $sanitize_build_dir was configured with another compiler; configuring it afresh with clang++" >&2
    rm -rf "$sanitize_build_dir/CMakeCache.txt" "$sanitize_build_dir/CMakeFiles"
  fi
}
