#!/usr/bin/env bash
# Wall time of the whole `plan` command (load, search, robustness checks, shortcutting with
# the default --shortcut 3, writing) against --time, for the default scene, three benchmark
# scenes, a dense one and tests/data/fine_steps.yaml (0.1 ms steps: the longest paths to
# re-simulate); then a thousand robustness trials on scene_05 at --time 2. The bound is
# 5 % + 0.2 s. BENCHMARKS.md, "The time limit". PLANNERS lists the planners (default:
# pcrrt, the one the first figures are of).
#
#   benches/time_limit.sh [PUSHPLAN_BINARY] [TIMES...]
set -u
bin=${1:-target/release/pushplan}
shift || true
times=${*:-1 2 5}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# One run: scene, time, planner, extra flags.
run() {
  local scene=$1 t=$2 planner=$3
  shift 3
  local start end wall first
  start=$(date +%s.%N)
  first=$("$bin" plan "$scene" --planner "$planner" --time "$t" --threads 1 "$@" --quiet --out "$out/plan.json" 2>&1 | grep -v "^warning:" | head -1)
  end=$(date +%s.%N)
  wall=$(echo "$end - $start" | bc -l)
  printf '%-34s %-12s %6s %8.2f %8.2f  %s\n' "$scene" "$planner" "$t" "$wall" "$(echo "$wall - 1.05 * $t - 0.2" | bc -l)" "${first%% in *}"
}
printf '%-34s %-12s %6s %8s %8s  %s\n' scene planner time wall "past bound" outcome
for planner in ${PLANNERS:-pcrrt}; do
  for scene in scenes/herb_fig1_clutter.yaml scenes/benchmark/scene_03.yaml \
    scenes/benchmark/scene_12.yaml scenes/benchmark/scene_30.yaml scenes/dense/scene_05.yaml \
    tests/data/fine_steps.yaml; do
    for t in $times; do
      run "$scene" "$t" "$planner"
    done
  done
done
run scenes/benchmark/scene_05.yaml 2 push_kpiece --robust 1000
