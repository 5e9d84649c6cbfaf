#!/usr/bin/env bash
# Installs optional Debian packages with apt-get when this runs as root (or with password-less
# sudo); otherwise, or when apt-get fails, says what is missing. Never fails: its callers carry
# on without the packages, each saying what it skips.
# Usage: scripts/install-optional.sh CALLER PACKAGE...     (CALLER names the script in messages)
set -uo pipefail
caller=$1
shift
[ $# -gt 0 ] || exit 0
sudo=""
if [ "$(id -u)" != 0 ] && command -v sudo > /dev/null 2>&1 && sudo -n true 2> /dev/null; then
    sudo="sudo -n"
fi
if command -v apt-get > /dev/null 2>&1 && { [ "$(id -u)" = 0 ] || [ -n "$sudo" ]; }; then
    echo "$caller: installing the Debian packages $* with apt-get (apt-get lists them with what they depend on)" >&2
    if ! { $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q "$@"; } >&2; then
        echo "$caller: apt-get could not install $*; carrying on without" >&2
    fi
else
    echo "$caller: $* not installed and apt-get is not usable here; carrying on without (apt-get install $*)" >&2
fi
exit 0
