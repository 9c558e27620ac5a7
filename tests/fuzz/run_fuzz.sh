#!/usr/bin/env bash
# Builds the datagram fuzz target (the gateway's handler, the client's checks) with clang
# (libFuzzer + ASan + UBSan) and runs it for a fixed time.
# Usage: tests/fuzz/run_fuzz.sh [BUILD_DIR] [SECONDS]. Exit 0: no crash, no leak,
# no sanitizer report. Skips (exit 77) where clang cannot link libFuzzer, except under CI
# (CI=true), where deploy/setup.sh has installed clang and its runtimes: there it fails.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
BUILD="${1:-$ROOT/build-fuzz}"
SECONDS_RUN="${2:-60}"
probe="$(mktemp -d)"
trap 'rm -rf "$probe"' EXIT
printf 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }\n' \
  >"$probe/p.cpp"
if ! clang++ -fsanitize=fuzzer "$probe/p.cpp" -o "$probe/p" 2>/dev/null; then
  if [ "${CI:-}" = "true" ]; then
    echo "FAIL: clang++ cannot link libFuzzer, and CI installs it (deploy/setup.sh)"
    exit 1
  fi
  echo "SKIP: clang++ cannot link libFuzzer here (install clang and libclang-rt-dev)"
  exit 77
fi
cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DZONESIM_FUZZ=ON \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ >/dev/null
cmake --build "$BUILD" --target fuzz_datagram_handler -j "${ZONESIM_JOBS:-2}"
corpus="$probe/corpus"
mkdir -p "$corpus"
echo "== fuzzing the gateway's datagram handler and the client's checks for $SECONDS_RUN s"
"$BUILD/bin/fuzz_datagram_handler" -max_total_time="$SECONDS_RUN" -max_len=2048 -rss_limit_mb=2048 \
  -print_final_stats=1 "$corpus" 2>&1 | tail -15
