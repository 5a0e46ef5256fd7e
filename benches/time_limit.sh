#!/usr/bin/env bash
# Wall time of the whole `plan` command (load, search, shortcutting with the default
# --shortcut 3, writing) against --time, for the default scene, three benchmark scenes
# and a dense one. BENCHMARKS.md, "The time limit". PLANNER picks the planner (default:
# pcrrt, the one those figures are of).
#
#   benches/time_limit.sh [PUSHPLAN_BINARY] [TIMES...]
set -u
bin=${1:-target/release/pushplan}
shift || true
times=${*:-1 2 5}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '%-34s %6s %8s %8s  %s\n' scene time wall over outcome
for scene in scenes/herb_fig1_clutter.yaml scenes/benchmark/scene_03.yaml \
  scenes/benchmark/scene_12.yaml scenes/benchmark/scene_30.yaml scenes/dense/scene_05.yaml; do
  for t in $times; do
    start=$(date +%s.%N)
    first=$("$bin" plan "$scene" --planner "${PLANNER:-pcrrt}" --time "$t" --threads 1 --quiet --out "$out/plan.json" 2>&1 | head -1)
    end=$(date +%s.%N)
    wall=$(echo "$end - $start" | bc -l)
    printf '%-34s %6s %8.2f %8.2f  %s\n' "$scene" "$t" "$wall" "$(echo "$wall - $t" | bc -l)" "${first%% in *}"
  done
done
