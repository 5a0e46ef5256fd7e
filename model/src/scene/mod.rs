//! Scenes: the robot, the table, static obstacles, movable objects, the goal and the
//! planner parameters, loaded from YAML ([`file`](mod@file)) and validated ([`Scene::load`]).
//!
//! World frame: z up, the table top horizontal at `table.top`.

pub mod builtin;
pub mod check;
mod clearances;
pub mod file;
pub mod generate;
mod load;
mod number;
mod start;

pub use check::SceneWarning;
pub use clearances::Clearances;
pub use load::{MAX_CONTROL_STEPS, MAX_FRICTION, MAX_K, MAX_MASS, MAX_OBJECTS, MAX_STEP, MIN_STEP};
pub use start::MAX_SEPARATION;

use crate::collision::Geometry;
use crate::math::Pose2;
use crate::physics::{Footprint, LimitSurface, LoadedSupport, SupportBalance};
pub use crate::robot::wgr::Grasp;
use crate::robot::wgr::{distance_to_grasps, GRASP_TOLERANCE};
use crate::robot::Robot;
use crate::state::State;
use nalgebra::{DVector, Isometry3, Vector2};
use std::path::PathBuf;

pub use file::{
    PhysicsSpec as PhysicsParams, PlannerSpec as PlannerParams, TrajectorySpec as TrajectoryParams,
};

/// Default `goal.margin` (m): how far inside the goal disc's edge the goal object's
/// centre must end. Set from the engines' disagreement with the model: open loop, the goal
/// object ends within 60 mm of the plan's pose in 79 % of MuJoCo's trials and 93 % of
/// rapier's, 30 mm only 58 % and 85 % (BENCHMARKS.md, "The goal margin from the engines'
/// disagreement"). Small discs get at most [`DEFAULT_GOAL_MARGIN_SHARE`] of their radius.
pub const DEFAULT_GOAL_MARGIN: f64 = 0.06;

/// The largest share of the goal disc's radius the default margin takes: a disc of 5 cm
/// keeps 2 cm to end in.
pub const DEFAULT_GOAL_MARGIN_SHARE: f64 = 0.6;

/// The default `goal.margin` (m) of a goal disc of `radius` (m).
pub fn default_goal_margin(radius: f64) -> f64 {
    DEFAULT_GOAL_MARGIN.min(DEFAULT_GOAL_MARGIN_SHARE * radius)
}

/// A validated scene: the robot, the table, obstacles, movable objects, the goal, the
/// parameters and the start state, ready to plan in. Loaded from a file ([`Scene::load`])
/// or YAML text ([`Scene::from_yaml`]); every field checked, the start state valid.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The scene's name (`name:`, else the file stem).
    pub name: String,
    /// The file the scene came from (or a label for scenes built from text).
    pub source: PathBuf,
    /// The robot that pushes.
    pub robot: Robot,
    /// The support surface.
    pub table: Table,
    /// Static obstacles.
    pub obstacles: Vec<Obstacle>,
    /// Movable objects, in the state's object order.
    pub objects: Vec<MovableObject>,
    /// What the plan must achieve.
    pub goal: Goal,
    /// Planner parameters.
    pub planner: PlannerParams,
    /// Physics parameters.
    pub physics: PhysicsParams,
    /// How plans are timed into trajectories.
    pub trajectory: TrajectoryParams,
    /// The start state (robot start projected onto its pushing plane).
    pub start: State,
    /// The distance each object keeps from the others and the obstacles (from `start`).
    pub clearances: Clearances,
    /// Link–table and link–obstacle pairs that may touch (allowed link–link pairs are
    /// left out of the robot's self-collision pairs).
    pub allowed: AllowedCollisions,
}

/// The scene's `allowed_collisions` between the robot and the static world.
#[derive(Clone, Debug, Default)]
pub struct AllowedCollisions {
    /// Links (indices into the chain's links) that may touch the table.
    pub table: Vec<usize>,
    /// (link, obstacle) index pairs that may touch.
    pub obstacles: Vec<(usize, usize)>,
}

impl AllowedCollisions {
    /// May `link` touch the table?
    pub fn link_table(&self, link: usize) -> bool {
        self.table.contains(&link)
    }

    /// May `link` touch `obstacle`?
    pub fn link_obstacle(&self, link: usize, obstacle: usize) -> bool {
        self.obstacles.contains(&(link, obstacle))
    }
}

/// Is the point `p` (m) within the extent `x` x `y` (m)?
pub fn within_extent(p: Vector2<f64>, x: (f64, f64), y: (f64, f64)) -> bool {
    p.x >= x.0 && p.x <= x.1 && p.y >= y.0 && p.y <= y.1
}

