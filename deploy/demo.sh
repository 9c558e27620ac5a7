#!/usr/bin/env bash
# The main job: a local cluster of 4 zone ranks, one gateway and one client_stub with 32 players
# on scenes/demo.yaml for about 20 s, then the handoff/bandwidth report (printed and report.json).
# Usage: deploy/demo.sh [RUN_DIR]
#   (environment: ZONESIM_DEMO_SECONDS, ZONESIM_DEMO_PLAYERS, ZONESIM_DEMO_SCENE,
#    ZONESIM_DEMO_TRUTH_EVERY: zones log the truth of every K-th entity id and clients what they
#    showed of it, for the error-against-truth table of the report; 0 = off;
#    ZONESIM_DEMO_CLIENT_ARGS: more client_stub options, e.g. "--max-lead-s 0" to compare;
#    ZONESIM_BIN: run the programs already built there, without setup.sh's apt-get and build,
#    as tests/integration/demo_smoke.py does)
set -euo pipefail
if [ -n "${ZONESIM_BIN:-}" ]; then
  ZONESIM_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
  BIN="$ZONESIM_BIN"
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
else
  source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
  BIN="$BUILD_DIR/bin"
fi

SECONDS_RUN="${ZONESIM_DEMO_SECONDS:-20}"
PLAYERS="${ZONESIM_DEMO_PLAYERS:-32}"
SCENE="${ZONESIM_DEMO_SCENE:-$ZONESIM_ROOT/scenes/demo.yaml}"
TRUTH_EVERY="${ZONESIM_DEMO_TRUTH_EVERY:-32}"
read -r -a CLIENT_ARGS <<<"${ZONESIM_DEMO_CLIENT_ARGS:-}"
RUN_DIR="$(realpath -m "${1:-$ZONESIM_ROOT/runs/demo-$(date +%Y%m%d-%H%M%S)}")"
mkdir -p "$RUN_DIR"
rm -f "$RUN_DIR/gateway.port"  # a port left by an earlier run in the same folder would mislead us
export CYCLONEDDS_URI="file://$ZONESIM_ROOT/deploy/cyclonedds.xml"
# A domain whose ports (7400 + 250 d + [0, 250)) lie below the ephemeral port range, so no
# player or gateway socket can draw one of them and receive Cyclone's discovery packets.
DOMAIN="${ZONESIM_DDS_DOMAIN:-$(( (RANDOM % 90) + 1 ))}"

pids=()
cleanup() { for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT

echo "== run folder: $RUN_DIR (DDS domain $DOMAIN)"
# Zones run a little longer than the clients so that every client second has live zones.
ZONE_SECONDS=$(( SECONDS_RUN + 6 ))
mpirun -np 4 --oversubscribe --bind-to none "$BIN/zone_node" --scene "$SCENE" --duration "$ZONE_SECONDS" \
  --realtime --metrics "$RUN_DIR" --dds-domain "$DOMAIN" --truth-every "$TRUTH_EVERY" >"$RUN_DIR/zones.log" 2>&1 &
zones_pid=$!
pids+=("$zones_pid")

"$BIN/gateway" --scene "$SCENE" --port 0 --port-file "$RUN_DIR/gateway.port" --dds-domain "$DOMAIN" \
  --metrics "$RUN_DIR" >"$RUN_DIR/gateway.log" 2>&1 &
gateway_pid=$!
pids+=("$gateway_pid")
for _ in $(seq 100); do [ -s "$RUN_DIR/gateway.port" ] && break; sleep 0.1; done
[ -s "$RUN_DIR/gateway.port" ] || { echo "gateway did not start:"; cat "$RUN_DIR/gateway.log"; exit 1; }
PORT="$(cat "$RUN_DIR/gateway.port")"
sleep 2  # let DDS discovery between zones and gateway settle before players ask for avatars

echo "== $PLAYERS players for $SECONDS_RUN s against 127.0.0.1:$PORT"
"$BIN/client_stub" --scene "$SCENE" --gateway "127.0.0.1:$PORT" --players "$PLAYERS" \
  --duration "$SECONDS_RUN" --metrics "$RUN_DIR" --summary "$RUN_DIR/clients_summary.json" \
  --truth-every "$TRUTH_EVERY" "${CLIENT_ARGS[@]}" \
  >"$RUN_DIR/clients.log" 2>&1 &
clients_pid=$!
pids+=("$clients_pid")
# Progress every 5 s from the clients' per-second metrics line.
while kill -0 "$clients_pid" 2>/dev/null; do
  sleep 5
  [ -s "$RUN_DIR/clients.jsonl" ] && python3 "$ZONESIM_ROOT/deploy/report.py" --progress "$RUN_DIR" || true
done
wait "$clients_pid" || { echo "client_stub failed:"; tail -20 "$RUN_DIR/clients.log"; exit 1; }

kill -TERM "$gateway_pid" 2>/dev/null || true
wait "$gateway_pid" 2>/dev/null || true
wait "$zones_pid" || { echo "zones failed:"; tail -20 "$RUN_DIR/zones.log"; exit 1; }
pids=()
python3 "$ZONESIM_ROOT/deploy/report.py" "$RUN_DIR"
