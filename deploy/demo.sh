#!/usr/bin/env bash
# The main job: a local cluster of 4 zone ranks, one gateway and one client_stub with 32 players
# on scenes/demo.yaml for about 20 s, then the handoff/bandwidth report (printed and report.json).
# It is deploy/cluster.sh with deploy/clusters/local.cluster.
# Usage: deploy/demo.sh [RUN_DIR]
#   (environment: ZONESIM_DEMO_SECONDS, ZONESIM_DEMO_PLAYERS, ZONESIM_DEMO_SCENE,
#    ZONESIM_DEMO_TRUTH_EVERY: zones log the truth of every K-th entity id and clients what they
#    showed of it, for the error-against-truth table of the report; 0 = off;
#    ZONESIM_DEMO_CLIENT_ARGS: more client_stub options, e.g. "--max-lead-s 0" to compare;
#    ZONESIM_DEMO_GATEWAY_ARGS: more gateway options, e.g. "--budget-kbps 20";
#    ZONESIM_DEMO_RECORD: yes (default) or no: zones and gateway record every tick into
#    RUN_DIR/record/ for deploy/inspect.sh;
#    ZONESIM_DDS_DOMAIN: the DDS domain (default: a random one of 1-90);
#    ZONESIM_BIN: run the programs already built there, without setup.sh's apt-get and build,
#    as tests/integration/demo_smoke.py does)
set -euo pipefail
DEPLOY="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
RUN_DIR="${1:-$DEPLOY/../runs/demo-$(date +%Y%m%d-%H%M%S)}"
exec "$DEPLOY/cluster.sh" "$DEPLOY/clusters/local.cluster" "$RUN_DIR"
