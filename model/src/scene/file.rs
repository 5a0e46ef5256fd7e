//! The scene file format (YAML), as typed structs. Unknown keys are rejected everywhere.
//! Units: metres, radians, kilograms, seconds. See the README for an annotated example.

use super::number::number;
use crate::robot::ProjectionSettings;
use serde::Deserialize;
use std::path::PathBuf;

/// A name: a string, not YAML's null (which would otherwise become the name "null").
fn name<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<String, D::Error> {
    Option::<String>::deserialize(deserializer)?
        .ok_or_else(|| serde::de::Error::custom("a name is needed, not null"))
}

/// A scene file as written (YAML): every field as read, before validation
/// ([`crate::scene::Scene`] is the validated form).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Human-readable scene name (defaults to the file stem).
    pub name: Option<String>,
    /// The robot and its start.
    pub robot: RobotSpec,
    /// The table.
    pub table: TableSpec,
    /// Static obstacles.
    #[serde(default)]
    pub obstacles: Vec<ObstacleSpec>,
    /// Movable objects (the goal object among them).
    #[serde(default)]
    pub objects: Vec<ObjectSpec>,
    /// What the plan must achieve.
    pub goal: GoalSpec,
    /// Planner parameters (every one has a default).
    #[serde(default)]
    pub planner: PlannerSpec,
    /// Physics parameters (every one has a default).
    #[serde(default)]
    pub physics: PhysicsSpec,
    /// How the plan is timed into a trajectory.
    #[serde(default)]
    pub trajectory: TrajectorySpec,
    /// Pairs allowed to touch: a robot link with `table`, an obstacle or another link
    /// (a base bolted onto the table, say).
    #[serde(default)]
    pub allowed_collisions: Vec<[String; 2]>,
}

/// The robot: an arm from URDF or the planar hand (`type`).
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum RobotSpec {
    /// A serial arm from URDF.
    Arm {
        /// URDF file, relative to the scene file.
        urdf: PathBuf,
        /// World pose of the URDF's root link.
        #[serde(default)]
        base_pose: PoseSpec,
        /// Start configuration (rad / m), one value per joint from base to end effector.
        #[serde(deserialize_with = "number")]
        start_joints: Vec<f64>,
        /// The end-effector link (default: the tip of the SRDF group's chain).
        #[serde(default)]
        end_effector: Option<String>,
        /// MoveIt SRDF, relative to the scene file (default: the URDF's path with `.srdf`,
        /// if there is such a file): its `disable_collisions` pairs are never checked, its
        /// chain group names the arm.
        #[serde(default)]
        srdf: Option<PathBuf>,
        /// The SRDF group whose chain is the arm: its base link's joints and those above
        /// are held, its tip is the default end effector (default: the only chain group,
        /// used when `end_effector` is not given).
        #[serde(default)]
        group: Option<String>,
        /// The tool point and frame in the end-effector link (default: the link frame).
        #[serde(default)]
        tool: PoseSpec,
        /// The plane the tool is held on.
        pushing_plane: PlaneSpec,
    },
    /// The free-flying planar pusher.
    PlanarHand {
        /// The hand's solid, centred on the hand frame.
        shape: ShapeSpec,
        /// Start pose [x, y, yaw] (m, m, rad), world frame.
        #[serde(deserialize_with = "number")]
        start: [f64; 3],
        /// Height of the hand frame above the table top (m).
        #[serde(deserialize_with = "number")]
        height: f64,
    },
}

/// A pose: translation (m) and roll, pitch, yaw (rad), applied as `Rz(yaw) Ry(pitch) Rx(roll)`.
#[derive(Debug, Deserialize, Default, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct PoseSpec {
    /// Translation (m).
    #[serde(default)]
    #[serde(deserialize_with = "number")]
    pub xyz: [f64; 3],
    /// Roll, pitch, yaw (rad).
    #[serde(default)]
    #[serde(deserialize_with = "number")]
    pub rpy: [f64; 3],
}

