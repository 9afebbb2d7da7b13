#!/usr/bin/env bash
# The second demo: installs what is missing, builds the example SLAM front end and runs it on its
# embedded default (37 real TUM fr1/xyz RGB-D frames with a real person composited in),
# screening matches with the default HBOS screen. Results, plots and a summary go to out/slam/.
# Extra arguments are passed to hbos-slam (try --help).
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/deps.sh
cmake -S . -B build-demo -DCMAKE_BUILD_TYPE=Release -DHBOS_BUILD_TESTS=OFF \
  -DHBOS_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-demo -j"$(nproc)" --target hbos-slam
./build-demo/examples/slam/hbos-slam "$@"
