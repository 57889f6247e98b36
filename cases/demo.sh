#!/usr/bin/env bash
# The flagship demo on a fresh Debian 12 machine: install, build, then run
# Bingham plane-Couette cessation (Bn = 1, Papanastasiou m = 1e4, top plate
# stopped at t = 0) with adaptive BDF2 (IDA, order <= 2) until arrest.
# Outputs go to out/couette_cessation/ (summary.csv, series.csv, steps.csv,
# fields.xmf + fields.h5 for ParaView). Extra options are passed to slump.
set -euo pipefail
cd "$(dirname "$0")/.."
bash cases/setup.sh
exec ./build/slump -scene couette_cessation "$@"
