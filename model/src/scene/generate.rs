//! Benchmark scene sets: the same goal object in every scene with a random start pose,
//! the goal disc (r = 0.1 m) at the arm's place for it, and a valid start state (checked
//! by loading each scene). For each shipped arm ([`Arm`]: the WAM on HERB's table, the
//! Panda, the UR5e and the iiwa 14 on a table before them), five designs:
//! - [`Design::Paper`], the whole-arm paper's (Sec. V-A): 1 to 7 (at most 12) movable
//!   objects in the arm's reachable workspace, each layout drawn whole and kept if valid;
//! - [`Design::Dense`]: 8 to 20 objects placed one by one where each fits, in three
//!   layouts taken in turn ([`Layout`]): scattered, the goal disc partly covered, and a
//!   wall of clutter across the straight route from the goal object to the goal disc;
//! - [`Design::OccupiedGoal`]: one to four objects inside or touching the goal disc,
//!   which lies at the table's far edge in every other scene;
//! - [`Design::MixedHeights`]: tall narrow objects (they tip unless pushed low) and flat
//!   ones (only the lowest parts of the arm reach them) among the usual clutter;
//! - [`Design::Walls`]: two static walls across the way from the goal object to the goal
//!   disc, leaving a passage of 0.20-0.26 m.
//!
//! Placed designs (all but the paper's) put objects one by one where each fits, and let
//! objects push one another. In every design a goal object that must come nearer the
//! arm's base starts where the tool reaches its centre
//! ([`super::check::goal_object_beyond_reach`]): from beyond, pushes only send it out.

use super::check::goal_object_beyond_reach;
use super::Scene;
use crate::random::SplitMix64;
use std::path::{Path, PathBuf};

/// Where the goal disc is in the WAM's scenes (m): in reach of HERB's other arm.
pub const GOAL_CENTER: [f64; 2] = [0.85, -0.3];
/// The goal disc's radius (m), in every scene.
pub const GOAL_RADIUS: f64 = 0.1;
/// A region of the table (x, y ranges, m; world frame).
type Region = ([f64; 2], [f64; 2]);

/// A kind of clutter.
#[derive(Clone, Copy)]
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

/// Clutter of mixed heights beside [`CLUTTER`]'s: tall and narrow (a sliding push tips
/// them above `b / mu_g`, 0.0875 m for the tall bottle: only the tool, on a plane below
/// that, can push them) and flat (under most of the arm: only its lowest parts reach them).
const LOW_AND_TALL: [Clutter; 3] = [
    Clutter {
        kind: "tall_bottle",
        shape: "{type: cylinder, radius: 0.035, height: 0.3}",
        mass: 0.5,
        side_grasps: Some((0.035, 0.3)),
    },
    Clutter {
        kind: "plate",
        shape: "{type: cylinder, radius: 0.09, height: 0.025}",
        mass: 0.4,
        side_grasps: None,
    },
    Clutter {
        kind: "low_box",
        shape: "{type: box, size: [0.12, 0.08, 0.04]}",
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

/// A shipped arm that scenes are generated for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arm {
    /// The Barrett WAM on HERB's table (`robots/wam7.urdf`), as in the whole-arm paper.
    Wam,
    /// The Franka Emika Panda (`robots/panda7.urdf`) on the table's near edge.
    Panda,
    /// The Universal Robots UR5e (`robots/ur5e.urdf`) with a square pusher.
    Ur5e,
    /// The KUKA LBR iiwa 14 R820 (`robots/iiwa14.urdf`) with a square pusher.
    Iiwa14,
}

impl Arm {
    /// Every shipped arm.
    pub const ALL: [Arm; 4] = [Arm::Wam, Arm::Panda, Arm::Ur5e, Arm::Iiwa14];

    /// Its name on the command line and in folder names.
    pub fn name(self) -> &'static str {
        match self {
            Arm::Wam => "wam",
            Arm::Panda => "panda",
            Arm::Ur5e => "ur5e",
            Arm::Iiwa14 => "iiwa14",
        }
    }

    fn setup(self) -> &'static ArmSetup {
        match self {
            Arm::Wam => &WAM,
            Arm::Panda => &PANDA,
            Arm::Ur5e => &UR5E,
            Arm::Iiwa14 => &IIWA14,
        }
    }
}

