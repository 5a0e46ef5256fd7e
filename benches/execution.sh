#!/usr/bin/env bash
# The execution benchmark of BENCHMARKS.md ("Plans that work in the world"): for every
# benchmark scene, plan once (seed SEED, default 1), play the plan 10 times in each 3D engine (ENGINES,
# default "rapier mujoco": the same plan, trials and perturbed worlds in each) and
# re-simulate it 10 times with parameter noise. Extra `plan` options go in PLAN_ARGS
# (e.g. PLAN_ARGS="--robust 20"); TIME sets the search time (default 10 s); SCENES the
# scenes, folders (their scene_*.yaml) or files, separated by spaces (default
# scenes/benchmark; e.g. SCENES="scenes/dense/scene_17.yaml scenes/benchmark"); TRIALS the
# 3D trials and perturbed re-simulations per plan (default 10). CLOSED_LOOP=1 also plays
# each plan closed loop (`execute --closed-loop`, the same trials and worlds), into
# OUT_DIR/*.closed.{json,txt}, with CLOSED_LOOP_ARGS (e.g. "--replan-shortcut 0.1 --replan-budget 60");
# OPEN_LOOP=0 then skips the open-loop plays. Closed-loop re-plans search on one thread per
# core by default; with JOBS > 1, or another run beside this one, add "--replan-threads 1"
# to CLOSED_LOOP_ARGS so that the runs do not share cores unevenly. REUSE_PLANS=1 judges the plans already in
# OUT_DIR (FOLDER_scene_NN.json with its .plan.txt) instead of planning again. JOBS runs
# that many scenes at a time (default 1; each scene's runs stay one after the other).
# Closed-loop runs write a line per finished trial to FOLDER_scene_NN.ENGINE.closed.log as
# they go (and their errors, if any).
#
#   benches/execution.sh OUT_DIR [PUSHPLAN_BINARY]
#
# Writes OUT_DIR/FOLDER_scene_NN.{json,plan.txt,check.txt}, FOLDER_scene_NN.ENGINE.{exec,closed}.{json,txt}
# and summary lines per scene and engine in OUT_DIR/summary.txt.
set -u
out=${1:?usage: benches/execution.sh OUT_DIR [PUSHPLAN_BINARY]}
bin=${2:-target/release/pushplan}
mkdir -p "$out"
: > "$out/summary.txt"
trials=${TRIALS:-10}
engines=(${ENGINES:-rapier mujoco})
scenes=()
for s in ${SCENES:-scenes/benchmark}; do
  if [ -d "$s" ]; then scenes+=("$s"/scene_*.yaml); else scenes+=("$s"); fi
done
for scene in "${scenes[@]}"; do
  [ -f "$scene" ] || { echo "$scene: no such scene file" >&2; exit 2; }
done
# A scene's name in OUT_DIR: by folder and file, since scenes of two folders may share a
# file name.
name_of() {
  echo "$(basename "$(dirname "$1")")_$(basename "$1" .yaml)"
}
# One scene: plan (or reuse), check, play; its summary lines go to OUT_DIR/NAME.summary.
judge() {
  local scene=$1 n e line
  n=$(name_of "$scene")
  local summary="$out/$n.summary"
  : > "$summary"
  if [ -z "${REUSE_PLANS:-}" ] || [ ! -f "$out/$n.plan.txt" ]; then
    # shellcheck disable=SC2086
    "$bin" plan "$scene" --seed "${SEED:-1}" --time "${TIME:-10}" ${PLAN_ARGS:-} --out "$out/$n.json" --quiet > "$out/$n.plan.txt" 2>&1
  fi
  if grep -v '^warning:' "$out/$n.plan.txt" | head -1 | grep -q '^solved'; then
    "$bin" check "$out/$n.json" --noise "$trials" --path-only > "$out/$n.check.txt" 2>&1
    echo "$n: $(grep -o 'perturbed re-simulations: [0-9]* of [0-9]*' "$out/$n.check.txt")" >> "$summary"
    for e in "${engines[@]}"; do
      if [ "${OPEN_LOOP:-1}" != 0 ]; then
        "$bin" execute "$out/$n.json" --engine "$e" --trials "$trials" --json "$out/$n.$e.exec.json" > "$out/$n.$e.exec.txt" 2>&1
        echo "$n $e: $(head -1 "$out/$n.$e.exec.txt" | sed 's/.*speed: //')" >> "$summary"
      fi
      if [ "${CLOSED_LOOP:-0}" != 0 ]; then
        # shellcheck disable=SC2086
        "$bin" execute "$out/$n.json" --engine "$e" --closed-loop --trials "$trials" ${CLOSED_LOOP_ARGS:-} --json "$out/$n.$e.closed.json" > "$out/$n.$e.closed.txt" 2> "$out/$n.$e.closed.log"
        # The report's first line, or the error that stopped it.
        line=$(head -1 "$out/$n.$e.closed.txt")
        [ -n "$line" ] || line=$(tail -1 "$out/$n.$e.closed.log")
        echo "$n $e closed loop: ${line/*speed: /}" >> "$summary"
      fi
    done
  else
    echo "$n: not solved" >> "$summary"
  fi
}
running=0
for scene in "${scenes[@]}"; do
  if [ "$running" -ge "${JOBS:-1}" ]; then wait -n; running=$((running - 1)); fi
  judge "$scene" &
  running=$((running + 1))
done
wait
for scene in "${scenes[@]}"; do
  cat "$out/$(name_of "$scene").summary" >> "$out/summary.txt"
done
for e in "${engines[@]}"; do
  reached=$(cat "$out"/*."$e".exec.txt 2>/dev/null | grep -o '[0-9]* reach the goal' | awk '{s += $1} END {print s + 0}')
  echo "$e: trials reaching the goal: $reached of $(( ${#scenes[@]} * trials ))" | tee -a "$out/summary.txt"
  if [ "${CLOSED_LOOP:-0}" != 0 ]; then
    closed=$(cat "$out"/*."$e".closed.txt 2>/dev/null | grep -o '[0-9]* reach the goal' | awk '{s += $1} END {print s + 0}')
    echo "$e closed loop: trials reaching the goal: $closed of $(( ${#scenes[@]} * trials ))" | tee -a "$out/summary.txt"
    python3 - "$out" "$e" <<'PY' | tee -a "$out/summary.txt"
import glob, json, math, sys
lat, replans, trials, tipped = [], 0, 0, 0
for f in glob.glob(f"{sys.argv[1]}/*.{sys.argv[2]}.closed.json"):
    for t in json.load(open(f))["trials"]:
        lat += t["replan_latencies"]; replans += t["replans"]; trials += 1; tipped += bool(t["tipped"])
lat.sort()
q = lambda p: lat[min(len(lat) - 1, max(0, math.ceil(p * len(lat)) - 1))] if lat else 0.0
print(f"{sys.argv[2]} closed loop over {trials} trials: {replans / max(trials, 1):.2f} re-plans per trial; "
      f"re-planning latency median {q(0.5):.3f} s, 95th percentile {q(0.95):.3f} s ({len(lat)} re-plans); "
      f"{tipped} trials tip an object")
PY
  fi
done
