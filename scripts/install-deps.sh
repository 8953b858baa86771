#!/usr/bin/env bash
# Installs what fireswarm needs to build and test, from Debian 12 packages only.
# Idempotent and non-interactive: apt is skipped when every package is present,
# so CI and developers can run it before every build. Also adds the loopback
# multicast route that LCM's udpm:// needs on a machine whose only interface is lo.
set -euo pipefail

PACKAGES=(
  cmake g++ make pkg-config git
  liblcm-dev liblcm-bin
  libeigen3-dev libompl-dev libgeographiclib-dev libbox2d-dev
  libboost-dev libboost-system-dev libboost-program-options-dev
  libboost-serialization-dev libboost-filesystem-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev libyaml-cpp-dev libspdlog-dev
  libssl-dev libsqlite3-dev
  lld
  iproute2
  clang libclang-rt-dev
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "install-deps: missing packages: ${missing[*]}; run this script as root" >&2
    exit 1
  fi
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# LCM udpm:// needs a route for 224.0.0.0/4. Where a default route exists the
# kernel uses it; on a machine with only lo we add one. Best effort: without
# root or iproute2 the udpm:// tests skip and say why.
if command -v ip >/dev/null 2>&1 && [ "$(id -u)" -eq 0 ]; then
  if ! ip route show default 2>/dev/null | grep -q . &&
     ! ip route show 224.0.0.0/4 2>/dev/null | grep -q .; then
    ip link set lo up 2>/dev/null || true
    ip link set lo multicast on 2>/dev/null || true
    ip route add 224.0.0.0/4 dev lo 2>/dev/null &&
      echo "install-deps: added multicast route 224.0.0.0/4 on lo" || true
  fi
fi

# The command-center page's browser tests: chromium, Node.js and web/'s npm packages.
bash "$(dirname "$0")/install-web-deps.sh"

# fireswarm sweep's Slurm test (ctest -L slurm) needs a single-node Slurm. Its
# packages set themselves up as their own system users (munge's postinst runs
# `su munge -s /bin/sh`); where a system user cannot run a shell (a root
# directory others may not enter, as in a chroot made with mktemp -d) they would
# stay half-configured and every later apt-get would fail. There they are left
# out, saying so, and the Slurm test skips, saying why.
SLURM_PACKAGES=(slurmctld slurmd slurm-client munge)
slurm_missing=()
for p in "${SLURM_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || slurm_missing+=("$p")
done
if [ ${#slurm_missing[@]} -gt 0 ] && [ "$(id -u)" -eq 0 ]; then
  if su -s /bin/sh nobody -c true >/dev/null 2>&1; then
    echo "install-deps: installing ${slurm_missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    [ ${#missing[@]} -gt 0 ] || apt-get update -qq
    # Last, and never fatal: the build and every other test do not need Slurm.
    apt-get install -y -qq --no-install-recommends "${slurm_missing[@]}" >/dev/null ||
      echo "install-deps: WARNING: installing ${slurm_missing[*]} failed (see above);" \
           "the Slurm test (ctest -L slurm) will skip" >&2
  else
    echo "install-deps: not installing ${slurm_missing[*]}: a system user cannot run" \
         "/bin/sh here (su -s /bin/sh nobody fails), which their setup needs; the Slurm" \
         "test (ctest -L slurm) will skip" >&2
  fi
fi
