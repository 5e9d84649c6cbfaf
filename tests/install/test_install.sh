#!/bin/sh
# Installs the built ttd into a temporary prefix, then builds and runs a consumer through
# find_package(ttd) (shared and static) and, where pkg-config exists, through ttd.pc.
# Usage: test_install.sh BUILD_DIR SOURCE_DIR
set -eu
build=$1
src=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/ttd-install.XXXXXX")
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
test -f "$work/prefix/include/ttd/ttd.h"
# bin/ holds the ttd program (when the CLI is built) and nothing else: no benchmark helpers.
if [ -d "$work/prefix/bin" ]; then
    extra=$(ls "$work/prefix/bin" | grep -vx ttd || true)
    if [ -n "$extra" ]; then
        echo "test_install: cmake --install put more than ttd in bin/: $extra" >&2
        exit 1
    fi
fi
# The installed program starts as installed: it finds libttd_gpu (and any other shared library of
# ours) through its relative RPATH, with no LD_LIBRARY_PATH.
if [ -x "$work/prefix/bin/ttd" ]; then
    if ! env -u LD_LIBRARY_PATH "$work/prefix/bin/ttd" --version >/dev/null; then
        echo "test_install: the installed bin/ttd does not start without LD_LIBRARY_PATH" >&2
        exit 1
    fi
    # and still when the whole prefix moves (the RPATH is relative to the program)
    mv "$work/prefix" "$work/moved"
    env -u LD_LIBRARY_PATH "$work/moved/bin/ttd" --version >/dev/null
    mv "$work/moved" "$work/prefix"
fi
cmake -S "$src/tests/install/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
libdir=$(dirname "$(find "$work/prefix" -name 'libttd.so*' | head -n 1)")
LD_LIBRARY_PATH="$libdir" "$work/consumer/consumer_shared"
"$work/consumer/consumer_static"
if command -v pkg-config >/dev/null 2>&1; then
    pc=$(dirname "$(find "$work/prefix" -name ttd.pc | head -n 1)")
    flags=$(PKG_CONFIG_PATH="$pc" pkg-config --cflags --libs ttd)
    # shellcheck disable=SC2086
    cc "$src/tests/install/consumer/main.c" $flags -o "$work/consumer_pc"
    LD_LIBRARY_PATH="$libdir" "$work/consumer_pc"
else
    echo "test_install: pkg-config not installed: ttd.pc not exercised (apt-get install pkg-config)"
fi
echo "test_install: ok"
