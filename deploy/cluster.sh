#!/usr/bin/env bash
# Starts a zonesim cluster from a cluster file (deploy/clusters/*.cluster; the format is at the
# top of deploy/cluster_file.py): zones with mpirun, gateways and client fleets on their hosts, all
# metrics in RUN_DIR, then the report (printed and RUN_DIR/report.json).
# Usage: deploy/cluster.sh CLUSTER_FILE [RUN_DIR]
#   ZONESIM_BIN: run the programs already built there, without setup.sh's apt-get and build.
set -euo pipefail
if [ -n "${ZONESIM_BIN:-}" ]; then
  # Root runs mpirun only when told, as CI and the test machines do.
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
else
  source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
  export ZONESIM_BIN="$BUILD_DIR/bin"
fi
exec python3 "$(dirname "${BASH_SOURCE[0]}")/cluster.py" "$@"
