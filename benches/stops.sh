#!/usr/bin/env bash
# Why propagations stop (BENCHMARKS.md, "Dense clutter: what the search does"): one run
# of each planner on every scene of the paper's set (1-7 objects) and of the dense set
# (8-20 objects), SECONDS each, then, per scene class and planner, the share of
# propagations stopped by each rule, and the share that moved the goal object or other
# objects. The counts are run properties of the benchmark log (cpp/api/benchmark.cpp).
#
#   benches/stops.sh [SECONDS] [PLANNERS] [PUSHPLAN_BINARY]
set -eu
time=${1:-10}
planners=${2:-pcrrt,kpiece}
bin=${3:-target/release/pushplan}
out=${STOPS_OUT:-$(mktemp -d)}
mkdir -p "$out"
for class in benchmark dense; do
  "$bin" bench scenes/$class/*.yaml --planners "$planners" --runs 1 --time "$time" \
    --shortcut 0 --out "$out/$class" > "$out/$class.txt" 2>&1
done
reasons=$(for class in benchmark dense; do
  sqlite3 "$out/$class/results.db" "select name from pragma_table_info('runs') where name like 'stopped_by_%'"
done | sort -u)
header="| scenes | planner | propagations | steps each | stopped early"
rule="|---|---|---|---|---"
for r in $reasons; do header="$header | ${r#stopped_by_}"; rule="$rule|---"; done
echo "$header | moved the goal object | moved other objects |" | tr _ ' '
echo "$rule|---|---|"
for class in benchmark dense; do
  db="$out/$class/results.db"
  present=$(sqlite3 "$db" "select name from pragma_table_info('runs') where name like 'stopped_by_%'")
  sum_of() { if grep -qx "$1" <<< "$present"; then echo "total($1)"; else echo 0; fi; }
  all=0; cols=""
  for r in $reasons; do all="$all + $(sum_of "$r")"; cols="$cols, printf('%.1f %%', 100.0 * $(sum_of "$r") / total(propagations))"; done
  sqlite3 -separator ' | ' "$db" "
    select '| $class', p.name, cast(total(propagations) as int),
      printf('%.1f', total(propagation_steps) / total(propagations)),
      printf('%.1f %%', 100.0 * ($all) / total(propagations)) $cols,
      printf('%.1f %%', 100.0 * total(propagations_moving_the_goal_object) / total(propagations)),
      printf('%.1f %% |', 100.0 * total(propagations_moving_other_objects) / total(propagations))
    from runs r join plannerConfigs p on r.plannerid = p.id
    where propagations is not null group by p.name order by p.name"
done
echo "(logs and databases: $out)" >&2
