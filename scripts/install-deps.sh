#!/usr/bin/env bash
# Installs every Debian package freeform needs to build, test and run, and nothing else.
# Idempotent: packages already present are skipped, so running it twice costs one dpkg query.
#
#   scripts/install-deps.sh          # build + tests + editor
#
# Why each package is here is written down in docs/dependencies.md.
set -euo pipefail

packages=(
  build-essential cmake pkg-config      # toolchain
  ninja-build                           # the Ninja generator (scripts/test.sh)
  libeigen3-dev                         # vectors and matrices (header-only)
  nlohmann-json3-dev                    # the JSON document format (header-only)
  libcli11-dev                          # command-line parsing of the freeform tool (header-only)
  catch2                                # unit tests (v2.13, single header)
  libbenchmark-dev                      # benchmarks (not run by the tests)
  libosd-dev                            # OpenSubdiv 3.5: subdivision limit surfaces
  libassimp-dev                         # mesh import (glTF, and cross-checks)
  libglfw3-dev libgl-dev libepoxy-dev   # editor: window, OpenGL, GL function loader
  libimgui-dev libstb-dev               # editor: Dear ImGui 1.86 (+ GLFW/OpenGL3 backends), stb
  xvfb xauth libgl1-mesa-dri            # headless rendering (render tests, screenshots)
  pybind11-dev python3-dev python3-numpy   # the Python module (python/, docs/python.md)
  python3-pytest                        # its tests (run by ctest)
  python3-dask python3-distributed      # Python: scaling out on Dask (examples/python/batch_ffd_dask.py, its test)
  python3-mypy                          # Python: mypy.stubtest checks python/freeform.pyi in the tests
  valgrind                              # Python: the memcheck test of the module's shape checks
  xdotool                               # editor test driving the real window under Xvfb (x11 label)
  clang libfuzzer-14-dev                # sanitizer + fuzzing build (scripts/test.sh, fuzz.sh): clang 14 + libFuzzer
  assimp-testmodels                     # files other tools wrote: fuzz seeds, reader tests
  libocct-data-exchange-dev             # Open CASCADE 7.6: STEP and IGES parts (cad/, docs/cad.md) and the tests' reference
  occt-misc                             # Open CASCADE's sample parts (STEP, IGES, .brep): the CAD tests read them
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
