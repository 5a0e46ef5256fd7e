#!/usr/bin/env bash
# Time to solve on more cores (BENCHMARKS.md, "Every core of a bigger machine"): every
# scene x seed with `plan --threads T` for each T given, all in one run, no shortcutting
# (benches/solve_time.sh: the first solution's time; a run not solved counts as the
# limit). Runs of T threads go JOBS_T at a time (JOBS="1:4 4:2" runs four one-thread runs
# at once and two four-thread runs; one at a time where unnamed), so that the one-thread
# runs of a many-core machine need not take an hour; say beside the figures what ran at
# once. FIRST_SEED (default 1) starts the seeds elsewhere. Prints a line per run as it ends (stderr), then a table per scene and run, and per
# thread count the runs solved, the median time and the ratio of medians to one thread's.
#
#   [JOBS="1:4 4:2"] [FIRST_SEED=1] benches/scaling.sh SECONDS SEEDS BINARY "1 4 8 16" SCENES...
set -u
limit=${1:?seconds}
seeds=${2:?seeds}
bin=${3:?pushplan binary}
counts=${4:?thread counts, e.g. "1 4 8 16"}
shift 4
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || { echo "scaling.sh: no scenes given" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
here=$(cd "$(dirname "$0")" && pwd)
seed_list=$(seq "${FIRST_SEED:-1}" $(( ${FIRST_SEED:-1} + seeds - 1 )))
read -r first _ <<< "$counts"

jobs_for() {  # threads -> runs at once
  local pair
  for pair in ${JOBS:-}; do
    [ "${pair%%:*}" = "$1" ] && { echo "${pair#*:}"; return; }
  done
  echo 1
}

# One run: threads scene seed -> "threads scene seed seconds" in $tmp/runs.
run_one() {
  source "$here/solve_time.sh"
  local threads=$1 scene=$2 seed=$3 name seconds
  name=$(basename "$(dirname "$scene")")/$(basename "$scene" .yaml)
  seconds=$(solve_time "$bin" "$limit" "$scene" "$seed" "$tmp/$threads-${name//\//-}-$seed.json" --threads "$threads")
  echo "$threads $name $seed $seconds" | tee -a "$tmp/runs" >&2
}
export -f run_one
export here bin limit tmp

start=$(date +%s)
for threads in $counts; do
  for scene in "${scenes[@]}"; do
    for seed in $seed_list; do
      echo "$threads $scene $seed"
    done
  done | xargs -P "$(jobs_for "$threads")" -L1 bash -c 'run_one "$@"' _
  echo "# $threads threads done after $(( $(date +%s) - start )) s" >&2
done

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
echo "| scene | seed |$(for t in $counts; do printf ' %s thr. (s) |' "$t"; done)"
echo "|---|---|$(for t in $counts; do printf -- '---|'; done)"
for scene in "${scenes[@]}"; do
  name=$(basename "$(dirname "$scene")")/$(basename "$scene" .yaml)
  for seed in $seed_list; do
    row="| $name | $seed |"
    for threads in $counts; do
      row+=" $(awk -v t="$threads" -v n="$name" -v s="$seed" '$1 == t && $2 == n && $3 == s { print $4 }' "$tmp/runs") |"
    done
    echo "$row"
  done
done
echo
one=$(awk -v t="$first" '$1 == t { print $4 }' "$tmp/runs" | median)
echo "| threads | runs at once | solved within $limit s | median time to solve (s) | ratio of medians to $first thread(s) |"
echo "|---|---|---|---|---|"
for threads in $counts; do
  awk -v t="$threads" -v l="$limit" '$1 == t { n++; if ($4 < l) s++ } END { printf "%d %d\n", s, n }' "$tmp/runs" > "$tmp/solved"
  read -r solved runs < "$tmp/solved"
  med=$(awk -v t="$threads" '$1 == t { print $4 }' "$tmp/runs" | median)
  awk -v t="$threads" -v j="$(jobs_for "$threads")" -v s="$solved" -v n="$runs" -v m="$med" -v o="$one" \
    'BEGIN { printf "| %s | %s | %d of %d | %.3f | %.2fx |\n", t, j, s, n, m, o / m }'
done
