//! Benchmark scene sets on HERB's table: the same goal object in every scene with a random
//! start pose, the goal disc (r = 0.1 m) at the same place, and a valid start state
//! (checked by loading each scene). Two designs:
//! - [`Design::Paper`], the whole-arm paper's (Sec. V-A): 1 to 7 (at most 12) movable
//!   objects in the arm's reachable workspace, each layout drawn whole and kept if valid;
//! - [`Design::Dense`]: 8 to 20 objects placed one by one where each fits, in three
//!   layouts taken in turn ([`Layout`]): scattered, the goal disc partly covered, and a
//!   wall of clutter across the straight route from the goal object to the goal disc.

use super::Scene;
use crate::random::SplitMix64;
use std::path::{Path, PathBuf};

/// Where the goal disc is, in every scene (m): in reach of HERB's other arm.
pub const GOAL_CENTER: [f64; 2] = [0.85, -0.3];
/// The goal disc's radius (m), in every scene.
pub const GOAL_RADIUS: f64 = 0.1;
/// The region objects are placed in (x, y ranges, m): in the arm's reach on the table.
const REGION: ([f64; 2], [f64; 2]) = ([0.45, 0.95], [-0.45, 0.5]);

/// A kind of clutter of HERB's experiments.
struct Clutter {
    kind: &'static str,
    /// Its shape, as scene YAML.
    shape: &'static str,
    /// kg.
    mass: f64,
    /// Half width and height (m) if the hand can hold it from the side.
    side_grasps: Option<(f64, f64)>,
}

const CLUTTER: [Clutter; 4] = [
    Clutter {
        kind: "box",
        shape: "{type: box, size: [0.10, 0.10, 0.14]}",
        mass: 1.0,
        side_grasps: Some((0.05, 0.14)),
    },
    Clutter {
        kind: "glass",
        shape: "{type: cylinder, radius: 0.035, height: 0.15}",
        mass: 0.3,
        side_grasps: Some((0.035, 0.15)),
    },
    Clutter {
        kind: "bottle",
        shape: "{type: cylinder, radius: 0.045, height: 0.25}",
        mass: 0.6,
        side_grasps: Some((0.045, 0.25)),
    },
    // Too low for the hand to close round it above the table.
    Clutter {
        kind: "bowl",
        shape: "{type: cylinder, radius: 0.08, height: 0.06}",
        mass: 0.5,
        side_grasps: None,
    },
];

/// The goal object's half width and height (m): `goal_box`, 0.102 x 0.102 x 0.215.
const GOAL_BOX: (f64, f64) = (0.051, 0.215);

/// The hand's centre keeps this far from a grasped object's side (m): its fingers reach
/// 8 cm in front of the tool frame, and 1 cm is left clear.
const GRASP_STANDOFF: f64 = 0.09;

/// Side grasps of an upright object (half width `b`, height `h`), as the default scene's
/// goal box has: the hand level at half height (±3 cm), its approach axis at the object's
/// axis, from any direction; inverse kinematics keeps those the hand clears.
fn grasps_of_side((b, h): (f64, f64)) -> String {
    format!(
        ", grasps: [{{frame: {{xyz: [0, 0, {}]}}, end_effector: {{xyz: [{}, 0, 0], rpy: [0, 1.5707963267948966, 0]}}, bounds: {{z: [-0.03, 0.03], yaw: [-3.141592653589793, 3.141592653589793]}}}}]",
        h / 2.0,
        -(b + GRASP_STANDOFF)
    )
}

/// Which scene set to generate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Design {
    /// The whole-arm paper's design (Sec. V-A): 1 to 12 objects, whole layouts drawn and
    /// kept when valid.
    Paper,
    /// Dense clutter: objects placed one by one (scattered, over the goal disc, or as a
    /// wall across the way), objects pushing objects.
    Dense,
}

impl std::str::FromStr for Design {
    type Err = String;

    fn from_str(name: &str) -> Result<Design, String> {
        match name {
            "paper" => Ok(Design::Paper),
            "dense" => Ok(Design::Dense),
            _ => Err(format!("unknown design '{name}' (known: paper, dense)")),
        }
    }
}

/// How the clutter of a dense scene is laid out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    /// Everywhere in the region.
    Scattered,
    /// One or two clutter objects overlap the goal disc: they must be moved first.
    GoalCovered,
    /// A row of clutter across the straight route from the goal object to the goal disc.
    Walled,
}

impl Layout {
    const ALL: [Layout; 3] = [Layout::Scattered, Layout::GoalCovered, Layout::Walled];
}

