#!/usr/bin/env bash
# Installs the Debian 12 packages Caustica builds with; does nothing when they are all present.
set -euo pipefail
packages=(build-essential cmake pkg-config libglm-dev libnanoflann-dev libopenimageio-dev
          libtbb-dev catch2 nlohmann-json3-dev libcli11-dev libtinyobjloader-dev fonts-dejavu-core
          openimageio-tools libpugixml-dev zlib1g-dev libembree-dev
          libopenvdb-dev libboost-dev  # OpenVDB grids for heterogeneous media (its headers include Boost's)
          libopenmpi-dev openmpi-bin  # MPI: one image on many machines (docs/cluster.md)
          python3-dev python3-pybind11 pybind11-dev python3-numpy  # `import caustica` (docs/python.md)
          python3-pytest python3-matplotlib python3-nbconvert python3-ipykernel jupyter-notebook  # its tests and examples
          glmark2-data)  # glmark2-data: the Stanford bunny of scenes/cornell-bunny.json
packages+=("$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
