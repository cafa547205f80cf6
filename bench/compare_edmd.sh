#!/usr/bin/env bash
# Collisions per CPU-second of grainshock against Smallenburg's EDMD (Eur. Phys. J. E 45, 22
# (2022)) on the same elastic 3D gas: N = 1e5 at packings 0.2, 0.4 and 0.5, the start of
# `run --initial thermal` (the state of the bench cases sim/thermal3d_phi*), warm-up 2 collisions
# per particle, then 20 per particle measured. EDMD is not built here: give the path of a binary
# you built from its public sources (it reads init.sph from its working folder and draws its own
# Maxwell velocities). EDMD should run microcanonically (thermostat off, as its paper's
# benchmarks do) and to a maxtime past the measured window. Its fastest variant depends on the
# packing (on 2 cores: Cell at 0.2, Single at 0.4 and 0.5): run the script once per variant.
#
#   bench/compare_edmd.sh GRAINSHOCK EDMD [PAIRS] [PACKING ...]
#   bench/compare_edmd.sh build/apps/grainshock /work/edmd/Single/md 3 0.2 0.4 0.5
#
# The two run at the same time, one per core, swapping cores every pair, so that a drift of the
# shared machine hits both; what is quoted is the ratio within each pair and its median. EDMD's
# CPU time is read from /proc at the output lines it prints once per unit of its time, so its
# window starts at the first line past the warm-up and ends at the first line 20 N collisions
# later (its rate is that of the whole lines' span, a little more than 20 N collisions).
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 GRAINSHOCK EDMD [PAIRS] [PACKING ...]" >&2
  exit 2
fi
gs=$(realpath "$1") edmd=$(realpath "$2") pairs=${3:-3}
shift $(($# < 3 ? $# : 3))
packings=(0.2 0.4 0.5)
[ $# -eq 0 ] || packings=("$@")
for phi in "${packings[@]}"; do  # the packings of the bench cases sim/thermal3d_phi*
  case $phi in 0.2 | 0.4 | 0.5) ;; *) echo "$0: packing $phi: not 0.2, 0.4 or 0.5" >&2; exit 2 ;; esac
done
for b in "$gs" "$edmd"; do
  [ -x "$b" ] || { echo "$0: $b is not an executable" >&2; exit 2; }
done
for t in taskset stdbuf mkfifo; do
  command -v "$t" >/dev/null || { echo "$0: $t (util-linux, coreutils) is needed" >&2; exit 2; }
done
n=100000
tick=$(getconf CLK_TCK)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# EDMD's input (.sph: N, the box's three sides, then "type x y z radius" per sphere) from the
# extended XYZ snapshot of grainshock's thermal start (diameter 1 in both).
make_input() {  # packing folder
  local density
  density=$(awk -v p="$1" 'BEGIN { printf "%.17g", p * 6 / 3.14159265358979324 }')
  "$gs" run --dim 3 --initial thermal --restitution 1 --particles "$n" --density "$density" \
    --t-max 1e-9 --snapshot-times 1e-9 --out "$2/run" --quiet --no-page >/dev/null
  awk 'NR == 1 { print } NR == 2 { match($0, /Lattice="[^"]*"/); split(substr($0, RSTART + 9,
       RLENGTH - 10), l, " "); printf "%.17g %.17g %.17g\n", l[1], l[5], l[9] }
       NR > 2 { printf "a %s %s %s 0.5\n", $2, $3, $4 }' "$2"/run/snapshots/*.xyz >"$2/init.sph"
}

# Runs EDMD on core $2 in folder $1 and prints its collisions per CPU-second over the window.
edmd_rate() {
  local dir=$1 core=$2 pid line coll cpu c0="" t0="" rate=""
  rm -f "$dir/fifo" && mkfifo "$dir/fifo"
  (cd "$dir" && exec taskset -c "$core" stdbuf -oL "$edmd" >fifo 2>&1) &
  pid=$!
  while IFS= read -r line; do
    case $line in *"Started thermostat"*) echo "$0: note: EDMD runs its thermostat" >&2 ;; esac
    [[ $line =~ Collisions:\ ([0-9]+) ]] || continue
    coll=${BASH_REMATCH[1]}
    cpu=$(awk -v t="$tick" '{ print ($14 + $15) / t }' "/proc/$pid/stat")
    if [ -z "$c0" ]; then
      if [ "$coll" -ge $((2 * n)) ]; then c0=$coll t0=$cpu; fi
    elif [ "$coll" -ge $((c0 + 20 * n)) ]; then
      rate=$(awk -v c="$((coll - c0))" -v t="$(awk -v a="$cpu" -v b="$t0" 'BEGIN { print a - b }')" \
        'BEGIN { printf "%.0f", c / t }')
      break
    fi
  done <"$dir/fifo"
  kill "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  [ -n "$rate" ] || { echo "$0: EDMD ended before its window (maxtime too short?)" >&2; exit 1; }
  echo "$rate"
}

for phi in "${packings[@]}"; do
  dir="$out/phi$phi"
  mkdir -p "$dir"
  make_input "$phi" "$dir"
  ratios=()
  for ((p = 0; p < pairs; ++p)); do
    a=$((p % 2)) b=$((1 - p % 2))
    taskset -c "$a" "$gs" bench "sim/thermal3d_phi$phi" >"$dir/ours" 2>&1 &
    pid=$!
    theirs=$(edmd_rate "$dir" "$b") || { kill "$pid"; exit 1; }
    wait "$pid"
    ours=$(awk '$1 == "collisions_per_cpu_second" { printf "%.0f", $2 }' "$dir/ours")
    [ -n "$ours" ] || { echo "$0: no figure from grainshock bench:" >&2; cat "$dir/ours" >&2; exit 1; }
    r=$(awk -v o="$ours" -v t="$theirs" 'BEGIN { printf "%.3f", o / t }')
    echo "packing $phi pair $((p + 1)): grainshock $ours  EDMD $theirs  collisions/CPU-s  ratio $r"
    ratios+=("$r")
  done
  printf '%s\n' "${ratios[@]}" | sort -g | awk -v phi="$phi" '{ v[NR] = $1 } END {
    m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
    printf "packing %s: median grainshock/EDMD over %d pairs: %.3f\n", phi, NR, m }'
done
