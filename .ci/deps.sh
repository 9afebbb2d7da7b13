#!/usr/bin/env bash
# Installs the Debian packages hbos needs, but only those missing (apt-get update runs once, and
# only when something is missing). Extra package names may be passed as arguments. numba, scipy
# and sklearn are PyOD's own dependencies: tests/python/test_pyod_live.py runs PyOD from its source.
set -euo pipefail
packages=(g++ cmake make libeigen3-dev libopencv-dev catch2 libbenchmark-dev libcli11-dev
          nlohmann-json3-dev libfmt-dev pkg-config libosmesa6-dev pybind11-dev python3-dev
          python3-numpy python3-pytest python3-dask python3-distributed
          python3-numba python3-scipy python3-sklearn "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq "${missing[@]}" >/dev/null
fi
