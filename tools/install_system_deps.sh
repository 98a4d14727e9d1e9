#!/bin/sh
# System libraries for homesim's extras: OSMesa (software OpenGL) for `homesim.render`.
# Installs only what is missing; needs root (or sudo) when something is missing.
set -e
missing=""
ldconfig -p 2>/dev/null | grep -q "libOSMesa.so" || missing="$missing libosmesa6"
[ -z "$missing" ] && exit 0
if [ "$(id -u)" = "0" ]; then SUDO=""; elif command -v sudo >/dev/null; then SUDO="sudo -n"; else
  echo "install_system_deps: need root to install:$missing (rendering tests will skip)" >&2
  exit 0
fi
echo "install_system_deps: installing$missing" >&2
$SUDO apt-get update -qq >/dev/null 2>&1 || true
# shellcheck disable=SC2086
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $missing >/dev/null
