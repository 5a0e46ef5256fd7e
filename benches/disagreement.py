#!/usr/bin/env python3
"""How far the planning model and the two 3D engines disagree on final object poses.

Reads the output folder of benches/execution.sh (run with ENGINES="rapier mujoco"): each
solved plan FOLDER_scene_NN.json and its executions FOLDER_scene_NN.{rapier,mujoco}.exec.json
(the same trials, in the same perturbed worlds). For every scene class (the scenes'
folder: benchmark, dense, ...) it prints, in mm, the median, 90th percentile and largest
distance between final object positions:

  model-rapier, model-mujoco   the plan's predicted final pose against each engine's
  rapier-mujoco                the two engines, trial by trial (same world)

for the goal object and for every object the plan moves (by more than 1 cm), in the
nominal trial (the scene as it is: model error alone) and in all trials (with the
perturbations), and how many trials' goal-object error stays within the plan's goal
margin.

Then, per scene class and object count (1-3, 4-5, 6-7, 8-12, 13 or more objects), whether
the model's own noise covers each engine's disagreement: for every plan, the goal
object's median distance from its predicted final pose in the engine's trials, against
its mean distance in the model's perturbed re-simulations (`check --noise`, the
FOLDER_scene_NN.check.txt beside the plan: the worlds robust planning must reach the goal
in). A ratio at or below 1 means a plan robust in the model's worlds keeps a margin as
wide as the engine's error.

    benches/disagreement.py OUT_DIR [OUT_DIR ...]
"""
import glob
import json
import math
import os
import re
import sys
from collections import defaultdict


def quantile(values, p):
    values = sorted(values)
    if not values:
        return float("nan")
    return values[min(len(values) - 1, max(0, math.ceil(p * len(values)) - 1))]


def object_count_class(objects):
    for top, label in ((3, "1-3"), (5, "4-5"), (7, "6-7"), (12, "8-12")):
        if objects <= top:
            return f"{label} objects"
    return "13 or more objects"


def noise_coverage(outs):
    """Per (folder, object count, engine): (engine's median goal error, model's mean
    perturbed distance) per plan, in m."""
    rows = defaultdict(list)
    for out in outs:
        for check_path in sorted(glob.glob(os.path.join(out, "*_scene_*.check.txt"))):
            name = os.path.basename(check_path)[: -len(".check.txt")]
            found = re.search(r"([\d.]+) mm from the planned one on average", open(check_path).read())
            if not found:
                continue
            spread = 1e-3 * float(found.group(1))
            for engine in ("rapier", "mujoco"):
                path = os.path.join(out, f"{name}.{engine}.exec.json")
                if not os.path.exists(path):
                    continue
                report = json.load(open(path))
                goal = report["objects"].index(report["goal_object"])
                errors = [t["final_errors"][goal] for t in report["trials"]]
                key = (name.rsplit("_scene_", 1)[0], object_count_class(len(report["objects"])), engine)
                rows[key].append((quantile(errors, 0.5), spread))
    return rows


def main(outs):
    # stats[class][(which objects, which trials, pair)] = distances (m)
    stats = defaultdict(lambda: defaultdict(list))
    margins = defaultdict(list)
    within = defaultdict(lambda: defaultdict(lambda: [0, 0]))
    plan_paths = sorted(p for out in outs for p in glob.glob(os.path.join(out, "*_scene_*.json")))
    for plan_path in plan_paths:
        out = os.path.dirname(plan_path)
        name = os.path.basename(plan_path)[: -len(".json")]
        if name.count(".") or not os.path.exists(os.path.join(out, f"{name}.rapier.exec.json")):
            continue
        cls = name.rsplit("_scene_", 1)[0]
        plan = json.load(open(plan_path))
        runs, report = {}, None
        for engine in ("rapier", "mujoco"):
            path = os.path.join(out, f"{name}.{engine}.exec.json")
            if os.path.exists(path):
                report = json.load(open(path))
                runs[engine] = report["trials"]
        if len(runs) < 2:
            continue
        # The reports list objects in scene order, the plan in its own.
        scene_objects = report["objects"]
        plan_index = {o: k for k, o in enumerate(plan["objects"])}
        start = [plan["start"]["objects"][plan_index[o]] for o in scene_objects if o in plan_index]
        predicted = [plan["trajectory"]["objects"][-1][plan_index[o]] for o in scene_objects if o in plan_index]
        if len(predicted) != len(scene_objects):
            continue  # a plan that does not move every object (Static RRT's clutter)
        goal_index = scene_objects.index(report["goal_object"])
        margin = plan["margins"]["goal"]
        margins[cls].append(margin)
        moved = [i for i in range(len(scene_objects))
                 if math.dist(predicted[i][:2], start[i][:2]) > 0.01]
        n = min(len(runs["rapier"]), len(runs["mujoco"]))
        for t in range(n):
            r = runs["rapier"][t]["final_poses"]
            m = runs["mujoco"][t]["final_poses"]
            for label, objects in (("goal object", [goal_index]), ("moved objects", moved)):
                for i in objects:
                    pairs = {
                        "model-rapier": math.dist(predicted[i][:2], r[i][:2]),
                        "model-mujoco": math.dist(predicted[i][:2], m[i][:2]),
                        "rapier-mujoco": math.dist(r[i][:2], m[i][:2]),
                    }
                    for pair, d in pairs.items():
                        if t == 0:
                            stats[cls][(label, "nominal", pair)].append(d)
                        stats[cls][(label, "all trials", pair)].append(d)
                        if label == "goal object" and pair != "rapier-mujoco":
                            within[cls][pair][0] += d <= margin
                            within[cls][pair][1] += 1
    for cls in sorted(stats):
        print(f"## {cls} (goal margin {1e3 * max(margins[cls]):.0f} mm)")
        print("| objects | trials | pair | n | median mm | p90 mm | max mm |")
        print("|---|---|---|---|---|---|---|")
        for (label, trials, pair), values in sorted(stats[cls].items()):
            print(f"| {label} | {trials} | {pair} | {len(values)} | {1e3 * quantile(values, 0.5):.0f} "
                  f"| {1e3 * quantile(values, 0.9):.0f} | {1e3 * max(values):.0f} |")
        for pair, (ok, total) in sorted(within[cls].items()):
            print(f"{pair}: goal object within the goal margin of its predicted pose in {ok} of {total} trials")
        print()
    print("## Does the model's noise cover the engines' error? (goal object, per plan)")
    print("| class | objects | engine | plans | engine error, median of plans, mm | model's perturbed spread, median, mm | ratio, median (<= 1: covered) | plans covered |")
    print("|---|---|---|---|---|---|---|---|")
    for (cls, count, engine), plans in sorted(noise_coverage(outs).items()):
        ratios = [error / max(spread, 1e-3) for error, spread in plans]
        print(f"| {cls} | {count} | {engine} | {len(plans)} | {1e3 * quantile([e for e, _ in plans], 0.5):.0f} "
              f"| {1e3 * quantile([s for _, s in plans], 0.5):.0f} | {quantile(ratios, 0.5):.2f} "
              f"| {sum(r <= 1 for r in ratios)} of {len(plans)} |")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
