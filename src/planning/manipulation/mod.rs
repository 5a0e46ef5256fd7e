//! Pick and place of one object with the arm's hand, by the lecture's PRM-based
//! manipulation planning (Nielsen and Kavraki, IROS 2000): a manipulation graph whose
//! nodes are `(q_obj, g, q_rob)` (a placement of the object, a grasp, a configuration
//! holding that grasp there), with transfer edges where the grasp is shared (the arm
//! carries the object) and transit edges where the placement is shared (the object rests,
//! the arm changes grasp), searched by a two-level Fuzzy PRM (`graph.rs`, `fuzzy.rs`).
//!
//! Frames: `X_0O` the object on the table (its planar pose, base on the table top);
//! a grasp is `X_OE`, the tool in the object frame (a fixed sample of one of the object's
//! grasp regions); while carried the object is at `X_0E X_OE^-1`.

pub mod fuzzy;
pub mod graph;

pub use graph::{EdgeKind, ManipulationGraph, Settings};

use crate::collision::query::overlaps_beyond;
use crate::math::Pose2;
use crate::planning::transit::{transit_points, transit_segments};
use crate::random::SplitMix64;
use crate::robot::{IkSettings, Robot};
use crate::scene::Scene;
use crate::state::State;
use crate::validity::{check_arm, check_objects, check_state};
use nalgebra::{DVector, Isometry3};

/// Random seeds inverse kinematics tries for a node after the start configuration.
pub const IK_SEEDS: usize = 20;

/// One object to move from its start placement to another, with the grasps to use.
#[derive(Clone, Debug)]
pub struct PickAndPlace {
    /// The scene.
    pub scene: Scene,
    /// Where the arm starts and every object rests (the scene's start, or a state part
    /// way through a plan).
    pub start: State,
    /// The object to move (scene index).
    pub object: usize,
    /// Placements of the object: its start first, the goal second, then any others
    /// (places to put it down and grasp it anew).
    pub placements: Vec<Pose2>,
    /// Grasps `X_OE`: the tool in the object frame.
    pub grasps: Vec<Isometry3<f64>>,
}

/// How the arm moves along a segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// The object rests at a placement; the arm moves (to or between grasps).
    Transit {
        /// The placement the object rests at.
        placement: usize,
    },
    /// The arm carries the object in a grasp from one placement to another.
    Transfer {
        /// The grasp held (index).
        grasp: usize,
        /// The placement it is picked up at.
        from: usize,
        /// The placement it is put down at.
        to: usize,
    },
}

/// Part of a pick-and-place path: joint waypoints joined by straight lines.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// How the arm moves.
    pub motion: Motion,
    /// Joint waypoints, the first where the segment starts.
    pub waypoints: Vec<DVector<f64>>,
}

impl PickAndPlace {
    /// Moving `object` of `scene` from where it rests in `start` to `goal`, the arm
    /// starting at `start`'s configuration, with grasps sampled from the object's grasp
    /// regions: `grasps_per_region` displacements of each, drawn from `seed`. An error if
    /// the object has no grasps or the goal is not a valid placement.
    pub fn new(
        scene: &Scene,
        start: &State,
        object: usize,
        goal: Pose2,
        grasps_per_region: usize,
        seed: u64,
    ) -> Result<PickAndPlace, String> {
        let o = &scene.objects[object];
        if o.grasps.is_empty() {
            return Err(format!("object '{}' has no grasps", o.name));
        }
        let mut placed = start.objects.clone();
        placed[object] = goal;
        check_objects(scene, &placed, |i| i == object)
            .map_err(|why| format!("the goal placement of '{}' is not valid: {why}", o.name))?;
        let mut rng = SplitMix64::new(seed);
        let grasps = o
            .grasps
            .iter()
            .flat_map(|g| {
                let draws: Vec<_> = (0..grasps_per_region)
                    .map(|_| g.0.sample_displacement(&mut rng))
                    .collect();
                draws.into_iter().map(move |d| g.0.end_effector_pose(&d))
            })
            .collect();
        Ok(PickAndPlace {
            scene: scene.clone(),
            start: start.clone(),
            object,
            placements: vec![start.objects[object], goal],
            grasps,
        })
    }

    /// The objects with this one at `placement`.
    pub fn objects_at(&self, placement: usize) -> Vec<Pose2> {
        let mut objects = self.start.objects.clone();
        objects[self.object] = self.placements[placement];
        objects
    }

