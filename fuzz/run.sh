#!/usr/bin/env bash
# Builds the snapshot-reader fuzzers with clang-14's libFuzzer and AddressSanitizer and runs each
# for SECONDS (default 120), seeded with assets/io. Findings land in build-fuzz/<format>/.
#   bash fuzz/run.sh [SECONDS]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=$root/build-fuzz
seconds=${1:-120}
mkdir -p "$out"
srcs=(sim/mapped_file.cpp sim/text_scan.cpp sim/xyz.cpp sim/lammps_dump.cpp sim/gsd.cpp
      sim/snapshot_file.cpp sim/error.cpp sim/atomic_file.cpp)
for fmt in 1:xyz 2:lammps 3:gsd; do
  id=${fmt%%:*} name=${fmt#*:}
  clang++-14 -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -DFUZZ_FORMAT="$id" -I"$root" -isystem /usr/include/eigen3 \
    "$root/fuzz/fuzz_snapshot.cpp" "${srcs[@]/#/$root/}" -o "$out/fuzz_$name" -lpthread
  mkdir -p "$out/$name/corpus" "$out/$name/findings"
  case $name in
    xyz) cp "$root"/assets/io/*.xyz "$root"/assets/io/*.extxyz "$out/$name/corpus/" ;;
    lammps) cp "$root"/assets/io/*.lammpstrj "$out/$name/corpus/" ;;
    gsd) cp "$root"/assets/io/*.gsd "$out/$name/corpus/" ;;
  esac
  (cd "$out/$name/findings" &&
    "$out/fuzz_$name" -max_total_time="$seconds" -rss_limit_mb=2048 -max_len=65536 \
      -print_final_stats=1 "$out/$name/corpus") || echo "fuzz_$name: a finding, see $out/$name/findings"
done
