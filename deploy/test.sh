#!/usr/bin/env bash
# The test command: installs what is missing, builds into build/, runs the whole suite with ctest.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
start=$(date +%s)
cd "$BUILD_DIR"
ctest --output-on-failure -j "${ZONESIM_TEST_JOBS:-2}" --timeout 600
echo "== tests took $(( $(date +%s) - start )) s"
