#!/usr/bin/env bash
# The pictures at the top of README.md, made again from the built binary:
#   bash scripts/readme_pictures.sh [BUILD_DIR]     (default: build)
# writes assets/readme/fig1.png (the Fig. 1(a) overlay: one kick of 2.5e5 discs at n = 0.25,
# r = 0.1, drawn at the paper's times 5000 to 50000, 640x320) and assets/readme/movie_strip.png
# (the four frames of the movie of the same snapshots, the camera following the front, 320x240
# each, two by two).
# Takes under a minute on 2 cores; needs ffmpeg (the command-line tool) to tile the frames.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
gs="$build/apps/grainshock"
out="$here/assets/readme"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# The Fig. 1 job's physics and times (simulation time is twice the paper's at n = 0.25).
"$gs" run --quiet --medium box --particles 250000 --restitution 0.1 --seed 1 --t-max 100000 \
  --snapshot-times 10000,20000,40000,100000 --out "$work/run"
snaps=("$work"/run/snapshots/tsim_{10000,20000,40000,100000}.xyz)
"$gs" render "${snaps[@]}" --width 640 --height 320 --compression 9 --out "$out/fig1.png"
"$gs" movie --quiet "${snaps[@]}" --width 320 --height 240 --keep-frames \
  --out "$work/movie"
ffmpeg -loglevel error -y -i "$work/movie/frames/frame_%05d.png" -vf tile=2x2 -frames:v 1 \
  -compression_level 100 "$out/movie_strip.png"
ls -l "$out"
