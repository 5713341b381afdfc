#!/usr/bin/env bash
# Install the Debian packages demcal needs (build, tests, MPI batches, plots).
# Idempotent: prints nothing and exits 0 when everything is already installed.
set -euo pipefail

packages=(
  build-essential cmake make pkg-config git
  libeigen3-dev libceres-dev libhdf5-dev nlohmann-json3-dev
  libgtest-dev libboost-dev libcli11-dev
  libopenmpi-dev openmpi-bin
  python3-matplotlib python3-numpy python3-h5py
  python3-jsonschema python3-markdown python3-pytest python3-emcee
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: missing Debian packages: ${missing[*]}; run as root (sudo $0) or install them with apt-get" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
