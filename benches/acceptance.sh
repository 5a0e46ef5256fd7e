#!/usr/bin/env bash
# The planners side by side (BENCHMARKS.md, "The acceptance"): from the database
# of a `pushplan bench` folder (merged, if it ran in shards), per scene set (experiments
# named SET-NN: `benchmark`, the paper's 35 scenes; `dense`) and planner: runs, runs
# solved exactly within each budget (OMPL's status "Exact solution"; its `solved` column
# also counts approximate paths), scenes with such a run within each budget, the median
# time to solve (unsolved runs count as never) and the runs that ended approximate.
# SST improves its path until the time limit and records the limit as its time: its
# exact runs count at the limit only.
#
#   pushplan bench scenes/benchmark/*.yaml scenes/dense/*.yaml \
#     --planners push_kpiece,pcrrt,static,darrt,kpiece,est,pdst,sst --runs 2 --time 60 \
#     --shortcut 0 --out acc          # or --shard K/3 into three folders, then bench merge
#   benches/acceptance.sh acc [BUDGETS]   # BUDGETS: seconds, comma-separated (default
#                                         # 1,2,5,10,20,30,60; the last is the time limit)
set -eu
dir=${1:?usage: benches/acceptance.sh BENCH_DIR [BUDGETS]}
budgets=${2:-1,2,5,10,20,30,60}
db="$dir/results.db"
[ -f "$db" ] || { echo "$db: no benchmark database (run pushplan bench, or bench merge)" >&2; exit 2; }
sqlite3 -separator ' ' "$db" "
  select substr(e.name, 1, instr(e.name, '-') - 1), replace(p.name, 'control_', ''), e.name,
         r.status, r.time, e.timelimit
  from runs r join experiments e on r.experimentid = e.id join plannerConfigs p on r.plannerid = p.id
  order by e.name, p.id" |
  awk -v budgets="$budgets" '
    {
      set = $1; planner = $2; scene = $3; exact = ($4 == 6); time = $5; limit = $6
      key = set SUBSEP planner
      if (!(key in runs)) { order[++keys] = key }
      runs[key]++
      if ($4 == 5) approximate[key]++
      times[key, runs[key]] = exact ? time : "inf"
      for (b = 1; b <= nb; b++)
        if (exact && (time <= budget[b] || budget[b] >= limit)) {
          within[key, b]++
          if (!((key, b, scene) in seen)) { seen[key, b, scene] = 1; scenes[key, b]++ }
        }
      if (!(set in sets)) { sets[set] = 1; setorder[++nsets] = set }
    }
    BEGIN { nb = split(budgets, budget, ",") }
    function median(key, n,   i, j, v, t, a) {
      for (i = 1; i <= n; i++) a[i] = (times[key, i] == "inf") ? 1e300 : times[key, i] + 0
      for (i = 2; i <= n; i++) { v = a[i]; for (j = i - 1; j >= 1 && a[j] > v; j--) a[j + 1] = a[j]; a[j + 1] = v }
      t = (n % 2) ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
      return t >= 1e300 ? "never" : sprintf("%.3f s", t)
    }
    function row(counts, key,   b, s) {
      s = ""
      for (b = 1; b <= nb; b++) s = s (b > 1 ? " / " : "") (counts[key, b] + 0)
      return s
    }
    END {
      heading = ""
      for (b = 1; b <= nb; b++) heading = heading (b > 1 ? " / " : "") budget[b]
      for (s = 1; s <= nsets; s++) {
        printf "\n%s\n\n| planner | runs | runs solved within %s s | scenes solved within the same | median time to solve | approximate |\n|---|---|---|---|---|---|\n", setorder[s], heading
        for (k = 1; k <= keys; k++) {
          split(order[k], part, SUBSEP)
          if (part[1] != setorder[s]) continue
          printf "| %s | %d | %s | %s | %s | %d |\n", part[2], runs[order[k]], row(within, order[k]), row(scenes, order[k]), median(order[k], runs[order[k]]), approximate[order[k]] + 0
        }
      }
    }'
