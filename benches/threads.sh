#!/usr/bin/env bash
# Parallel search (BENCHMARKS.md, "Every core"): `plan --threads 1` and `--threads N`
# interleaved scene by scene in one run (nothing else should run meanwhile), no
# shortcutting; prints each pair's times to solve and the median speedup over the pairs
# solved by both (a run not solved counts as the time limit). PLANNER picks the planner
# (default: plan's own, push_kpiece; the figures of BENCHMARKS.md before 2026-11-23 are
# PC RRT's: PLANNER=pcrrt).
#
#   benches/threads.sh [N] [SECONDS] [SEEDS] [PUSHPLAN_BINARY] [SCENES...]
set -u
threads=${1:-2}
time=${2:-30}
seeds=${3:-1}
bin=${4:-target/release/pushplan}
shift $(( $# < 4 ? $# : 4 ))
scenes=("$@")
[ ${#scenes[@]} -eq 0 ] && scenes=(scenes/benchmark/*.yaml)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
source "$(dirname "$0")/solve_time.sh"
solve_threads() {  # threads, scene, seed
  solve_time "$bin" "$time" "$2" "$3" "$tmp/plan.json" --planner "${PLANNER:-push_kpiece}" --threads "$1"
}
echo "| scene | seed | 1 thread (s) | $threads threads (s) | speedup |"
echo "|---|---|---|---|---|"
for scene in "${scenes[@]}"; do
  for seed in $(seq 1 "$seeds"); do
    one=$(solve_threads 1 "$scene" "$seed")
    many=$(solve_threads "$threads" "$scene" "$seed")
    echo "$(basename "$scene" .yaml) $seed $one $many" >> "$tmp/pairs"
    awk -v s="$(basename "$scene" .yaml)" -v seed="$seed" -v a="$one" -v b="$many" \
      'BEGIN { printf "| %s | %s | %.3f | %.3f | %.2f |\n", s, seed, a, b, a / b }'
  done
done
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
one=$(awk '{ print $3 }' "$tmp/pairs" | median)
many=$(awk '{ print $4 }' "$tmp/pairs" | median)
ratio=$(awk '{ print $3 / $4 }' "$tmp/pairs" | median)
# The geometric mean of the per-run speedups: at medians of a few hundredths of a second
# the median moves with the seeds drawn (BENCHMARKS.md); this summary moves less.
geomean=$(awk '{ s += log($3 / $4) } END { print exp(s / NR) }' "$tmp/pairs")
runs=$(wc -l < "$tmp/pairs")
awk -v a="$one" -v b="$many" -v r="$ratio" -v g="$geomean" -v n="$runs" -v t="$threads" 'BEGIN {
  printf "\nmedian time to solve over %d runs: %.3f s on 1 thread, %.3f s on %d: %.2fx (median of the per-run speedups: %.2fx; their geometric mean: %.2fx)\n", n, a, b, t, a / b, r, g }'
