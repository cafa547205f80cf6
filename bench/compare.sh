#!/usr/bin/env bash
# Compares two grainshock builds on one bench figure. On a shared 2-core machine a figure drifts
# by 10% from minute to minute, so two builds measured one after the other cannot be told apart
# by less than that. Here they run at the same time, one per core (swapping cores every pair),
# and what is reported is the ratio within each pair and its median.
#
#   bench/compare.sh OLD_BINARY NEW_BINARY CASE FIGURE [PAIRS]   (CASE names one bench case)
#   bench/compare.sh /tmp/old/grainshock build/apps/grainshock sim/thermal3d_phi0.5 \
#       collisions_per_cpu_second 6
#
# Prints NEW / OLD for each pair and the median ratio (for a rate, above 1 means NEW is faster;
# for a time, below 1).
set -euo pipefail
if [ $# -lt 4 ]; then
  echo "usage: $0 OLD_BINARY NEW_BINARY CASE FIGURE [PAIRS]" >&2
  exit 2
fi
old=$1 new=$2 case=$3 figure=$4 pairs=${5:-6}
for b in "$old" "$new"; do
  [ -x "$b" ] || { echo "$0: $b is not an executable" >&2; exit 2; }
done
command -v taskset >/dev/null || { echo "$0: taskset (util-linux) is needed" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

value() {  # the figure's value in a bench table
  awk -v f="$figure" '$1 == f { print $2; found = 1; exit } END { exit !found }' "$1" || {
    echo "$0: no figure $figure in the output of case $case:" >&2
    cat "$1" >&2
    exit 2
  }
}

ratios=()
for ((p = 0; p < pairs; ++p)); do
  a=$((p % 2)) b=$((1 - p % 2))
  taskset -c "$a" "$old" bench "$case" >"$out/old" 2>&1 &
  pid=$!
  taskset -c "$b" "$new" bench "$case" >"$out/new" 2>&1
  wait "$pid"
  o=$(value "$out/old")
  n=$(value "$out/new")
  r=$(awk -v o="$o" -v n="$n" 'BEGIN { printf "%.4f", n / o }')
  echo "pair $((p + 1)): old $o  new $n  new/old $r"
  ratios+=("$r")
done
printf '%s\n' "${ratios[@]}" | sort -g |
  awk '{ v[NR] = $1 } END { m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
                            printf "median new/old over %d pairs: %.4f\n", NR, m }'
