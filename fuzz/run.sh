#!/usr/bin/env bash
# Builds the snapshot-reader fuzzers with clang-14's libFuzzer, AddressSanitizer and UBSan and
# runs each for SECONDS (default 120), seeded with assets/io and what earlier runs found to be
# new. Crashes, leaks and out-of-memory inputs land in build-fuzz/<format>/findings/; re-run one
# with build-fuzz/fuzz_<format> FILE. Not part of the CMake build or CI (needs clang).
#   bash fuzz/run.sh [SECONDS] [xyz|lammps|gsd ...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=$root/build-fuzz
seconds=${1:-120}
shift || true
formats=("$@")
[ ${#formats[@]} -gt 0 ] || formats=(xyz lammps gsd)
mkdir -p "$out"
srcs=(io/mapped_file.cpp io/text_scan.cpp io/xyz.cpp io/lammps_dump.cpp io/gsd.cpp
      io/snapshot_file.cpp sim/error.cpp io/atomic_file.cpp io/atomic_masses.cpp io/gunzip.cpp)
status=0
for name in "${formats[@]}"; do
  case $name in
    xyz) id=1 seeds=("$root"/assets/io/*.xyz "$root"/assets/io/*.extxyz) ;;
    lammps) id=2 seeds=("$root"/assets/io/*.lammpstrj) ;;
    gsd) id=3 seeds=("$root"/assets/io/*.gsd) ;;
    *) echo "unknown format '$name' (use xyz, lammps or gsd)" >&2; exit 2 ;;
  esac
  clang++-14 -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -DFUZZ_FORMAT="$id" -I"$root" -isystem /usr/include/eigen3 \
    "$root/fuzz/fuzz_snapshot.cpp" "${srcs[@]/#/$root/}" -o "$out/fuzz_$name" -lpthread -lz
  mkdir -p "$out/$name/corpus" "$out/$name/findings"
  cp "${seeds[@]}" "$out/$name/corpus/"
  (cd "$out/$name/findings" &&
    "$out/fuzz_$name" -max_total_time="$seconds" -rss_limit_mb=2048 -max_len=65536 \
      -print_final_stats=1 "$out/$name/corpus") || {
    echo "fuzz_$name: a finding, see $out/$name/findings"
    status=1
  }
done
exit $status
