#!/usr/bin/env bash
# The planner across the matrix of arms and scene designs (BENCHMARKS.md, "Any arm, any
# table"): for every arm (wam, panda, ur5e, iiwa14) and design (paper, dense,
# occupied_goal, mixed_heights, walls), a set generated with SEED (default 2: held out;
# the shipped sets, scenes/ARM/DESIGN, are seed 1, development) is planned once per scene
# with `plan` (each of PLANNERS, default push_kpiece; TIME s, default 10, one thread, the
# first solution as found: --robust 0, shortcutting for SHORTCUT s of work, default 3 as
# `plan`'s), JOBS runs at a time (default 2). COUNT sets the scenes per set (default: four,
# two dense).
#
#   benches/matrix.sh OUT_DIR [PUSHPLAN_BINARY]
#
# Writes OUT_DIR/scenes/ARM/DESIGN/, OUT_DIR/plans/PLANNER/ARM_DESIGN_NN.{json,txt} and
# prints a table per arm, design and planner: scenes solved, median time to solve
# (unsolved counted at the limit), and the end effector's travel per metre the goal object
# moved (as found and after shortcutting; medians over the solved plans); with more than
# one planner, the runs each solved within budgets of 1 s up to the limit, and the cells
# Push KPIECE is ahead of, level with or behind the best other planner at each. RETRY=60
# plans every run left unsolved within TIME again with RETRY s (OUT_DIR/plans/PLANNER/
# NAME.retry.{json,txt}; a search is deterministic in its propagation steps, so this is
# the run with the longer limit) and the budgets go on to RETRY s; a run's time to solve
# is its faster measurement.
set -eu
out=${1:?usage: benches/matrix.sh OUT_DIR [PUSHPLAN_BINARY]}
bin=${2:-target/release/pushplan}
seed=${SEED:-2}
time=${TIME:-10}
jobs=${JOBS:-2}
planners=(${PLANNERS:-push_kpiece})
# SUMMARY_ONLY=1: the table of the plans already in OUT_DIR.
if [ -z "${SUMMARY_ONLY:-}" ]; then
for arm in wam panda ur5e iiwa14; do
  for design in paper dense occupied_goal mixed_heights walls; do
    case $design in
      paper) count=4; objects=1..7;;
      dense) count=2; objects=8..14;;
      *) count=4; objects=2..7;;
    esac
    count=${COUNT:-$count}
    "$bin" scenes generate --robot $arm --design $design --count $count --objects $objects \
      --seed "$seed" --out "$out/scenes/$arm/$design" > /dev/null
  done
done
for planner in "${planners[@]}"; do
  mkdir -p "$out/plans/$planner"
  ls "$out"/scenes/*/*/scene_*.yaml | while read -r scene; do
    design=$(basename "$(dirname "$scene")")
    arm=$(basename "$(dirname "$(dirname "$scene")")")
    echo "$scene $planner/${arm}_${design}_$(basename "$scene" .yaml | sed 's/scene_//') $planner"
  done
done | xargs -P "$jobs" -L 1 sh -c '"$0" plan "$1" --planner "$3" --seed 1 --time '"$time"' --robust 0 --threads 1 --shortcut '"${SHORTCUT:-3}"' --quiet \
  --out "'"$out"'/plans/$2.json" > "'"$out"'/plans/$2.txt" 2>&1 || true' "$bin"
