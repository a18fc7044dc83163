#!/usr/bin/env bash
# Installs the Debian packages shoremesh needs to build, test and run its demo.
# Idempotent: installs only what is missing, so `make demo` and `make test` can call it every time.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev      # Delaunay, exact arithmetic
  voro++-dev                                           # independent 3D Voronoi verifier
  libopencv-dev                                        # coastline tracing
  libgeographiclib-dev                                 # GPS projections
  libopenimageio-dev openimageio-tools                 # previews, GeoTIFF tags (its CMake targets name the tools)
  libgdal-dev libproj-dev                              # DEM rasters, coordinate systems, scale factors (PROJ)
  gdal-bin python3-gdal                                # tests: independent raster reads and test rasters
  libpugixml-dev nlohmann-json3-dev                    # GPX (XML) and GeoJSON parsers
  libcli11-dev                                         # command line
  libtbb-dev
  libjemalloc-dev                                      # the executables' allocator (huge pages)
  libgtest-dev libgmock-dev libbenchmark-dev           # tests and benchmarks
  python3-meshio python3-numpy gmsh                    # third-party readers of our exports (tests)
  libcpp-httplib-dev                                   # serve: the editor's HTTP server
  chromium                                             # serve: the editor's browser test (headless)
)
# serve's page is bundled with npm at build time; a Node.js from elsewhere (with its own npm) will do.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then packages+=(nodejs npm); fi
if [ "${1:-}" = "--list" ]; then printf '%s\n' "${packages[@]}"; exit 0; fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then exit 0; fi

echo "shoremesh: installing missing Debian packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
