#!/bin/sh
# Install the project into a scratch prefix, build the consumer with the
# installed pkg-config file, and run it.
set -e
build=$1; src=$2; work=$3
rm -rf "$work"; mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
libdir=$(find "$work/prefix" -name slump.pc -printf '%h\n' | head -1)
export PKG_CONFIG_PATH="$libdir${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
mpicc -o "$work/consumer" "$src/consumer.c" $(pkg-config --cflags --libs slump) -lm
LD_LIBRARY_PATH="$(dirname "$libdir")" "$work/consumer"
echo "consumer linked against $(dirname "$libdir")/libslump.so and passed"
