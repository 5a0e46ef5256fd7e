#!/usr/bin/env bash
# Two builds of pushplan side by side (BENCHMARKS.md: the "Tried" sections of issue 11):
# every scene and seed is planned by both binaries at once, each on one thread of its own
# core, so that both meet the same machine load. Prints each pair's times to solve, then
# per scene the runs each solved within the time limit, and the geometric mean of B's
# time over A's (a run not solved counts as the time limit). Plans are decided by
# propagation steps, not by the clock: a run solved well within the limit gives the same
# plan alone or beside another. The last column says whether the two plan files are the
# same byte for byte (a refactoring must keep every plan: "same" in every row).
#
#   benches/ab.sh A_BINARY B_BINARY SECONDS FIRST_SEED LAST_SEED SCENE... [-- PLAN_ARGS...]
#
# PLAN_ARGS go to both (e.g. `--planner kpiece`, `--restart 0`); AB_A_ARGS and AB_B_ARGS
# (words) to one of them only, e.g. AB_B_ARGS="--restart 800000"; AB_THREADS (default 1)
# the threads of each run.
set -u
[ $# -ge 6 ] || { sed -n '2,15p' "$0" >&2; exit 2; }
a=$1 b=$2 time=$3 first=$4 last=$5
shift 5
scenes=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do scenes+=("$1"); shift; done
[ $# -gt 0 ] && shift
plan_args=("$@")
read -r -a a_args <<< "${AB_A_ARGS:-}"
read -r -a b_args <<< "${AB_B_ARGS:-}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
source "$(dirname "$0")/solve_time.sh"
echo "| scene | seed | A (s) | B (s) | plan files |"
echo "|---|---|---|---|---|"
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .yaml)
  for seed in $(seq "$first" "$last"); do
    rm -f "$tmp/a.json" "$tmp/b.json"
    solve_time "$a" "$time" "$scene" "$seed" "$tmp/a.json" --threads "${AB_THREADS:-1}" "${plan_args[@]}" "${a_args[@]}" > "$tmp/a" &
    solve_time "$b" "$time" "$scene" "$seed" "$tmp/b.json" --threads "${AB_THREADS:-1}" "${plan_args[@]}" "${b_args[@]}" > "$tmp/b"
    wait
    if [ ! -e "$tmp/a.json" ] && [ ! -e "$tmp/b.json" ]; then same=none
    elif cmp -s "$tmp/a.json" "$tmp/b.json"; then same=same
    else same=differ; fi
    echo "$name $seed $(cat "$tmp/a") $(cat "$tmp/b") $same" | tee -a "$tmp/pairs" |
      awk '{ printf "| %s | %s | %.3f | %.3f | %s |\n", $1, $2, $3, $4, $5 }'
  done
done
echo
echo "| scene | runs | A solved | B solved | B / A, geometric mean |"
echo "|---|---|---|---|---|"
awk -v limit="$time" '
  { if (!($1 in runs)) order[++n] = $1
    runs[$1]++; sa[$1] += ($3 < limit); sb[$1] += ($4 < limit); lr[$1] += log($4 / $3)
    all++; ta += ($3 < limit); tb += ($4 < limit); tl += log($4 / $3) }
  END {
    for (i = 1; i <= n; i++) { s = order[i]
      printf "| %s | %d | %d | %d | %.2f |\n", s, runs[s], sa[s], sb[s], exp(lr[s] / runs[s]) }
    printf "| all | %d | %d | %d | %.2f |\n", all, ta, tb, exp(tl / all) }' "$tmp/pairs"
echo
awk '{ n[$5]++ } END { printf "plan files: %d same, %d differ, %d written by neither\n", n["same"], n["differ"], n["none"] }' "$tmp/pairs"