/// The support surface: a slab whose top is at `top`, spanning `x` x `y`.
#[derive(Clone, Debug)]
pub struct Table {
    /// World height of the top surface (m).
    pub top: f64,
    /// Extent along x and y (m).
    pub x: (f64, f64),
    /// Extent along y (m).
    pub y: (f64, f64),
    /// The slab, in world coordinates (its body pose is the identity).
    pub geometry: Geometry,
}

impl Table {
    /// Is the world point (x, y) over the table?
    pub fn contains(&self, p: Vector2<f64>) -> bool {
        within_extent(p, self.x, self.y)
    }

    /// Does the table carry the whole `footprint` (object frame) at `pose`? An object
    /// whose centre is on the table but whose footprint hangs over the edge rests on a
    /// support polygon the planar model does not know, and tips off at the slightest
    /// push: the model keeps every footprint wholly on the table (but see
    /// [`Clearances::with_start_overhangs`] for a start observed in the world).
    pub fn holds(&self, footprint: &Footprint, pose: &Pose2) -> bool {
        self.overhang(footprint, pose) <= 0.0
    }

    /// How far `footprint` (object frame) at `pose` reaches past the table's edges (m):
    /// the largest distance along x or y of any of its points beyond the table's extent;
    /// zero or less when the table carries it whole (then minus its least distance from
    /// an edge).
    pub fn overhang(&self, footprint: &Footprint, pose: &Pose2) -> f64 {
        let beyond = |p: Vector2<f64>, radius: f64| {
            (self.x.0 - (p.x - radius))
                .max(p.x + radius - self.x.1)
                .max(self.y.0 - (p.y - radius))
                .max(p.y + radius - self.y.1)
        };
        match footprint {
            Footprint::Circle { radius } => beyond(pose.translation(), *radius),
            Footprint::Polygon { vertices } => vertices
                .iter()
                .map(|v| beyond(pose.translation() + pose.rotation() * v, 0.0))
                .fold(f64::NEG_INFINITY, f64::max),
        }
    }
}

/// A static obstacle.
#[derive(Clone, Debug)]
pub struct Obstacle {
    /// Its name.
    pub name: String,
    /// World pose of the obstacle's frame.
    pub pose: Isometry3<f64>,
    /// Its solid, in the obstacle's frame.
    pub geometry: Geometry,
}

/// A rigid prism resting on the table.
#[derive(Clone, Debug)]
pub struct MovableObject {
    /// Its name.
    pub name: String,
    /// Footprint in the object frame, centred on the centre of friction (m).
    pub footprint: Footprint,
    /// Height of the prism (m).
    pub height: f64,
    /// The solid in the object frame (the frame sits on the table top).
    pub geometry: Geometry,
    /// Radius of the footprint's bounding circle about the origin (m).
    pub bounding_radius: f64,
    /// Mass (kg).
    pub mass: f64,
    /// Support friction and contact friction coefficients.
    pub mu_g: f64,
    /// Friction coefficient against the robot.
    pub mu_c: f64,
    /// The limit surface under uniform support pressure (object frame).
    pub limit_surface: LimitSurface,
    /// How `c` changes as a push at height loads the support toward an edge.
    pub support: LoadedSupport,
    /// Ways to grasp it (Workspace Goal Regions), in the object frame.
    pub grasps: Vec<Grasp>,
}

impl MovableObject {
    /// The object frame's world pose for a planar pose (its base on the table top).
    pub fn isometry(&self, pose: &Pose2, table_top: f64) -> Isometry3<f64> {
        pose.to_isometry(table_top)
    }

    /// The limit surface (object frame) under the support pressure `balance` gives: the
    /// centre of friction (the pressure-weighted centroid) moves with the centre of
    /// pressure, `c` with the pressure's spread (`physics.pressure_shift`).
    pub fn loaded_surface(&self, balance: &SupportBalance) -> LimitSurface {
        let shift = balance.p_OP - self.footprint.centroid();
        LimitSurface {
            centre: self.limit_surface.centre + shift,
            c: self.limit_surface.c * self.support.c_ratio(shift),
            ..self.limit_surface
        }
    }
}

