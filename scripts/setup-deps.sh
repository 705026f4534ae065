#!/usr/bin/env bash
# Installs the Debian 12 packages geotex needs, only those that are missing.
# Usage: scripts/setup-deps.sh [build|test|bench]   (each level includes the previous)
set -euo pipefail

level=${1:-build}
pkgs=(build-essential cmake ninja-build pkg-config libcgal-dev libeigen3-dev
      libraptor2-dev librasqal3-dev nlohmann-json3-dev libyaml-cpp-dev libtbb-dev
      libcli11-dev catch2 libpng-dev)
case "$level" in
  build) ;;
  test)  pkgs+=(raptor2-utils rasqal-utils python3) ;;
  bench) pkgs+=(raptor2-utils rasqal-utils python3 hyperfine time gnuplot-nox) ;;
  *) echo "setup-deps: unknown level '$level' (build, test or bench)" >&2; exit 1 ;;
esac

missing=()
for p in "${pkgs[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [ "$status" = installed ] || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "geotex setup: installing ${missing[*]}" >&2
sudo=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
