#!/usr/bin/env bash
# Optional: the libraries the benchmarks compare against in the same run (not needed to build or
# test). Open CASCADE 7.6 for the curve benchmark (and its meshing module, BRepMesh, for the tessellation benchmark); OpenSubdiv is already a dependency.
set -euo pipefail
sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends libocct-modeling-data-dev libocct-modeling-algorithms-dev libocct-foundation-dev libtbb-dev
