#!/usr/bin/env bash
# What a search costs before it searches (reading and preparing the scene), two binaries
# side by side: `plan SCENE --time 0.001` (the search stops at once) with binary OLD, then
# NEW, on each scene in turn, ROUNDS rounds (default 5), so that both meet the same load
# on the machine. Prints each pair (seconds, whole process) and the medians. THREADS
# (default 1) is `plan --threads`: with more, the search is set up with its lanes.
#
#   OLD=BINARY NEW=BINARY [ROUNDS=5] [THREADS=1] benches/search_setup.sh SCENE.yaml...
set -u
old=${OLD:?OLD=the first pushplan binary}
new=${NEW:?NEW=the second pushplan binary}
[ $# -gt 0 ] || { echo "usage: OLD=BIN NEW=BIN benches/search_setup.sh SCENE.yaml..." >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
seconds() {
  local t0 t1
  t0=$(date +%s.%N)
  "$1" plan "$2" --robust 0 --shortcut 0 --time 0.001 --threads "${THREADS:-1}" --out "$out/plan.json" --quiet > /dev/null 2>&1
  t1=$(date +%s.%N)
  echo "$t1 - $t0" | bc
}
for _ in $(seq "${ROUNDS:-5}"); do
  for scene in "$@"; do
    echo "$(seconds "$old" "$scene") $(seconds "$new" "$scene") $scene"
  done
done | tee "$out/pairs.txt"
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
echo "pairs: $(wc -l < "$out/pairs.txt"); median OLD $(cut -d' ' -f1 "$out/pairs.txt" | median) s," \
  "NEW $(cut -d' ' -f2 "$out/pairs.txt" | median) s, OLD - NEW $(awk '{print $1 - $2}' "$out/pairs.txt" | median) s"
