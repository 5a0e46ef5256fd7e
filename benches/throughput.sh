#!/usr/bin/env bash
# The tree-growth benchmark of BENCHMARKS.md ("Dense clutter"): PC RRT on the throughput
# scenes (1, 7 and 12 objects, goal out of reach so the tree grows for the whole time),
# nearest neighbours with the default budget and exact, one after the other, one thread
# each (plan's default is every core: two searches would halve each one's tree), seed 1.
# Prints, at the first progress report past 1 000, 10 000 and 50 000 tree states, the
# propagation steps/s over the last second and the share of that second spent
# propagating (the planner's throughput as a fraction of bare propagation).
#
#   benches/throughput.sh [SECONDS] [PUSHPLAN_BINARY]
set -u
time=${1:-60}
bin=${2:-target/release/pushplan}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
row() {  # label, progress log
  awk -v label="$1" '
    /searching:/ {
      for (i = 1; i <= NF; i++) {
        if ($i == "steps/s,") rate = $(i - 1)
        if ($i == "propagating,") share = $(i - 2)
        if ($i == "tree") size = $(i + 2)
      }
      for (k = 1; k <= 3; k++)
        if (!done[k] && size + 0 >= target[k]) { done[k] = 1; cell[k] = sprintf("%.0f k/s, %s %%", rate / 1000, share) }
    }
    BEGIN { target[1] = 1000; target[2] = 10000; target[3] = 50000 }
    END { printf "| %s | %s | %s | %s | %s states |\n", label, cell[1] ? cell[1] : "-", cell[2] ? cell[2] : "-", cell[3] ? cell[3] : "-", size }' "$2"
}
echo "| scene, nearest neighbours | at 1 000 states | at 10 000 | at 50 000 | tree after ${time} s |"
echo "|---|---|---|---|---|"
for scene in benches/scenes/throughput_*.yaml; do
  name=$(basename "$scene" .yaml)
  exact="$(dirname "$scene")/.exact_$name.yaml"  # beside the scene: its URDF path is relative
  { cat "$scene"; echo "planner: {nearest_checks: 0}"; } > "$exact"
  "$bin" plan "$scene" --planner pcrrt --threads 1 --time "$time" --seed 1 --shortcut 0 --robust 0 --out "$tmp/$name.json" 2> "$tmp/$name.budget.log" > /dev/null
  "$bin" plan "$exact" --planner pcrrt --threads 1 --time "$time" --seed 1 --shortcut 0 --robust 0 --out "$tmp/$name.exact.json" 2> "$tmp/$name.exact.log" > /dev/null
  rm -f "$exact"
  row "$name, 128 checks" "$tmp/$name.budget.log"
  row "$name, exact" "$tmp/$name.exact.log"
done