/// The pushing plane: the tool's height and tilt.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneSpec {
    /// Height of the tool point above the table top (m).
    #[serde(deserialize_with = "number")]
    pub height: f64,
    /// The tool's world orientation at yaw 0 (roll, pitch, yaw in rad); yaw stays free.
    #[serde(deserialize_with = "number")]
    pub orientation_rpy: [f64; 3],
}

/// The table: its top's height and extent.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TableSpec {
    /// World height of the table top (m).
    #[serde(deserialize_with = "number")]
    pub height: f64,
    /// Extent of the support surface along world x and y: [min, max] (m).
    #[serde(deserialize_with = "number")]
    pub x: [f64; 2],
    /// Extent along world y: [min, max] (m).
    #[serde(deserialize_with = "number")]
    pub y: [f64; 2],
    /// Thickness of the table top slab (m).
    #[serde(default = "default_table_thickness")]
    #[serde(deserialize_with = "number")]
    pub thickness: f64,
}

fn default_table_thickness() -> f64 {
    0.05
}

/// A solid. Cylinders and prisms stand upright (along z), centred on their frame.
#[derive(Debug, Deserialize, Clone)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ShapeSpec {
    /// A box centred on its frame.
    Box {
        /// Full side lengths x, y, z (m).
        #[serde(deserialize_with = "number")]
        size: [f64; 3],
    },
    /// An upright cylinder.
    Cylinder {
        /// Radius (m).
        #[serde(deserialize_with = "number")]
        radius: f64,
        /// Height (m).
        #[serde(deserialize_with = "number")]
        height: f64,
    },
    /// A convex polygon (x, y vertices in the body frame) extruded to `height`.
    Polygon {
        /// The vertices, counter-clockwise (m).
        #[serde(deserialize_with = "number")]
        vertices: Vec<[f64; 2]>,
        /// Height of the extrusion (m).
        #[serde(deserialize_with = "number")]
        height: f64,
    },
    /// An STL mesh (file relative to the scene file), used as its convex hull.
    Mesh {
        /// The mesh file, relative to the scene file.
        file: PathBuf,
        /// Scale along x, y, z (default 1).
        #[serde(default = "unit_scale")]
        #[serde(deserialize_with = "number")]
        scale: [f64; 3],
    },
}

fn unit_scale() -> [f64; 3] {
    [1.0; 3]
}

/// A static obstacle.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObstacleSpec {
    /// Its name (unique among obstacles).
    #[serde(deserialize_with = "name")]
    pub name: String,
    /// Its solid.
    pub shape: ShapeSpec,
    /// World pose of the shape's frame.
    pub pose: PoseSpec,
}

/// A movable object.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectSpec {
    /// Its name (unique among objects).
    #[serde(deserialize_with = "name")]
    pub name: String,
    /// box, cylinder or polygon; it rests on the table.
    pub shape: ShapeSpec,
    /// [x, y, yaw] of the footprint's centre (m, m, rad), world frame.
    #[serde(deserialize_with = "number")]
    pub pose: [f64; 3],
    /// Mass (kg).
    #[serde(deserialize_with = "number")]
    pub mass: f64,
    /// Friction coefficient with the table.
    #[serde(deserialize_with = "number")]
    pub mu_g: f64,
    /// Friction coefficient with the robot.
    #[serde(deserialize_with = "number")]
    pub mu_c: f64,
    /// Pressure distribution over the footprint; sets the characteristic length.
    #[serde(default)]
    pub pressure: PressureSpec,
    /// Ways to grasp it: Workspace Goal Regions in the object frame.
    #[serde(default)]
    pub grasps: Vec<GraspSpec>,
}

/// The physics model of a scene (`physics.model`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PhysicsModel {
    /// Quasistatic planar pushing (the whole-arm paper).
    #[default]
    Quasistatic,
    /// A rigid-body engine run until the objects rest (the workshop paper).
    SemiDynamic,
}

