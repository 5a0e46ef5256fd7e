#!/usr/bin/env bash
# The README's two commands timed on a clean clone, as on a fresh machine (BENCHMARKS.md,
# "Build, install and test"): a clone of HEAD in a temporary folder, an empty cargo home
# (every crate downloaded), no target folder; with --purge (root, Debian) the project's
# Debian packages are purged and apt's cache emptied first, so that the first command
# installs them as on a new machine. Run it with nothing else running.
#
#   benches/setup_time.sh [--purge]
set -u
repo=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
git clone -q "$repo" "$work/clone"
cd "$work/clone"
echo "commit $(git log --oneline -1)"
if [ "${1:-}" = "--purge" ]; then
  # The packages of .ci/install-packages that a new machine of this kind lacks.
  pkgs="cmake libboost-serialization-dev libboost-filesystem-dev libboost-system-dev libompl-dev libeigen3-dev libfcl-dev ompl-demos chromium slurmctld slurmd slurm-client munge"
  DEBIAN_FRONTEND=noninteractive apt-get purge -y -qq $pkgs > "$work/purge.log" 2>&1
  DEBIAN_FRONTEND=noninteractive apt-get autoremove --purge -y -qq >> "$work/purge.log" 2>&1
  apt-get clean
fi
export CARGO_HOME="$work/cargo-home"
mkdir -p "$CARGO_HOME"
seconds() { date +%s.%N; }
t0=$(seconds)
bash .ci/install-packages > "$work/install.log" 2>&1 || { cat "$work/install.log"; exit 1; }
t1=$(seconds)
cargo run --release -- plan --render pictures > "$work/first.log" 2>&1 || { tail -20 "$work/first.log"; exit 1; }
t2=$(seconds)
cargo test --release > "$work/test.log" 2>&1 || { grep -E "FAILED|panicked" "$work/test.log"; exit 1; }
t3=$(seconds)
compile=$(grep -m1 -oE "Finished .* in [0-9ms. ]+" "$work/test.log")
awk -v a="$t0" -v b="$t1" -v c="$t2" -v d="$t3" -v compile="$compile" 'BEGIN {
  printf "first command: %.0f s (installing %.0f s, building and planning %.0f s)\n", c - a, b - a, c - b
  printf "cargo test --release: %.0f s (%s)\n", d - c, compile }'
grep "test result" "$work/test.log"