    /// The object's world pose at a placement.
    fn x_0o(&self, placement: usize) -> Isometry3<f64> {
        self.placements[placement].to_isometry(self.scene.table.top)
    }

    /// A configuration holding `grasp` on the object at `placement`, valid with the
    /// object resting there and with it held: inverse kinematics from the start
    /// configuration, then from up to [`IK_SEEDS`] random ones (drawn from the placement
    /// and grasp indices, so the same problem gives the same nodes); `None` if none is.
    pub fn grasp_configuration(&self, placement: usize, grasp: usize) -> Option<DVector<f64>> {
        let target = self.x_0o(placement) * self.grasps[grasp];
        let robot = &self.scene.robot;
        let mut rng = SplitMix64::new(((placement as u64) << 32) ^ grasp as u64);
        std::iter::once(self.start.q.clone())
            .chain((0..IK_SEEDS).map(|_| robot.chain.random_configuration(&mut rng)))
            .filter_map(|seed| robot.reach_tool_pose(&target, &seed, &IkSettings::default()))
            .find(|q| self.transit_valid(placement, q) && self.transfer_valid(grasp, q))
    }

    /// Is `q` valid with the object resting at `placement` (every rule of a state)?
    pub fn transit_valid(&self, placement: usize, q: &DVector<f64>) -> bool {
        check_state(
            &self.scene,
            &State {
                q: q.clone(),
                objects: self.objects_at(placement),
            },
        )
        .is_ok()
    }

    /// Is `q` valid with the object held in `grasp` ([`holding_valid`])?
    pub fn transfer_valid(&self, grasp: usize, q: &DVector<f64>) -> bool {
        holding_valid(
            &self.scene,
            &self.start.objects,
            self.object,
            &self.grasps[grasp],
            q,
        )
    }

    /// Is `q` valid in the motion `motion`?
    pub fn valid(&self, motion: Motion, q: &DVector<f64>) -> bool {
        match motion {
            Motion::Transit { placement } => self.transit_valid(placement, q),
            Motion::Transfer { grasp, .. } => self.transfer_valid(grasp, q),
        }
    }

    /// Checks a pick-and-place path independently of the planner: it starts at the
    /// start configuration and ends with the object at the goal; segments join; every
    /// straight line is valid at the Transit resolution in its motion; a transfer starts
    /// and ends holding its grasp (within 1 mm and 1 mrad) at its placements; a transit's
    /// object rests where the previous segment left it.
    pub fn check(&self, segments: &[Segment]) -> Result<(), String> {
        let mut at_q = self.start.q.clone();
        let mut placement = 0;
        for (i, s) in segments.iter().enumerate() {
            let first = s.waypoints.first().ok_or(format!("segment {i} is empty"))?;
            if (first - &at_q).amax() > 1e-9 {
                return Err(format!(
                    "segment {i} does not start where segment {} ends",
                    i.max(1) - 1
                ));
            }
            match s.motion {
                Motion::Transit { placement: p } if p != placement => {
                    return Err(format!(
                        "segment {i}: the object rests at placement {placement}, not {p}"
                    ))
                }
                Motion::Transfer { grasp, from, to } => {
                    if from != placement {
                        return Err(format!(
                            "segment {i}: the object is at placement {placement}, not {from}"
                        ));
                    }
                    for (end, p) in [(first, from), (s.waypoints.last().unwrap(), to)] {
                        if !self.holds(grasp, p, end) {
                            return Err(format!("segment {i}: the hand does not hold grasp {grasp} at placement {p}"));
                        }
                    }
                    placement = to;
                }
                _ => {}
            }
            for (k, pair) in s.waypoints.windows(2).enumerate() {
                let n = transit_segments(&pair[0], &pair[1]);
                let line =
                    std::iter::once(pair[0].clone()).chain(transit_points(&pair[0], &pair[1]));
                for (step, q) in line.enumerate() {
                    if !self.valid(s.motion, &q) {
                        return Err(format!(
                            "segment {i}, line {k}: invalid at {:.0} % of it ({:?})",
                            100.0 * step as f64 / n as f64,
                            s.motion
                        ));
                    }
                }
            }
            at_q = s.waypoints.last().unwrap().clone();
        }
        if placement != 1 {
            return Err("the object does not end at the goal placement".into());
        }
        Ok(())
    }