/// A Workspace Goal Region of an object (Berenson et al.): the grasp frame `w` in the
/// object frame (whose origin is the footprint's centre on the table top), the end
/// effector's pose in `w` (`T_e^w`), and how far the grasp may move within `w`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GraspSpec {
    /// The grasp frame `w` in the object frame.
    #[serde(default)]
    pub frame: PoseSpec,
    /// The end effector's pose in `w` (`T_e^w`).
    #[serde(default)]
    pub end_effector: PoseSpec,
    /// How far the grasp may move within `w`.
    #[serde(default)]
    pub bounds: BoundsSpec,
}

/// `B^w`: [min, max] of each displacement coordinate (m; rad); 0 when left out.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct BoundsSpec {
    /// Displacement along x (m).
    #[serde(default)]
    #[serde(deserialize_with = "number")]
    pub x: [f64; 2],
    /// Displacement along y (m).
    #[serde(default)]
    #[serde(deserialize_with = "number")]
    pub y: [f64; 2],
    /// Displacement along z (m).
    #[serde(default)]
    #[serde(deserialize_with = "number")]
    pub z: [f64; 2],
    /// Roll (rad).
    #[serde(default)]
    #[serde(deserialize_with = "number")]
    pub roll: [f64; 2],
    /// Pitch (rad).
    #[serde(default)]
    #[serde(deserialize_with = "number")]
    pub pitch: [f64; 2],
    /// Yaw (rad).
    #[serde(default)]
    #[serde(deserialize_with = "number")]
    pub yaw: [f64; 2],
}

/// The support pressure over an object's footprint.
#[derive(Debug, Deserialize, Default)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum PressureSpec {
    /// Uniform pressure: c is computed from the footprint.
    #[default]
    Uniform,
    /// A given characteristic length c (m).
    CharacteristicLength {
        /// The characteristic length (m).
        #[serde(deserialize_with = "number")]
        c: f64,
    },
}

/// Either `object` + `center` + `radius`, or `configuration` (+ `tolerance`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GoalSpec {
    /// Name of the goal object.
    pub object: Option<String>,
    /// Goal disc centre [x, y] (m), world frame.
    #[serde(default, deserialize_with = "number")]
    pub center: Option<[f64; 2]>,
    /// Goal disc radius (m).
    #[serde(default, deserialize_with = "number")]
    pub radius: Option<f64>,
    /// How far inside the disc's edge the goal object's centre must end (m).
    #[serde(default, deserialize_with = "number")]
    pub margin: Option<f64>,
    /// A robot goal configuration instead.
    #[serde(default, deserialize_with = "number")]
    pub configuration: Option<Vec<f64>>,
    /// Distance in configuration space counted as reached (rad).
    #[serde(default, deserialize_with = "number")]
    pub tolerance: Option<f64>,
    /// Or: an object whose grasp (one of its `grasps`) the tool must reach, pushing
    /// clutter aside on the way.
    pub grasp: Option<String>,
    /// With `grasp`: may pushes move the object to grasp too (default false: it must stay
    /// where it starts).
    #[serde(default, deserialize_with = "number")]
    pub object_may_move: Option<bool>,
}

