#!/usr/bin/env bash
# Hosts as Linux network namespaces on one machine, for trying a cluster file without
# machines (deploy/clusters/netns3.cluster; tests/integration/multi_host.py):
#   deploy/netns.sh up PREFIX COUNT [SUBNET]   namespaces PREFIX-h1..hCOUNT, each with an
#                                             interface zs0 at SUBNET.i/24 (default 10.77.0),
#                                             joined by the bridge PREFIXbr in this namespace
#   deploy/netns.sh down PREFIX               kills what runs in them, removes them and the bridge
#   deploy/netns.sh check PREFIX              exit 1, listing them, if any is left
# Needs root (CAP_NET_ADMIN). PREFIX: at most 10 characters, [a-z0-9], unique per run (the
# test uses its pid), so parallel runs never share a namespace or an interface name.
set -euo pipefail
cmd="${1:?usage: netns.sh up|down|check PREFIX [COUNT] [SUBNET]}"
prefix="${2:?PREFIX missing}"
[[ "$prefix" =~ ^[a-z0-9]{1,10}$ ]] || { echo "netns.sh: PREFIX '$prefix' must be 1-10 of [a-z0-9]" >&2; exit 2; }

namespaces() { ip netns list 2>/dev/null | awk '{print $1}' | grep -E "^${prefix}-h[0-9]+\$" || true; }
links() { ip -o link show 2>/dev/null | awk -F': ' '{print $2}' | sed 's/@.*//' | grep -E "^${prefix}(br|v[0-9]+)\$" || true; }

down() {
  local ns pid
  for ns in $(namespaces); do
    # Twice: a process may fork between the listing and the kill.
    for _ in 1 2; do
      for pid in $(ip netns pids "$ns" 2>/dev/null); do kill -KILL "$pid" 2>/dev/null || true; done
    done
    ip netns del "$ns" 2>/dev/null || true
  done
  local l
  for l in $(links); do ip link del "$l" 2>/dev/null || true; done
}

case "$cmd" in
  up)
    count="${3:?COUNT missing}"
    subnet="${4:-10.77.0}"
    trap 'down' ERR
    ip link add "${prefix}br" type bridge
    ip link set "${prefix}br" up
    for i in $(seq "$count"); do
      ns="${prefix}-h$i"
      ip netns add "$ns"
      ip link add "${prefix}v$i" type veth peer name zs0 netns "$ns"
      ip link set "${prefix}v$i" master "${prefix}br" up
      ip -n "$ns" addr add "$subnet.$i/24" dev zs0
      ip -n "$ns" link set zs0 up
      ip -n "$ns" link set lo up
    done
    ;;
  down) down ;;
  check)
    left="$(namespaces; links)"
    [ -z "$left" ] || { echo "left behind: $left" | tr '\n' ' '; echo; exit 1; }
    ;;
  *) echo "netns.sh: unknown command '$cmd' (up, down, check)" >&2; exit 2 ;;
esac