impl std::str::FromStr for Arm {
    type Err = String;

    fn from_str(name: &str) -> Result<Arm, String> {
        crate::input::by_name(&Arm::ALL, Arm::name, "robot", name)
    }
}

/// Where an arm stands and what its reach fits: the scene text of its robot, table and
/// allowed collisions, the goal disc's places and the regions objects are placed in.
struct ArmSetup {
    /// The URDF's file name in `robots/` and its text, built into the binary.
    urdf: &'static str,
    text: &'static str,
    /// The robot's fields after `urdf:` (base pose, end effector, start, pushing plane).
    robot: &'static str,
    /// The `table:` line and, for an arm on the table, its `allowed_collisions:`.
    table: &'static str,
    /// The goal disc's centre, and its centre at the far edge (occupied goals).
    goal: [f64; 2],
    far_goal: [f64; 2],
    /// Where the paper's design places objects, and the placed designs.
    region: Region,
    placed_region: Region,
}

/// HERB's table and WAM: the scenes of the whole-arm paper (BENCHMARKS.md's sets).
const WAM: ArmSetup = ArmSetup {
    urdf: super::builtin::WAM,
    text: include_str!("../../../robots/wam7.urdf"),
    robot: "  base_pose: {xyz: [0.1, 0.14, 0.45], rpy: [0, 0, 0]}
  end_effector: hand
  start_joints: [1.1203, 0.9148, -0.7126, 1.8616, 0.6553, -0.4267, 0.1763]
  pushing_plane: {height: 0.08, orientation_rpy: [0, 2.0, 0]}
",
    table: "table: {height: 0.76, x: [0.27, 1.03], y: [-0.93, 0.93]}\n",
    goal: GOAL_CENTER,
    far_goal: [0.93, -0.3],
    region: ([0.45, 0.95], [-0.45, 0.5]),
    placed_region: ([0.40, 0.98], [-0.6, 0.6]),
};

/// The table-mounted arms stand at the world origin at the table top's height (0.76 m),
/// the table before them; the tool points down, 6 cm above the table (a glass, the lowest
/// tipping height of the clutter at 0.0875 m, is pushed below it). Start: the tool at
/// (0.3, 0.35), found with `pushplan robot --reach` nearest a usual working pose. Tables
/// and goals fit each arm's reach with the tool down (`pushplan robot --reach`): the
/// Panda's to about 0.76 m from its base, the iiwa's to 0.81 m, the UR5e's beyond 0.85 m.
const PANDA: ArmSetup = ArmSetup {
    urdf: "panda7.urdf",
    text: include_str!("../../../robots/panda7.urdf"),
    robot: "  base_pose: {xyz: [0, 0, 0.76], rpy: [0, 0, 0]}
  end_effector: tool
  start_joints: [0.4281, 0.5118, 0.3225, -2.4368, -0.6343, 2.8766, 2.1139]
  pushing_plane: {height: 0.06, orientation_rpy: [3.141592653589793, 0, 0]}
",
    table: "table: {height: 0.76, x: [0.2, 0.8], y: [-0.6, 0.6]}
allowed_collisions: [[panda_link0, table]]
",
    goal: [0.5, -0.3],
    far_goal: [0.7, -0.25],
    region: ([0.3, 0.7], [-0.45, 0.45]),
    placed_region: ([0.25, 0.75], [-0.55, 0.55]),
};

