#!/usr/bin/env bash
# The README's main job: installs what is missing, builds the renderer and the dynamic-scene
# benchmark, renders a short walking_xyz sequence (two seeds) and runs the front end on it with
# no mask, the eroded mask, and the screens none / chi2 / HBOS default, then prints the table
# (mean ± standard deviation over the seeds). Results, per-cell outputs and figures go to
# out/dynbench-demo/ (a re-run reuses the finished cells). Extra arguments are passed to
# hbos-dynbench (try --help; --full is the whole benchmark, see docs/results.md).
# The 37-frame run on real TUM frames is .ci/demo-real.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/deps.sh pkg-config libosmesa6-dev
# A unity build: a one-off build of these ~60 files spends most of its time parsing the same
# OpenCV, Eigen and CLI11 headers in each (3 min 36 s -> 2 min 59 s here, 2 cores; 2 min 9 s
# with the command parsers out of hbos_slam); the test builds compile every file on its own.
cmake -S . -B build-demo -DCMAKE_BUILD_TYPE=Release -DHBOS_BUILD_TESTS=OFF \
  -DHBOS_BUILD_BENCHMARKS=OFF -DCMAKE_UNITY_BUILD=ON >/dev/null
cmake --build build-demo -j"$(nproc)" --target hbos-dynbench hbos-render
./build-demo/examples/dynbench/hbos-dynbench --scenarios walking_xyz --variants eroded \
  --seeds 1,2 --frames 60 --screens none,chi2,default --out out/dynbench-demo "$@"
