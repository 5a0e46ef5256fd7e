# Sourced by the bench scripts: one `pushplan plan` run, no shortcutting, the first
# solution as found (`--robust 0`: the search is measured, not the robustness check),
# reduced to its time to solve (s), or the time limit when it ends unsolved.
#
#   solve_time BINARY SECONDS SCENE SEED OUT [PLAN_ARGS...]
solve_time() {
  local bin=$1 limit=$2 scene=$3 seed=$4 out=$5 line
  shift 5
  line=$("$bin" plan "$scene" --seed "$seed" --time "$limit" --shortcut 0 --robust 0 --quiet --out "$out" "$@" 2>&1 | grep -v "^warning:" | head -1)
  case "$line" in
    "solved in "*) awk '{print $3}' <<< "$line" ;;
    *) echo "$limit" ;;
  esac
}
