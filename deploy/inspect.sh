#!/usr/bin/env bash
# The web inspector on a run folder that was recorded (deploy/demo.sh does; a cluster file's
# `record = yes`; zone_node and gateway --record RUN_DIR/record): serves the page on
# http://127.0.0.1:PORT/ (default 8765) until Ctrl-C. --live follows a run still going.
# Usage: deploy/inspect.sh RUN_DIR [--port P] [--live] [--max-entities N]
#   (environment: ZONESIM_BUILD_DIR, where the build generated the Python FlatBuffers classes;
#    default build/)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${ZONESIM_BUILD_DIR:-$ROOT/build}"
if [ $# -lt 1 ]; then
  sed -n '2,7p' "$0" >&2
  exit 2
fi
if [ ! -d "$BUILD_DIR/python/zonesim/recording" ]; then
  echo "inspect.sh: no generated Python classes in $BUILD_DIR/python: build first (deploy/setup.sh)" >&2
  exit 2
fi
# python3-flatbuffers and numpy are Debian's: its python3, whatever else is on the PATH.
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
export PYTHONPATH="$ROOT/inspector:$BUILD_DIR/python${PYTHONPATH:+:$PYTHONPATH}"
exec "$PY" "$ROOT/inspector/server.py" "$@"