    /// The states along a path at the Transit resolution, for pictures: the object where
    /// it rests, or while carried where the hand holds it (seen from above: the planar
    /// pose of its 3D pose). Also each segment's first state index.
    pub fn states(&self, segments: &[Segment]) -> (Vec<State>, Vec<usize>) {
        let robot = &self.scene.robot;
        let mut placement = 0;
        let mut states: Vec<State> = Vec::new();
        let mut starts = Vec::new();
        for s in segments {
            starts.push(states.len().saturating_sub(1));
            let state_at = |q: DVector<f64>| {
                let mut objects = self.objects_at(placement);
                if let Motion::Transfer { grasp, .. } = s.motion {
                    objects[self.object] = carried_pose(robot, &q, &self.grasps[grasp]);
                }
                State { q, objects }
            };
            if states.is_empty() {
                states.push(state_at(s.waypoints[0].clone()));
            }
            for pair in s.waypoints.windows(2) {
                states.extend(transit_points(&pair[0], &pair[1]).map(state_at));
            }
            if let Motion::Transfer { to, .. } = s.motion {
                placement = to;
            }
        }
        starts.push(states.len() - 1);
        (states, starts)
    }

    /// Does `q` hold `grasp` on the object at `placement` (tool within 1 mm, 1 mrad)?
    fn holds(&self, grasp: usize, placement: usize, q: &DVector<f64>) -> bool {
        let robot = &self.scene.robot;
        let tool = robot.tool_pose(&robot.link_poses(q));
        let error = (self.x_0o(placement) * self.grasps[grasp]).inverse() * tool;
        error.translation.vector.norm() <= 1e-3 && error.rotation.angle() <= 1e-3
    }
}

/// Is `q` valid with `object` held in the grasp `x_oe` (the tool in the object frame) and
/// the other objects resting at `objects`: the arm within its limits and clear of itself,
/// the table, obstacles and the other objects; the carried object clear of the table,
/// obstacles, the other objects and every link but the hand holding it.
pub fn holding_valid(
    scene: &Scene,
    objects: &[Pose2],
    object: usize,
    x_oe: &Isometry3<f64>,
    q: &DVector<f64>,
) -> bool {
    let robot = &scene.robot;
    let Ok((poses, _)) = check_arm(scene, q) else {
        return false;
    };
    let top = scene.table.top;
    let (arm_depth, depth) = (
        scene.physics.penetration_tolerance,
        scene.physics.overlap_tolerance,
    );
    let carried = &scene.objects[object];
    let x_0o = robot.tool_pose(&poses) * x_oe.inverse();
    let identity = Isometry3::identity();
    if overlaps_beyond(
        &carried.geometry,
        &x_0o,
        &scene.table.geometry,
        &identity,
        depth,
    ) {
        return false;
    }
    if scene
        .obstacles
        .iter()
        .any(|o| overlaps_beyond(&carried.geometry, &x_0o, &o.geometry, &o.pose, depth))
    {
        return false;
    }
    let links = &robot.chain.links;
    for (j, (other, pose)) in scene.objects.iter().zip(objects).enumerate() {
        if j == object {
            continue;
        }
        let x_0j = pose.to_isometry(top);
        if overlaps_beyond(&carried.geometry, &x_0o, &other.geometry, &x_0j, depth) {
            return false;
        }
        let hits = links.iter().zip(&poses).any(|(link, x)| {
            link.geometry
                .iter()
                .any(|g| overlaps_beyond(g, x, &other.geometry, &x_0j, arm_depth))
        });
        if hits {
            return false;
        }
    }
    links
        .iter()
        .zip(&poses)
        .enumerate()
        .filter(|(l, _)| *l != robot.ee_link)
        .all(|(_, (link, x))| {
            !link
                .geometry
                .iter()
                .any(|g| overlaps_beyond(g, x, &carried.geometry, &x_0o, arm_depth))
        })
}

/// The planar pose (seen from above) of an object held in grasp `x_oe` (the tool in the
/// object frame) by configuration `q` of `robot`.
pub fn carried_pose(robot: &Robot, q: &DVector<f64>, x_oe: &Isometry3<f64>) -> Pose2 {
    Pose2::from_isometry(&(robot.tool_pose(&robot.link_poses(q)) * x_oe.inverse()))
}
