#!/usr/bin/env bash
# The sanitizer variant: builds with ASan + UBSan at -O1 into build-sanitize/ and runs the whole
# ctest suite under it, integration tests included. Any sanitizer report fails its test.
# Usage: deploy/sanitize.sh [BUILD_DIR]; ZONESIM_JOBS and ZONESIM_TEST_JOBS as for test.sh.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${1:-$ROOT/build-sanitize}"
SAN="-fsanitize=address,undefined -fno-omit-frame-pointer"

# Open MPI leaks by design, so leak checks would fail every MPI program. UBSan only warns unless
# told to halt. Exported before the build as well: gtest_discover_tests runs the test binaries
# while building. ctest, mpirun and the python tests pass them on to every child process.
export ASAN_OPTIONS="detect_leaks=0${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# RelWithDebInfo keeps the project's assertions (CMakeLists.txt); only its -O2 becomes -O1.
echo "== configure + build in $BUILD"
start=$(date +%s)
cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS="$SAN" -DCMAKE_CXX_FLAGS="$SAN" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" >/dev/null
cmake --build "$BUILD" -j "${ZONESIM_JOBS:-$(nproc)}"
echo "== build took $(($(date +%s) - start)) s"

# The fuzz ctest is left out: it builds its own ASan + UBSan target (tests/fuzz/run_fuzz.sh).
start=$(date +%s)
cd "$BUILD"
ctest --output-on-failure -j "${ZONESIM_TEST_JOBS:-2}" --timeout 900 -LE fuzz
echo "== sanitized tests took $(($(date +%s) - start)) s"