const UR5E: ArmSetup = ArmSetup {
    urdf: "ur5e.urdf",
    text: include_str!("../../../robots/ur5e.urdf"),
    robot: "  base_pose: {xyz: [0, 0, 0.76], rpy: [0, 0, 0]}
  end_effector: tool
  start_joints: [3.7104, -1.4279, 2.1998, -2.3427, -1.5708, 0.568]
  pushing_plane: {height: 0.06, orientation_rpy: [3.141592653589793, 0, 0]}
",
    table: "table: {height: 0.76, x: [0.2, 0.95], y: [-0.6, 0.6]}
allowed_collisions: [[base_link, table]]
",
    goal: [0.6, -0.3],
    far_goal: [0.85, -0.3],
    region: ([0.3, 0.85], [-0.5, 0.5]),
    placed_region: ([0.25, 0.9], [-0.55, 0.55]),
};

/// The iiwa stands on a 0.2 m riser: with the tool down, its elbow (at most 120 degrees)
/// keeps the tool at least 0.41 m from the base axis when the shoulder is level with the
/// wrist; 0.25 m above it the nearest reach is 0.32 m.
const IIWA14: ArmSetup = ArmSetup {
    urdf: "iiwa14.urdf",
    text: include_str!("../../../robots/iiwa14.urdf"),
    robot: "  base_pose: {xyz: [0, 0, 0.96], rpy: [0, 0, 0]}
  end_effector: tool
  start_joints: [0.5876, -1.2113, 0.0006, -1.5521, -0.0015, -0.3781, -0.0024]
  pushing_plane: {height: 0.06, orientation_rpy: [3.141592653589793, 0, 0]}
",
    table: "table: {height: 0.76, x: [0.3, 0.85], y: [-0.6, 0.6]}\n",
    goal: [0.55, -0.3],
    far_goal: [0.72, -0.25],
    region: ([0.35, 0.78], [-0.5, 0.5]),
    placed_region: ([0.32, 0.8], [-0.55, 0.55]),
};

/// Which scene set to generate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Design {
    /// The whole-arm paper's design (Sec. V-A): 1 to 12 objects, whole layouts drawn and
    /// kept when valid.
    Paper,
    /// Dense clutter: objects placed one by one (scattered, over the goal disc, or as a
    /// wall across the way), objects pushing objects.
    Dense,
    /// One to four objects inside or touching the goal disc (at the table's far edge in
    /// every other scene): the goal region itself must be cleared.
    OccupiedGoal,
    /// Tall narrow and flat objects among the usual clutter.
    MixedHeights,
    /// Two static walls across the way to the goal disc, a narrow passage between them.
    Walls,
}

impl Design {
    /// Every design.
    pub const ALL: [Design; 5] = [
        Design::Paper,
        Design::Dense,
        Design::OccupiedGoal,
        Design::MixedHeights,
        Design::Walls,
    ];

    /// Its name on the command line and in folder names.
    pub fn name(self) -> &'static str {
        match self {
            Design::Paper => "paper",
            Design::Dense => "dense",
            Design::OccupiedGoal => "occupied_goal",
            Design::MixedHeights => "mixed_heights",
            Design::Walls => "walls",
        }
    }

    /// The most objects the design places.
    fn max_objects(self) -> usize {
        match self {
            Design::Paper => PAPER_MAX_OBJECTS,
            _ => DENSE_MAX_OBJECTS,
        }
    }

    /// The fewest: an occupied goal needs the goal object and one on the disc.
    fn min_objects(self) -> usize {
        match self {
            Design::OccupiedGoal => 2,
            _ => 1,
        }
    }
}

impl std::str::FromStr for Design {
    type Err = String;