/// The most objects the paper's design places (it draws whole layouts, and denser ones
/// are almost never valid).
const PAPER_MAX_OBJECTS: usize = 12;
/// The most objects the dense design places.
const DENSE_MAX_OBJECTS: usize = 20;
/// Tries to place one object of a dense scene before the layout is drawn again.
const PLACEMENT_TRIES: usize = 200;

/// Writes `count` scenes of `design` into `dir`, with object counts spread evenly over
/// `objects` (inclusive), drawn from `seed`. Returns the files.
pub fn generate(
    design: Design,
    count: usize,
    objects: (usize, usize),
    seed: u64,
    dir: &Path,
) -> Result<Vec<PathBuf>, String> {
    let (lo, hi) = objects;
    let max = match design {
        Design::Paper => PAPER_MAX_OBJECTS,
        Design::Dense => DENSE_MAX_OBJECTS,
    };
    if lo == 0 || lo > hi || hi > max {
        return Err(format!(
            "objects must be a range within 1..{max} for this design, got {lo}..{hi}{}",
            if design == Design::Paper {
                " (the dense design places up to 20)"
            } else {
                ""
            }
        ));
    }
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let urdf = crate::input::relative_path(dir, &super::builtin::wam_for(dir)?)?;
    let mut rng = SplitMix64::new(seed);
    let mut files = Vec::with_capacity(count);
    for i in 0..count {
        let n = lo + i * (hi - lo + 1) / count.max(1);
        let path = dir.join(format!("scene_{i:02}.yaml"));
        let yaml = match design {
            Design::Paper => {
                let name = format!("benchmark-{i:02}");
                (0..10_000)
                    .map(|_| paper_layout(n, &mut rng).yaml(&name, &urdf, PAPER_DESIGN))
                    .find(|yaml| Scene::from_yaml(yaml, &path).is_ok())
            }
            Design::Dense => {
                let layout = Layout::ALL[i % Layout::ALL.len()];
                let name = format!("dense-{i:02}");
                (0..100).find_map(|_| dense_layout(layout, n, &name, &urdf, &path, &mut rng))
            }
        }
        .ok_or_else(|| format!("no valid layout with {n} objects found"))?;
        crate::output::write_whole(&path, yaml)?;
        files.push(path);
    }
    Ok(files)
}

/// Object poses `[x, y, yaw]` (m, rad; world frame) of a scene: the goal object's, and
/// each clutter object's with its kind (an index into [`CLUTTER`]).
struct Placement {
    goal: [f64; 3],
    clutter: Vec<(usize, [f64; 3])>,
}

fn uniform_pose(rng: &mut SplitMix64, region: ([f64; 2], [f64; 2])) -> [f64; 3] {
    [
        rng.uniform(region.0[0], region.0[1]),
        rng.uniform(region.1[0], region.1[1]),
        rng.uniform(-std::f64::consts::PI, std::f64::consts::PI),
    ]
}

/// A goal-object start at least `away` (m) from the goal disc's centre.
fn goal_start(rng: &mut SplitMix64, region: ([f64; 2], [f64; 2]), away: f64) -> [f64; 3] {
    loop {
        let goal = uniform_pose(rng, region);
        if (goal[0] - GOAL_CENTER[0]).hypot(goal[1] - GOAL_CENTER[1]) >= away {
            return goal;
        }
    }
}

const PAPER_DESIGN: &str = "the whole-arm paper's dataset design";

/// The paper's design: a whole random layout (not yet checked).
fn paper_layout(objects: usize, rng: &mut SplitMix64) -> Placement {
    // The goal object starts out of the goal disc (it has to be pushed there).
    let goal = goal_start(rng, REGION, GOAL_RADIUS + 0.15);
    let clutter = (1..objects)
        .map(|_| (rng.below(CLUTTER.len()), uniform_pose(rng, REGION)))
        .collect();
    Placement { goal, clutter }
}

/// The dense design's region: a little wider than the paper's, still on the table and
/// mostly in the arm's reach.
const DENSE_REGION: ([f64; 2], [f64; 2]) = ([0.40, 0.98], [-0.6, 0.6]);

