#!/bin/bash
# Public robot descriptions, unmodified, as a new user meets them (issue 58): each loads,
# gets its self-collision pairs (MoveIt's SRDF where one is given, else computed by
# `pushplan robot --allowed-collisions`), and plans a one-box scene within 10 s on one
# thread, five seeds; one plan per robot is checked and played in both 3D engines.
#
#   benches/public_robots.sh OUT BAXTER_DESCRIPTION [MOVEIT_BAXTER_SRDF] [PANDA_DIR]
#
# BAXTER_DESCRIPTION: RethinkRobotics/baxter_common's `baxter_description` folder.
# MOVEIT_BAXTER_SRDF: moveit/moveit_robots' `baxter/baxter_moveit_config/config/baxter.srdf`
#   (52b4156 and before; later commits keep only its xacro).
# PANDA_DIR: bullet3's `examples/pybullet/gym/pybullet_data/franka_panda`.
# Fetch them for the trial; never commit them. PUSHPLAN names the binary (default:
# target/release/pushplan); SEEDS the seeds (default: 1 2 3 4 5).
set -euo pipefail
out=${1:?OUT folder}
baxter=$(realpath "${2:?BAXTER_DESCRIPTION folder}")
srdf=${3:+$(realpath "$3")}
panda=${4:+$(realpath "$4")}
pushplan=$(realpath "${PUSHPLAN:-target/release/pushplan}")
seeds=${SEEDS:-1 2 3 4 5}
mkdir -p "$out"
cd "$out"

# Baxter's right arm, base 0.93 m up (its pedestal's height), pushing with the bottom of
# its hand (no gripper fingers in the description) 3 cm above the table: its wrist, wider
# than the hand, then stays above a 10 cm cube's top.
baxter_scene() { # NAME, then extra robot lines
  local name=$1
  shift
  {
    echo "name: $name"
    echo "robot:"
    echo "  type: arm"
    echo "  urdf: $baxter/urdf/baxter.urdf"
    for line in "$@"; do echo "  $line"; done
    cat <<'EOF'
  base_pose: {xyz: [0, 0, 0.93], rpy: [0, 0, 0]}
  end_effector: right_hand
  start_joints: [0.7929, -0.3236, 0.0121, 1.5985, -0.0395, 0.2962, 0.0491]
  pushing_plane: {height: 0.03, orientation_rpy: [0, 3.1416, 0]}
table: {height: 0.76, x: [0.45, 1.05], y: [-0.85, 0.25]}
objects:
  - {name: box, shape: {type: box, size: [0.1, 0.1, 0.1]}, pose: [0.75, -0.25, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.3}
goal: {object: box, center: [0.75, -0.55], radius: 0.1}
EOF
  } >"$name.yaml"
}

# pybullet's Panda on the Panda set's table and start, tool down 6 cm above the table.
panda_scene() {
  cat >panda.yaml <<EOF
name: panda-public
robot:
  type: arm
  urdf: $panda/panda.urdf
  base_pose: {xyz: [0, 0, 0.76], rpy: [0, 0, 0]}
  end_effector: panda_grasptarget
  start_joints: [0.4281, 0.5118, 0.3225, -2.4368, -0.6343, 2.8766, 2.1139]
  pushing_plane: {height: 0.06, orientation_rpy: [3.141592653589793, 0, 0]}
table: {height: 0.76, x: [0.2, 0.8], y: [-0.6, 0.6]}
objects:
  - {name: goal_box, shape: {type: box, size: [0.102, 0.102, 0.215]}, pose: [0.5266, 0.2212, 2.9594], mass: 1.0, mu_g: 0.4, mu_c: 0.3}
goal: {object: goal_box, center: [0.5, -0.3], radius: 0.1}
EOF
}

# Appends the computed pairs (and the base bolted on the table) to scene NAME.
computed_pairs() { # NAME [extra pair line]
  "$pushplan" robot "$1.yaml" --allowed-collisions >"$1.pairs"
  head -3 "$1.pairs" | sed "s/^/  /"
  {
    grep -v '^#' "$1.pairs"
    [[ -z "${2:-}" ]] || echo "$2"
  } >>"$1.yaml"
}

trial() { # NAME: five seeds, then one plan checked and played
  local name=$1
  "$pushplan" check "$name.yaml" | tail -1
  for seed in $seeds; do
    "$pushplan" plan "$name.yaml" --robust 0 --time 10 --threads 1 --seed "$seed" --quiet \
      --out "$name.$seed.json" >"$name.$seed.txt" 2>&1 || true
    echo "  $name seed $seed: $(grep -E '^(solved|not solved)' "$name.$seed.txt" | cut -c1-60)"
  done
  local first
  first=$(set -- $seeds && echo "$1")
  "$pushplan" check "$name.$first.json" --path-only | tail -1 | sed "s/^/  check: /"
  for engine in rapier mujoco; do
    "$pushplan" execute "$name.$first.json" --trials 10 --engine "$engine" |
      grep -E 'reach the goal' | sed "s/^/  $engine: /"
  done
}

baxter_scene baxter-computed
echo "Baxter, pairs computed:"
computed_pairs baxter-computed
trial baxter-computed
if [[ -n "$srdf" ]]; then
  baxter_scene baxter-moveit "srdf: $srdf"
  echo "Baxter, MoveIt's SRDF:"
  trial baxter-moveit
fi
if [[ -n "$panda" ]]; then
  panda_scene
  echo "Panda, pairs computed:"
  computed_pairs panda "  - [panda_link0, table]"
  trial panda
fi