if [ -n "${RETRY:-}" ]; then
  for txt in "$out"/plans/*/*.txt; do
    case $txt in *.retry.txt) continue;; esac
    grep -q '^solved in' "$txt" && continue
    name=$(basename "$txt" .txt); planner=$(basename "$(dirname "$txt")")
    arm=${name%%_*}; rest=${name#*_}
    echo "$out/scenes/$arm/${rest%_*}/scene_${rest##*_}.yaml $planner/$name $planner"
  done | xargs -P "$jobs" -L 1 sh -c '"$0" plan "$1" --planner "$3" --seed 1 --time '"$RETRY"' --robust 0 --threads 1 --shortcut '"${SHORTCUT:-3}"' --quiet \
    --out "'"$out"'/plans/$2.retry.json" > "'"$out"'/plans/$2.retry.txt" 2>&1 || true' "$bin"
fi
fi
python3 - "$out" "$time" "${RETRY:-0}" <<'PY'
import glob, json, math, os, re, statistics, sys
out, limit, retry = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
rows = {}
solved_in = lambda text: re.search(r"^solved in ([0-9.]+) s", text, re.M)
for txt in sorted(glob.glob(f"{out}/plans/*/*.txt")):
    if txt.endswith(".retry.txt"):
        continue
    planner = os.path.basename(os.path.dirname(txt))
    name = os.path.basename(txt)[:-4]
    arm, rest = name.split("_", 1)
    design = rest.rsplit("_", 1)[0]
    m = solved_in(open(txt).read())
    row = rows.setdefault((arm, design, planner), {"runs": 0, "solved": 0, "times": [], "longer": [], "travel": [], "raw": []})
    row["runs"] += 1
    row["times"].append(float(m.group(1)) if m else limit)
    # Times to solve within RETRY s (infinite: unsolved), the faster measurement.
    again = solved_in(open(txt[:-4] + ".retry.txt").read()) if os.path.exists(txt[:-4] + ".retry.txt") else None
    row["longer"].append(min(float(x.group(1)) for x in (m, again) if x) if m or again else math.inf)
    if m:
        row["solved"] += 1
        plan = json.load(open(txt[:-4] + ".json"))
        start = plan["start"]["objects"][0]
        end = plan["controls"][-1]["state"]["objects"][0] if plan["controls"] else start
        moved = math.hypot(end[0] - start[0], end[1] - start[1])
        if moved > 0:
            row["travel"].append(plan["metrics"]["after_shortcut"]["ee_length"] / moved)
            row["raw"].append(plan["metrics"]["before_shortcut"]["ee_length"] / moved)
print("| arm | design | planner | solved | median time to solve (s) | EE travel per metre the goal object moved, as found / shortcut (medians) |")
print("|---|---|---|---|---|---|")
median = lambda v: f"{statistics.median(v):.1f}" if v else "-"
for (arm, design, planner), r in sorted(rows.items()):
    print(f"| {arm} | {design} | {planner} | {r['solved']} of {r['runs']} | {statistics.median(r['times']):.2f} | {median(r['raw'])} / {median(r['travel'])} |")

print()
for planner in sorted({key[2] for key in rows}):
    mine = [r for key, r in rows.items() if key[2] == planner]
    raw = [v for r in mine for v in r["raw"]]
    cut = [v for r in mine for v in r["travel"]]
    print(f"{planner}: {sum(r['solved'] for r in mine)} of {sum(r['runs'] for r in mine)} solved within {limit:g} s; "
          f"EE travel per metre the goal object moved, median {median(raw)} as found, {median(cut)} after shortcutting")

# Budgets: runs solved within each budget up to the limit (RETRY's, if given), per
# planner; per cell, whether push_kpiece solves more than the best other planner within
# the budget, as many, or fewer (those cells named).
planners = sorted({key[2] for key in rows})
if "push_kpiece" in planners and len(planners) > 1:
    budgets = [b for b in (1, 2, 5, 10, 20, 30, 45, 60, 120, 300, 600) if b <= max(limit, retry)]
    within = lambda r, b: sum(t <= b for t in r["longer"])
    cells = sorted({key[:2] for key in rows})
    print()
    print("| budget (s) | " + " | ".join(f"{p} solved" for p in planners) + " | cells push_kpiece is ahead / level / behind the best other |")
    print("|---|" + "---|" * len(planners) + "---|")
    for b in budgets:
        totals = {p: sum(within(rows[c + (p,)], b) for c in cells if c + (p,) in rows) for p in planners}
        ahead = level = 0
        behind = []
        for c in cells:
            mine = within(rows[c + ("push_kpiece",)], b)
            best = max(within(rows[c + (p,)], b) for p in planners if p != "push_kpiece" and c + (p,) in rows)
            ahead += mine > best
            level += mine == best
            if mine < best:
                behind.append(f"{' '.join(c)}: {mine} against {best}")
        where = f" ({', '.join(behind)})" if behind else ""
        print(f"| {b:g} | " + " | ".join(str(totals[p]) for p in planners) + f" | {ahead} / {level} / {len(behind)}{where} |")
PY