/// What a plan must achieve.
#[derive(Clone, Debug, PartialEq)]
pub enum Goal {
    /// The goal object's centre inside a disc on the table, at least `margin` inside its
    /// edge (so that small execution errors still end inside the disc).
    ObjectInDisc {
        /// Index of the goal object.
        object: usize,
        /// Centre of the goal disc (m, world frame).
        center: Vector2<f64>,
        /// Radius of the disc (m).
        radius: f64,
        /// How far inside the edge the centre must be (m), in [0, radius).
        margin: f64,
    },
    /// The robot within `tolerance` (Euclidean, joint space) of a configuration.
    Configuration {
        /// The configuration (rad or m).
        q: DVector<f64>,
        /// How close the robot must come (Euclidean, joint space).
        tolerance: f64,
    },
    /// The tool inside one of an object's grasp regions (its `grasps`, where the object is
    /// in the state), within [`GRASP_TOLERANCE`] of the lecture's distance;
    /// clutter may be pushed aside on the way, and the object itself if `object_may_move`.
    Grasp {
        /// Index of the object to grasp.
        object: usize,
        /// Its grasp regions, in the object frame.
        grasps: Vec<Grasp>,
        /// May the pushes move it?
        object_may_move: bool,
        /// Table top (m, world z): where the object frames stand.
        table_top: f64,
        /// The robot whose tool the regions hold (the scene's).
        robot: SharedRobot,
    },
}

/// The scene's robot shared with a goal measured at its tool; two are equal when they are
/// the same robot.
#[derive(Clone, Debug)]
pub struct SharedRobot(pub std::sync::Arc<crate::robot::Robot>);

impl PartialEq for SharedRobot {
    fn eq(&self, other: &Self) -> bool {
        std::sync::Arc::ptr_eq(&self.0, &other.0)
    }
}

impl Goal {
    /// Does the state satisfy the goal?
    pub fn is_satisfied(&self, state: &State) -> bool {
        self.distance(state) <= 0.0
    }

    /// How far the state is from the goal region (m for object goals, rad for
    /// configuration goals); zero or negative inside. For an object goal the region is
    /// the disc shrunk by the margin.
    pub fn distance(&self, state: &State) -> f64 {
        match self {
            Goal::ObjectInDisc {
                object,
                center,
                radius,
                margin,
            } => (state.objects[*object].translation() - center).norm() - (radius - margin),
            Goal::Configuration { q, tolerance } => (&state.q - q).norm() - tolerance,
            Goal::Grasp {
                object,
                grasps,
                table_top,
                robot,
                ..
            } => {
                distance_to_grasps(
                    &robot.0,
                    *table_top,
                    grasps,
                    &state.objects[*object],
                    &state.q,
                ) - GRASP_TOLERANCE
            }
        }
    }

    /// The object that must stay where it starts: a grasp goal's, unless it may move.
    pub fn pinned_object(&self) -> Option<usize> {
        match self {
            Goal::Grasp {
                object,
                object_may_move: false,
                ..
            } => Some(*object),
            _ => None,
        }
    }

    /// The object the goal is about (the goal object, or the one to grasp).
    pub fn object(&self) -> Option<usize> {
        match self {
            Goal::ObjectInDisc { object, .. } | Goal::Grasp { object, .. } => Some(*object),
            Goal::Configuration { .. } => None,
        }
    }
}

impl Goal {
    /// How far the state is from the task's own region (m or rad): for an object goal the
    /// whole disc, without the planning margin; zero or negative inside.
    pub fn task_distance(&self, state: &State) -> f64 {
        match self {
            Goal::ObjectInDisc { margin, .. } => self.distance(state) - margin,
            Goal::Configuration { .. } | Goal::Grasp { .. } => self.distance(state),
        }
    }
}

impl Scene {
    /// How far the tool point stands from the centre of `object` when the hand stands just
    /// behind it to push (m): the object's bounding radius and the end effector's reach
    /// beyond the tool point ([`crate::robot::Robot::tool_reach`]), so that no part of the
    /// hand overlaps the object from any side. The push headings stand the hand there; the
    /// scene check asks whether the arm reaches it.
    pub fn push_standoff(&self, object: usize) -> f64 {
        self.objects[object].bounding_radius + self.robot.tool_reach()
    }

    /// The scene of the Static RRT baseline: every movable object except the goal object
    /// becomes a static obstacle where it starts.
    pub fn with_static_clutter(&self) -> Scene {
        let keep = self.goal.object();
        let mut scene = self.clone();
        scene.name = format!("{} (static clutter)", self.name);
        scene.objects.clear();
        scene.start.objects.clear();
        for (i, (object, pose)) in self.objects.iter().zip(&self.start.objects).enumerate() {
            if Some(i) == keep {
                scene.objects.push(object.clone());
                scene.start.objects.push(*pose);
            } else {
                scene.obstacles.push(Obstacle {
                    name: object.name.clone(),
                    pose: pose.to_isometry(self.table.top),
                    geometry: object.geometry.clone(),
                });
            }
        }
        if let Goal::ObjectInDisc { object, .. } | Goal::Grasp { object, .. } = &mut scene.goal {
            *object = 0;
        }
        scene.clearances = Clearances::at_start(&scene);
        scene
    }
}