    fn from_str(name: &str) -> Result<Design, String> {
        crate::input::by_name(&Design::ALL, Design::name, "design", name)
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
/// The most objects the placed designs place.
const DENSE_MAX_OBJECTS: usize = 20;
/// Tries to place one object of a placed scene before the layout is drawn again.
const PLACEMENT_TRIES: usize = 200;

/// Writes `count` scenes of `design` for `arm` into `dir`, with object counts spread
/// evenly over `objects` (inclusive), drawn from `seed`. Returns the files.
pub fn generate(
    design: Design,
    arm: Arm,
    count: usize,
    objects: (usize, usize),
    seed: u64,
    dir: &Path,
) -> Result<Vec<PathBuf>, String> {
    let (lo, hi) = objects;
    let (min, max) = (design.min_objects(), design.max_objects());
    if lo < min || lo > hi || hi > max {
        return Err(format!(
            "objects must be a range within {min}..{max} for the {} design, got {lo}..{hi}{}",
            design.name(),
            if design == Design::Paper {
                " (the placed designs place up to 20)"
            } else {
                ""
            }
        ));
    }
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let setup = arm.setup();
    let urdf = super::builtin::robot_file_for(dir, setup.urdf, setup.text)?;
    let urdf = crate::input::relative_path(dir, &urdf)?;
    let mut rng = SplitMix64::new(seed);
    let mut files = Vec::with_capacity(count);
    for i in 0..count {
        let n = lo + i * (hi - lo + 1) / count.max(1);
        let path = dir.join(format!("scene_{i:02}.yaml"));
        let scene = SceneText {
            name: match design {
                Design::Paper => format!("benchmark-{i:02}"),
                Design::Dense => format!("dense-{i:02}"),
                _ => format!("{}-{}-{i:02}", arm.name(), design.name()),
            },
            urdf: &urdf,
            setup,
            path: &path,
        };
        let yaml = match design {
            Design::Paper => (0..10_000)
                .map(|_| scene.yaml(&paper_layout(setup, n, &mut rng), PAPER_DESIGN))
                .find(|yaml| loads_pushable(yaml, &path)),
            Design::Dense => {
                let layout = Layout::ALL[i % Layout::ALL.len()];
                (0..100).find_map(|_| dense_layout(&scene, layout, n, &mut rng))
            }
            Design::OccupiedGoal | Design::MixedHeights | Design::Walls => {
                (0..100).find_map(|_| family_layout(&scene, design, i % 2 == 1, n, &mut rng))
            }
        }
        .ok_or_else(|| {
            format!(
                "{}: no valid {} layout of {n} objects for the {} found (seed {seed}); \
                 another seed or fewer objects may give one",
                path.display(),
                design.name(),
                arm.name()
            )
        })?;
        crate::output::write_whole(&path, yaml)?;
        files.push(path);
    }
    Ok(files)
}

/// One shipped scene set: `scenes/ARM/DESIGN/scene_NN.yaml`, generated with seed 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShippedSet {
    /// The arm.
    pub arm: Arm,
    /// The design.
    pub design: Design,
    /// Scenes in the set.
    pub count: usize,
    /// The object counts, spread over the scenes.
    pub objects: (usize, usize),
}

impl ShippedSet {
    /// Its folder under the scenes folder: `ARM/DESIGN`.
    pub fn folder(&self) -> PathBuf {
        Path::new(self.arm.name()).join(self.design.name())
    }
}

/// The seed of every shipped set: development scenes (held-out sets use other seeds and
/// are not shipped).
pub const SHIPPED_SEED: u64 = 1;

/// The scene sets shipped for every arm and design, beside the WAM's paper and dense sets
/// (`scenes/benchmark`, 35 scenes, and `scenes/dense`, 20): ten paper scenes, four dense
/// and six of each family per arm.
pub fn shipped_sets() -> Vec<ShippedSet> {
    let mut sets = Vec::new();
    for arm in Arm::ALL {
        for design in Design::ALL {
            let (count, objects) = match design {
                Design::Paper => (10, (1, 7)),
                Design::Dense => (4, (8, 14)),
                _ => (6, (2, 7)),
            };
            if arm == Arm::Wam && matches!(design, Design::Paper | Design::Dense) {
                continue;
            }
            sets.push(ShippedSet {
                arm,
                design,
                count,
                objects,
            });
        }
    }
    sets
}

/// Writes every [`shipped_sets`] set under `root` (the scenes folder); returns the files.
pub fn generate_shipped(root: &Path) -> Result<Vec<PathBuf>, String> {
    let mut files = Vec::new();
    for set in shipped_sets() {
        let dir = root.join(set.folder());
        files.extend(generate(
            set.design,
            set.arm,
            set.count,
            set.objects,
            SHIPPED_SEED,
            &dir,
        )?);
    }
    Ok(files)
}

/// Object poses `[x, y, yaw]` (m, rad; world frame) of a scene: the goal object's, each
/// clutter object's with its kind, the goal disc's centre, and static walls.
struct Placement {
    goal: [f64; 3],
    clutter: Vec<(&'static Clutter, [f64; 3])>,
    goal_center: [f64; 2],
    walls: Vec<Wall>,
}

/// A static wall standing on the table: its centre (m), yaw (rad) and length (m).
struct Wall {
    center: [f64; 2],
    yaw: f64,
    length: f64,
}

/// Wall thickness and height (m): lower than the arm's upper links, higher than the tool.
const WALL_SIZE: (f64, f64) = (0.02, 0.12);

fn uniform_pose(rng: &mut SplitMix64, region: Region) -> [f64; 3] {
    [
        rng.uniform(region.0[0], region.0[1]),
        rng.uniform(region.1[0], region.1[1]),
        rng.uniform(-std::f64::consts::PI, std::f64::consts::PI),
    ]
}

/// A goal-object start at least `away` (m) from `center`.
fn goal_start(rng: &mut SplitMix64, region: Region, center: [f64; 2], away: f64) -> [f64; 3] {
    loop {
        let goal = uniform_pose(rng, region);
        if (goal[0] - center[0]).hypot(goal[1] - center[1]) >= away {
            return goal;
        }
    }
}

const PAPER_DESIGN: &str = "the whole-arm paper's dataset design";

/// The paper's design: a whole random layout (not yet checked).
fn paper_layout(setup: &ArmSetup, objects: usize, rng: &mut SplitMix64) -> Placement {
    // The goal object starts out of the goal disc (it has to be pushed there).
    let goal = goal_start(rng, setup.region, setup.goal, GOAL_RADIUS + 0.15);
    let clutter = (1..objects)
        .map(|_| {
            (
                &CLUTTER[rng.below(CLUTTER.len())],
                uniform_pose(rng, setup.region),
            )
        })
        .collect();
    Placement {
        goal,
        clutter,
        goal_center: setup.goal,
        walls: Vec::new(),
    }
}

/// A dense layout of `layout`, placed object by object, as scene text; none if an object
/// finds no place.
fn dense_layout(
    scene: &SceneText,
    layout: Layout,
    objects: usize,
    rng: &mut SplitMix64,
) -> Option<String> {
    let design = format!("dense clutter, {layout:?} layout");
    let setup = scene.setup;
    let away = match layout {
        Layout::Walled => GOAL_RADIUS + 0.3,
        _ => GOAL_RADIUS + 0.15,
    };
    let mut placed = Placement {
        goal: goal_start(rng, setup.placed_region, setup.goal, away),
        clutter: Vec::new(),
        goal_center: setup.goal,
        walls: Vec::new(),
    };
    if !scene.goal_object_pushable(&placed, &design) {
        return None;
    }
    // Where each clutter object is drawn: near its slot in the layout, or anywhere.
    let route = Route::of(&placed);
    place_clutter(scene, &mut placed, &design, objects, &CLUTTER, rng, |k| {
        match layout {
            Layout::GoalCovered if k <= 2 => Some((setup.goal, GOAL_RADIUS)),
            // Wall slots 0.12 m apart across the route, centred on its middle.
            Layout::Walled if k <= 5 => Some((route.across_middle(0.12 * (k as f64 - 3.0)), 0.02)),
            _ => None,
        }
    })?;
    Some(scene.yaml(&placed, &design) + PLACED_PHYSICS)
}

/// A layout of one of the families (occupied goal, mixed heights, walls), placed object
/// by object; `far`: the occupied goal's disc at the table's far edge.
fn family_layout(
    scene: &SceneText,
    design: Design,
    far: bool,
    objects: usize,
    rng: &mut SplitMix64,
) -> Option<String> {
    let setup = scene.setup;
    let goal_center = match (design, far) {
        (Design::OccupiedGoal, true) => setup.far_goal,
        _ => setup.goal,
    };
    let text = match (design, far) {
        (Design::OccupiedGoal, true) => "occupied goal at the table's far edge",
        (Design::OccupiedGoal, false) => "occupied goal",
        (Design::MixedHeights, _) => "mixed heights",
        _ => "walls with a narrow passage",
    };
    let away = match design {
        Design::Walls => GOAL_RADIUS + 0.3,
        _ => GOAL_RADIUS + 0.15,
    };
    let mut placed = Placement {
        goal: goal_start(rng, setup.placed_region, goal_center, away),
        clutter: Vec::new(),
        goal_center,
        walls: Vec::new(),
    };
    if design == Design::Walls {
        // Two walls on the line across the route's middle, the passage between them off
        // the middle by up to 8 cm.
        let route = Route::of(&placed);
        let gap = rng.uniform(0.20, 0.26);
        let shift = rng.uniform(-0.08, 0.08);
        let length = 0.3;
        for side in [-1.0, 1.0] {
            placed.walls.push(Wall {
                center: route.across_middle(shift + side * (gap + length) / 2.0),
                yaw: route.across[1].atan2(route.across[0]),
                length,
            });
        }
    }
    if !scene.goal_object_pushable(&placed, text) {
        return None;
    }
    let on_goal = match design {
        Design::OccupiedGoal => (1 + rng.below(4)).min(objects - 1),
        _ => 0,
    };
    let kinds: &'static [Clutter] = match design {
        Design::MixedHeights => &MIXED_HEIGHTS,
        _ => &CLUTTER,
    };
    // On the goal disc: centres within its radius (the object inside it or touching it).
    place_clutter(scene, &mut placed, text, objects, kinds, rng, |k| {
        (k <= on_goal).then_some((goal_center, GOAL_RADIUS))
    })?;
    Some(scene.yaml(&placed, text) + PLACED_PHYSICS)
}

/// [`CLUTTER`] and [`LOW_AND_TALL`] together.
const MIXED_HEIGHTS: [Clutter; 7] = [
    CLUTTER[0],
    CLUTTER[1],
    CLUTTER[2],
    CLUTTER[3],
    LOW_AND_TALL[0],
    LOW_AND_TALL[1],
    LOW_AND_TALL[2],
];

/// The straight route from the goal object's start to the goal disc's centre.
struct Route {
    middle: [f64; 2],
    /// Unit vector across it (to its left).
    across: [f64; 2],
}

impl Route {
    fn of(placed: &Placement) -> Route {
        let (g, c) = (placed.goal, placed.goal_center);
        let along = [c[0] - g[0], c[1] - g[1]];
        let length = along[0].hypot(along[1]);
        Route {
            middle: [(g[0] + c[0]) / 2.0, (g[1] + c[1]) / 2.0],
            across: [-along[1] / length, along[0] / length],
        }
    }