/// A dense layout of `layout`, placed object by object (each where the scene so far stays
/// valid), as scene text; none if an object finds no place.
fn dense_layout(
    layout: Layout,
    objects: usize,
    name: &str,
    urdf: &str,
    path: &Path,
    rng: &mut SplitMix64,
) -> Option<String> {
    let design = format!("dense clutter, {layout:?} layout");
    let away = match layout {
        Layout::Walled => GOAL_RADIUS + 0.3,
        _ => GOAL_RADIUS + 0.15,
    };
    let mut placed = Placement {
        goal: goal_start(rng, DENSE_REGION, away),
        clutter: Vec::new(),
    };
    if Scene::from_yaml(&placed.yaml(name, urdf, &design), path).is_err() {
        return None;
    }
    // Where each clutter object is drawn: near its slot in the layout, or anywhere.
    let (gx, gy) = (placed.goal[0], placed.goal[1]);
    let route = [GOAL_CENTER[0] - gx, GOAL_CENTER[1] - gy];
    let length = route[0].hypot(route[1]);
    let across = [-route[1] / length, route[0] / length];
    let middle = [(gx + GOAL_CENTER[0]) / 2.0, (gy + GOAL_CENTER[1]) / 2.0];
    for k in 1..objects {
        let kind = rng.below(CLUTTER.len());
        let slot: Option<([f64; 2], f64)> = match layout {
            Layout::GoalCovered if k <= 2 => Some((GOAL_CENTER, GOAL_RADIUS)),
            // Wall slots 0.12 m apart across the route, centred on its middle.
            Layout::Walled if k <= 5 => {
                let offset = 0.12 * (k as f64 - 3.0);
                Some((
                    [
                        middle[0] + offset * across[0],
                        middle[1] + offset * across[1],
                    ],
                    0.02,
                ))
            }
            _ => None,
        };
        let fits = (0..PLACEMENT_TRIES).find_map(|_| {
            let mut pose = uniform_pose(rng, DENSE_REGION);
            if let Some((centre, spread)) = slot {
                pose[0] = centre[0] + rng.uniform(-spread, spread);
                pose[1] = centre[1] + rng.uniform(-spread, spread);
            }
            placed.clutter.push((kind, pose));
            let text = placed.yaml(name, urdf, &design);
            if Scene::from_yaml(&text, path).is_ok() {
                Some(())
            } else {
                placed.clutter.pop();
                None
            }
        });
        fits?;
    }
    Some(placed.yaml(name, urdf, &design) + DENSE_PHYSICS)
}

/// Dense clutter is modelled with objects pushing objects: a pushed object that meets a
/// neighbour pushes it along, as it would on a real table (executed in 3D, such plans
/// reach the goal at least as often as plans that keep objects apart; `BENCHMARKS.md`).
/// Appended after placement, so a seed's layouts do not depend on it.
const DENSE_PHYSICS: &str = "physics: {object_pushing: true}\n";

impl Placement {
    /// The scene file of this placement.
    fn yaml(&self, name: &str, urdf: &str, design: &str) -> String {
        let fmt = |p: &[f64; 3]| format!("[{:.4}, {:.4}, {:.4}]", p[0], p[1], p[2]);
        let mut yaml = format!(
            "# Generated by `pushplan scenes generate` ({design}).
name: {name}
robot:
  type: arm
  urdf: {urdf}
  base_pose: {{xyz: [0.1, 0.14, 0.45], rpy: [0, 0, 0]}}
  end_effector: hand
  start_joints: [1.1203, 0.9148, -0.7126, 1.8616, 0.6553, -0.4267, 0.1763]
  pushing_plane: {{height: 0.08, orientation_rpy: [0, 2.0, 0]}}
table: {{height: 0.76, x: [0.27, 1.03], y: [-0.93, 0.93]}}
objects:
  - {{name: goal_box, shape: {{type: box, size: [0.102, 0.102, 0.215]}}, pose: {}, mass: 1.0, mu_g: 0.4, mu_c: 0.3{}}}
",
            fmt(&self.goal),
            grasps_of_side(GOAL_BOX)
        );
        for (k, (kind, pose)) in self.clutter.iter().enumerate() {
            let Clutter {
                kind,
                shape,
                mass,
                side_grasps,
            } = &CLUTTER[*kind];
            yaml += &format!(
                "  - {{name: {kind}_{}, shape: {shape}, pose: {}, mass: {mass}, mu_g: 0.4, mu_c: 0.3{}}}\n",
                k + 1,
                fmt(pose),
                side_grasps.map(grasps_of_side).unwrap_or_default()
            );
        }
        yaml += &format!(
            "goal: {{object: goal_box, center: [{}, {}], radius: {GOAL_RADIUS}}}\n",
            GOAL_CENTER[0], GOAL_CENTER[1]
        );
        yaml
    }
}