/// Planner parameters; every field has a default (see [`PlannerSpec::default`]). C++'s
/// `pushplan::detail::PlannerParams` (`cpp/problem/bridge_types.h`) is the same type: the
/// bridge
/// passes it as is.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq)]
#[serde(default, deny_unknown_fields)]
#[repr(C)]
pub struct PlannerSpec {
    /// Search time limit (s).
    #[serde(deserialize_with = "number")]
    pub time_limit: f64,
    /// Random seed.
    #[serde(deserialize_with = "number")]
    pub seed: u64,
    /// Control samples per extension (Alg. 1).
    #[serde(deserialize_with = "number")]
    pub k: u32,
    /// Tree states a nearest-neighbour query compares at most, nearest boxes first; 0
    /// for exact answers (slower as the tree grows; see `planner::NearestTree`).
    #[serde(deserialize_with = "number")]
    pub nearest_checks: u32,
    /// Probability of sampling the goal.
    #[serde(deserialize_with = "number")]
    pub goal_bias: f64,
    /// Propagation step dt (s).
    #[serde(deserialize_with = "number")]
    pub step: f64,
    /// Shortest and longest control duration (s).
    #[serde(deserialize_with = "number")]
    pub min_duration: f64,
    /// Longest control duration (s).
    #[serde(deserialize_with = "number")]
    pub max_duration: f64,
    /// Bound on |vx|, |vy| of the end effector (m/s).
    #[serde(deserialize_with = "number")]
    pub max_ee_speed: f64,
    /// Bound on |omega_z| of the end effector (rad/s).
    #[serde(deserialize_with = "number")]
    pub max_ee_turn_rate: f64,
    /// Bound on each joint's null-space sample (rad/s).
    #[serde(deserialize_with = "number")]
    pub max_nullspace_speed: f64,
    /// Distance weights: robot configuration, each object, the goal object.
    #[serde(deserialize_with = "number")]
    pub robot_weight: f64,
    /// Distance weight of each object other than the goal object.
    #[serde(deserialize_with = "number")]
    pub object_weight: f64,
    /// Distance weight of the goal object.
    #[serde(deserialize_with = "number")]
    pub goal_object_weight: f64,
    /// Length (m) that one radian of object yaw counts as in the distance.
    #[serde(deserialize_with = "number")]
    pub rotation_length: f64,
}

impl Default for PlannerSpec {
    fn default() -> Self {
        Self {
            time_limit: 30.0,
            seed: 1,
            k: 3,
            nearest_checks: 128,
            goal_bias: 0.05,
            step: 0.01,
            min_duration: 0.1,
            max_duration: 0.5,
            max_ee_speed: 0.5,
            max_ee_turn_rate: 1.0,
            max_nullspace_speed: 0.5,
            robot_weight: 1.0,
            object_weight: 1.0,
            goal_object_weight: 20.0,
            rotation_length: 0.1,
        }
    }
}