    /// The point `offset` (m) across the route from its middle.
    fn across_middle(&self, offset: f64) -> [f64; 2] {
        [
            self.middle[0] + offset * self.across[0],
            self.middle[1] + offset * self.across[1],
        ]
    }
}

/// Places clutter objects 1 to `objects - 1` one by one: each of a kind drawn from
/// `kinds`, near its slot (`slot(k)`: a centre and a spread, m) or anywhere in the
/// placed region, kept where the scene still loads (at most [`PLACEMENT_TRIES`] tries);
/// none if one finds no place.
fn place_clutter(
    scene: &SceneText,
    placed: &mut Placement,
    design: &str,
    objects: usize,
    kinds: &'static [Clutter],
    rng: &mut SplitMix64,
    slot: impl Fn(usize) -> Option<([f64; 2], f64)>,
) -> Option<()> {
    for k in 1..objects {
        let kind = &kinds[rng.below(kinds.len())];
        let slot = slot(k);
        (0..PLACEMENT_TRIES).find_map(|_| {
            let mut pose = uniform_pose(rng, scene.setup.placed_region);
            if let Some((centre, spread)) = slot {
                pose[0] = centre[0] + rng.uniform(-spread, spread);
                pose[1] = centre[1] + rng.uniform(-spread, spread);
            }
            placed.clutter.push((kind, pose));
            if scene.loads(placed, design) {
                Some(())
            } else {
                placed.clutter.pop();
                None
            }
        })?;
    }
    Some(())
}

/// Does the scene text load, its goal object where the arm can push it toward the goal
/// ([`goal_object_beyond_reach`])?
fn loads_pushable(yaml: &str, path: &Path) -> bool {
    Scene::from_yaml(yaml, path).is_ok_and(|s| !goal_object_beyond_reach(&s))
}

/// Placed designs are modelled with objects pushing objects: a pushed object that meets
/// a neighbour pushes it along, as it would on a real table (executed in 3D, such plans
/// reach the goal at least as often as plans that keep objects apart; `BENCHMARKS.md`).
/// Appended after placement, so a seed's layouts do not depend on it.
const PLACED_PHYSICS: &str = "physics: {object_pushing: true}\n";

/// What a scene file of a set is written with: its name, its arm and where it goes.
struct SceneText<'a> {
    name: String,
    urdf: &'a str,
    setup: &'static ArmSetup,
    path: &'a Path,
}

