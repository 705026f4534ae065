#!/usr/bin/env bash
# Installs the Debian 12 packages geotex needs, only those that are missing.
# Usage: scripts/setup-deps.sh [build|test|bench|fuzz]   (test and bench include build; fuzz is
# build plus clang and its libFuzzer/sanitizer runtimes)
set -euo pipefail

level=${1:-build}
pkgs=(build-essential cmake ninja-build pkg-config libcgal-dev libeigen3-dev
      libraptor2-dev librasqal3-dev nlohmann-json3-dev libyaml-cpp-dev libtbb-dev
      libcli11-dev catch2 libpng-dev libssl-dev
      libcurl4-gnutls-dev   # libcurl: geotex publish; the gnutls flavour, which libraptor2-dev depends on (the openssl one would remove it)
      pybind11-dev python3-dev python3-numpy  # the Python module (python/), for /usr/bin/python3
      libcpp-httplib-dev libjs-three)  # geotex view: the HTTP server, and three.js built into the binary
case "$level" in
  build) ;;
  # test: the RDF peers, GNU time (the corpus test's peak memory of each case), GNU parallel
  # (the sharded batch test), Virtuoso (the store test), xmllint (the datatypes test: an XML
  # Schema validator), strace (the limits test: -j1 starts no thread), pytest (the Python
  # module's tests, tests/python/), PyYAML (the workbench test reads the saved dictionary)
  # and Chromium (the workbench's browser test)
  test)  pkgs+=(raptor2-utils rasqal-utils python3 python3-rdflib time parallel virtuoso-opensource libxml2-utils strace
                python3-pytest python3-yaml
                chromium) ;;
  bench) pkgs+=(raptor2-utils rasqal-utils python3 python3-rdflib hyperfine time gnuplot-nox
                # make bench-perf: the CGAL demo meshes, MeshLab and the X server it needs
                libcgal-demo meshlab xvfb) ;;
  fuzz)  pkgs+=(clang libclang-rt-14-dev) ;;
  *) echo "setup-deps: unknown level '$level' (build, test, bench or fuzz)" >&2; exit 1 ;;
esac

# The JavaScript peers of the RDF tests (N3.js, rdf-validate-shacl, jsonld, Oxigraph), pinned by
# tests/js/package-lock.json; run after the Debian packages below. An existing node_modules
# is kept only when it holds every dependency of package.json at its pinned version, so that
# a package added to the pins is installed on machines set up before.
setup_js() {
  [ "$level" = build ] || [ "$level" = fuzz ] && return 0
  local here
  here=$(cd "$(dirname "$0")/.." && pwd)
  if [ -d "$here/tests/js/node_modules" ] && command -v node >/dev/null &&
     (cd "$here/tests/js" && node -e '
        const fs = require("fs"), deps = require("./package.json").dependencies;
        const ok = Object.entries(deps).every(([name, version]) => {
          const file = "node_modules/" + name + "/package.json";
          return fs.existsSync(file) && JSON.parse(fs.readFileSync(file, "utf8")).version === version;
        });
        process.exit(ok ? 0 : 1);'); then
    return 0
  fi
  if ! command -v npm >/dev/null; then
    echo "geotex setup: installing nodejs and npm" >&2
    "${sudo[@]}" apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null
  fi
  echo "geotex setup: npm ci in tests/js" >&2
  (cd "$here/tests/js" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
}

sudo=()
if [ "$(id -u)" -ne 0 ]; then sudo=(sudo); fi

missing=()
for p in "${pkgs[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [ "$status" = installed ] || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then setup_js; exit 0; fi

echo "geotex setup: installing ${missing[*]}" >&2
if [ ${#sudo[@]} -gt 0 ] && ! command -v sudo >/dev/null; then
  echo "setup-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
setup_js
