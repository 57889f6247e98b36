#!/usr/bin/env bash
# Install slump's Debian 12 packages and build it (into ./build).
# Used by cases/demo.sh (the README's first command) and by .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends \
  build-essential cmake pkg-config python3 \
  petsc-dev slepc-dev libsundials-dev libmetis-dev \
  libhdf5-openmpi-dev hdf5-tools libopenmpi-dev openmpi-bin gnuplot-nox > /dev/null
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j "$(nproc)"