/// Tolerances of the physics and validity model; every field has a default.
#[derive(Debug, Deserialize, Clone, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct PhysicsSpec {
    /// Contacts are tracked from this distance on (m): more than a link moves in a step.
    #[serde(deserialize_with = "number")]
    pub contact_margin: f64,
    /// Arm-object penetration tolerated (m).
    #[serde(deserialize_with = "number")]
    pub penetration_tolerance: f64,
    /// Object-object overlap tolerated (m).
    #[serde(deserialize_with = "number")]
    pub overlap_tolerance: f64,
    /// A touching contact whose normal is within this angle of vertical is invalid (rad):
    /// a link pressing down on the object, not pushing it in the plane.
    #[serde(deserialize_with = "number")]
    pub vertical_normal_angle: f64,
    /// Fastest joint motion a step may ask (rad/s or m/s); faster means a singularity.
    /// A speed, so that the same action near the same singularity is refused at any
    /// `planner.step` (at the default 0.01 s: 0.05 rad per step).
    #[serde(deserialize_with = "number")]
    pub max_joint_speed: f64,
    /// Tolerated distance of the tool from its plane (m) and tilt (rad).
    #[serde(deserialize_with = "number")]
    pub plane_tolerance: f64,
    /// Tolerated tilt of the tool from its plane's orientation (rad).
    #[serde(deserialize_with = "number")]
    pub tilt_tolerance: f64,
    /// Reserve against tipping, a fraction in [0, 1): the support's centre of pressure
    /// must stay inside the footprint shrunk by this fraction about its centroid. The
    /// default 0.3 covers a support friction 20 % above the scene's (the noise of
    /// `check --noise`) and what a real, compliant contact adds on top: in the 3D engine
    /// a glass pushed at 0.8 of its `b / mu_g` leans by 0.03 rad on its compressed edge,
    /// and with 0.2 two of 330 executed trials rocked a glass past 8.6 degrees
    /// (BENCHMARKS.md, "Plans that work in the world").
    #[serde(deserialize_with = "number")]
    pub tipping_margin: f64,
    /// Smallest distance between a moving object and any other object or obstacle (m).
    #[serde(deserialize_with = "number")]
    pub object_clearance: f64,
    /// Smallest distance a moving object keeps from the table's edges (m), or its
    /// distance in the start state where that is smaller (default 0.01; 0: an object may
    /// touch an edge but not reach past it). A plan that slides an object flush along an
    /// edge leaves the world no room: a box pushed along it creeps over by a millimetre
    /// or so in MuJoCo, and every rest from there is refused (BENCHMARKS.md, "Room at
    /// the table's edge").
    #[serde(deserialize_with = "number")]
    pub edge_clearance: f64,
    /// Smallest distance a link closing in on an object keeps from it where a push
    /// hard enough to slide the object would tip it (m): such a touch must not happen,
    /// and a plan that misses it by millimetres tips the object when it stands a little
    /// elsewhere. At most `contact_margin` (contacts are tracked from there on); 0 turns
    /// the rule off.
    #[serde(deserialize_with = "number")]
    pub arm_clearance: f64,
    /// How pushed objects move: `quasistatic` (the default: the planar pushing model) or
    /// `semi_dynamic` (the workshop paper's: a 2D rigid-body engine; objects may be
    /// struck, push one another and coast, and must come to rest within `t_max`).
    pub model: PhysicsModel,
    /// Semi-dynamic model: longest time for every object to come to rest after a step (s).
    #[serde(deserialize_with = "number")]
    pub t_max: f64,
    /// A push at height loads the object's leading edge: the centre of friction follows
    /// the support's centre of pressure (the tipping balance's), instead of staying where
    /// a uniform pressure puts it.
    #[serde(deserialize_with = "number")]
    pub pressure_shift: bool,
    /// Quasistatic model: an object pushed against another pushes it along
    /// (`physics::chain`), instead of the state being invalid (the whole-arm paper's
    /// rule). Off by default: plans keep `object_clearance`; the perturbed worlds that
    /// judge a plan's robustness turn it on, since a real object touched by its
    /// neighbour moves.
    #[serde(deserialize_with = "number")]
    pub object_pushing: bool,
}

impl Default for PhysicsSpec {
    fn default() -> Self {
        // The projection's limits and tolerances are the projection's own defaults.
        let projection = ProjectionSettings::default();
        Self {
            contact_margin: 0.02,
            penetration_tolerance: 0.003,
            overlap_tolerance: 0.001,
            // A contact more vertical than horizontal presses the object into the table
            // more than it pushes it: not a planar push (at 0.35 rad, an upper arm pressing
            // a bowl's rim 34 degrees from vertical tipped it in rapier).
            vertical_normal_angle: std::f64::consts::FRAC_PI_4,
            max_joint_speed: projection.max_joint_speed,
            plane_tolerance: projection.height_tolerance,
            tilt_tolerance: projection.tilt_tolerance,
            tipping_margin: 0.3,
            object_clearance: 0.01,
            edge_clearance: 0.01,
            arm_clearance: 0.01,
            model: PhysicsModel::Quasistatic,
            t_max: 8.0,
            pressure_shift: true,
            object_pushing: false,
        }
    }
}

/// Limits of the executable trajectory in plan files; every field has a default.
#[derive(Debug, Deserialize, Clone, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct TrajectorySpec {
    /// Largest joint acceleration (rad/s^2, m/s^2 for prismatic joints).
    #[serde(deserialize_with = "number")]
    pub max_joint_acceleration: f64,
    /// Fastest any point of a pushed object may move (m/s): the quasistatic model holds
    /// for slow pushes (an object let go at `v` slides on by `v^2 / (2 mu_g g)`).
    #[serde(deserialize_with = "number")]
    pub max_object_speed: f64,
}

impl Default for TrajectorySpec {
    fn default() -> Self {
        Self {
            max_joint_acceleration: 2.0,
            max_object_speed: 0.1,
        }
    }
}