impl SceneText<'_> {
    /// Does the scene of `placed` load (every rule, the start valid)?
    fn loads(&self, placed: &Placement, design: &str) -> bool {
        Scene::from_yaml(&self.yaml(placed, design), self.path).is_ok()
    }

    /// [`loads_pushable`] for the scene of `placed`, asked once the goal object (and
    /// walls) are placed: clutter does not change it.
    fn goal_object_pushable(&self, placed: &Placement, design: &str) -> bool {
        loads_pushable(&self.yaml(placed, design), self.path)
    }

    /// The scene file of `placed`.
    fn yaml(&self, placed: &Placement, design: &str) -> String {
        let fmt = |p: &[f64; 3]| format!("[{:.4}, {:.4}, {:.4}]", p[0], p[1], p[2]);
        let mut yaml = format!(
            "# Generated by `pushplan scenes generate` ({design}).
name: {}
robot:
  type: arm
  urdf: {}
{}{}",
            self.name, self.urdf, self.setup.robot, self.setup.table
        );
        if !placed.walls.is_empty() {
            yaml += "obstacles:\n";
            for (k, wall) in placed.walls.iter().enumerate() {
                let (thickness, height) = WALL_SIZE;
                yaml += &format!(
                    "  - {{name: wall_{}, shape: {{type: box, size: [{}, {thickness}, {height}]}}, pose: {{xyz: [{:.4}, {:.4}, {}], rpy: [0, 0, {:.4}]}}}}\n",
                    k + 1,
                    wall.length,
                    wall.center[0],
                    wall.center[1],
                    TABLE_TOP + height / 2.0,
                    wall.yaw
                );
            }
        }
        yaml += &format!(
            "objects:
  - {{name: goal_box, shape: {{type: box, size: [0.102, 0.102, 0.215]}}, pose: {}, mass: 1.0, mu_g: 0.4, mu_c: 0.3{}}}
",
            fmt(&placed.goal),
            grasps_of_side(GOAL_BOX)
        );
        for (k, (clutter, pose)) in placed.clutter.iter().enumerate() {
            let Clutter {
                kind,
                shape,
                mass,
                side_grasps,
            } = clutter;
            yaml += &format!(
                "  - {{name: {kind}_{}, shape: {shape}, pose: {}, mass: {mass}, mu_g: 0.4, mu_c: 0.3{}}}\n",
                k + 1,
                fmt(pose),
                side_grasps.map(grasps_of_side).unwrap_or_default()
            );
        }
        yaml += &format!(
            "goal: {{object: goal_box, center: [{}, {}], radius: {GOAL_RADIUS}}}\n",
            placed.goal_center[0], placed.goal_center[1]
        );
        yaml
    }
}

/// The table top's height in every set (m, world z).
const TABLE_TOP: f64 = 0.76;
