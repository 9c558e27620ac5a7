#!/usr/bin/env bash
# Installs what zonesim needs (Debian packages) and configures + builds into build/.
# Sourced by test.sh and demo.sh; safe to run again (installs only what is missing).
set -euo pipefail

ZONESIM_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config
  libopenmpi-dev openmpi-bin
  libeigen3-dev
  cyclonedds-dev cyclonedds-tools
  flatbuffers-compiler libflatbuffers-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers pocl-opencl-icd
  libcli11-dev libyaml-cpp-dev nlohmann-json3-dev
  python3 python3-matplotlib
  python3-yaml  # bench/tune.py reads scenes and writes overlays
  python3-flatbuffers python3-numpy  # recordings read from Python (inspector/, tests)
  chromium python3-websockets  # the inspector_browser test: headless Chromium over its DevTools protocol
  libbullet-dev
  clang libclang-rt-14-dev
  iproute2  # ip netns, veth and bridge for the multi_host test (deploy/netns.sh)
  openssh-server openssh-client  # sshd in each namespace for the multi_host_ssh test; ssh for reach = ssh
  slurmctld slurmd slurm-client munge  # a one-node Slurm for the slurm_cluster test; srun for reach = slurm
  libsqlite3-dev libpq-dev  # the ledger's two back ends (ledger/)
  postgresql  # the server the ledger's PostgreSQL tests and benchmark start in a temporary folder
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "== installing: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

BUILD_DIR="${ZONESIM_BUILD_DIR:-$ZONESIM_ROOT/build}"
JOBS="${ZONESIM_JOBS:-$(nproc)}"
echo "== configure + build in $BUILD_DIR ($JOBS jobs)"
start=$(date +%s)
cmake -S "$ZONESIM_ROOT" -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$BUILD_DIR" -j "$JOBS"
echo "== build took $(( $(date +%s) - start )) s"

# mpirun as root (containers, CI) must be allowed explicitly.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
