//! The clearances objects keep (`physics.object_clearance`, `physics.edge_clearance`),
//! fixed once per scene from its start state, and the arm clearance of each object
//! (`physics.arm_clearance`).

use super::{Scene, Table};
use crate::collision::footprint;
use crate::collision::query::signed_distance;
use crate::collision::Geometry;
use crate::math::Pose2;
use crate::physics::Footprint;
use nalgebra::Isometry3;

/// How near the table's edge an observed object stands (m) for a re-plan to give it the
/// room its support allows over the edge ([`Clearances::with_start_overhangs`]): what an
/// observation may be off, so that an object seen just short of the edge counts as at it.
const AT_EDGE: f64 = 0.002;

/// The least distance each object keeps from every other object and obstacle (m):
/// `physics.object_clearance`, or the pair's distance in the start state when that is
/// smaller (objects that start close together may stay so, but not come closer).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Clearances {
    objects: usize,
    /// Row-major, objects x objects.
    between_objects: Vec<f64>,
    /// Row-major, objects x obstacles.
    to_obstacles: Vec<f64>,
    /// Per object: how far it may reach past the table's edge (m; negative: how far
    /// inside the edge it must stay, `physics.edge_clearance`; empty, in
    /// `Clearances::default()`: 0 for every object).
    overhangs: Vec<f64>,
    /// Per object, from a start observed in the world: its footprint shrunk by
    /// `physics.tipping_margin` about its centroid, which must stay on the table where
    /// the object reaches further past the edge than `overhangs` allow; None for the
    /// goal's object and for objects observed away from the edge (empty: a scene file's
    /// start).
    edge_support: Vec<Option<Footprint>>,
    /// Per object: the arm clearance it is given (m), where it is not
    /// `physics.arm_clearance` (empty: every object has that).
    arm: Vec<f64>,
}

impl Clearances {
    /// The clearances of `scene` from its start state (between objects none, when they
    /// push one another).
    pub fn at_start(scene: &Scene) -> Clearances {
        let clearance = scene.physics.object_clearance;
        let top = scene.table.top;
        let poses: Vec<Isometry3<f64>> = scene
            .start
            .objects
            .iter()
            .map(|p| p.to_isometry(top))
            .collect();
        let gap = |a: &Geometry, pa: &Isometry3<f64>, b: &Geometry, pb: &Isometry3<f64>| {
            signed_distance(a, pa, b, pb, clearance).map_or(clearance, |d| d.min(clearance))
        };
        let objects = &scene.objects;
        // Objects that push one another touch: only overlapping beyond the tolerance is
        // invalid between them.
        let touching = -scene.physics.overlap_tolerance;
        let between_objects = (0..objects.len())
            .flat_map(|i| (0..objects.len()).map(move |j| (i, j)))
            .map(|(i, j)| {
                if i == j {
                    0.0
                } else if scene.physics.object_pushing {
                    touching
                } else {
                    footprint::gap(
                        &objects[i].footprint,
                        &scene.start.objects[i],
                        &objects[j].footprint,
                        &scene.start.objects[j],
                    )
                    .min(clearance)
                }
            })
            .collect();
        let to_obstacles = (0..objects.len())
            .flat_map(|i| scene.obstacles.iter().map(move |o| (i, o)))
            .map(|(i, o)| gap(&objects[i].geometry, &poses[i], &o.geometry, &o.pose))
            .collect();
        // Each object keeps `physics.edge_clearance` from the table's edges, or its
        // distance in the start state where that is smaller.
        let edge = scene.physics.edge_clearance;
        let overhangs = (objects.iter().zip(&scene.start.objects))
            .map(|(o, pose)| {
                let from_edge = (-scene.table.overhang(&o.footprint, pose)).max(0.0);
                -edge.min(from_edge)
            })
            .collect();
        Clearances {
            objects: objects.len(),
            between_objects,
            to_obstacles,
            overhangs,
            edge_support: Vec::new(),
            arm: Vec::new(),
        }
    }

    /// These clearances with object `i` given arm clearance `arm[i]` (m) instead of
    /// `physics.arm_clearance` (the closed loop judges the rest with less of it for objects
    /// the world has not moved: `pushplan::planner::closed_loop`).
    pub fn with_arm_clearances(mut self, arm: Vec<f64>) -> Clearances {
        debug_assert_eq!(arm.len(), self.objects);
        self.arm = arm;
        self
    }

    /// The arm clearance of object `i` (m): `physics_arm_clearance` unless these
    /// clearances give it another ([`Clearances::with_arm_clearances`]).
    pub fn arm(&self, i: usize, physics_arm_clearance: f64) -> f64 {
        self.arm.get(i).copied().unwrap_or(physics_arm_clearance)
    }

    /// These clearances from a start observed in the world, where objects pushed to the
    /// table's edge may hang a little over it and still stand. Each object may reach past
    /// the edge as far as it does in `scene`'s start ([`Table::overhang`]). One the world
    /// brought to the edge (within 2 mm of it, or over it) may also go as far over as the
    /// footprint the tipping check keeps the support pressure in (shrunk by
    /// `physics.tipping_margin` about its centroid, [`Footprint::scaled_about_centroid`])
    /// stays on the table: that shrunk footprint then lies within the table's true
    /// support (the footprint cut by the edge, both convex), so a push the tipping check
    /// lets stand does not tip the object over the edge. A re-plan may so push such an object along
    /// the edge, or turn it there (dense 16 in MuJoCo: a box 4 mm over the far edge
    /// blocked every search from where a trial stood; docs/notes/plans-in-the-world.md,
    /// "Objects at the table's edge").
    ///
    /// Not the goal's object: it must end where the plan says, and the planar model
    /// spreads its support friction over the whole footprint, part of which the table no
    /// longer carries (dense 19: legs that took the goal box along the edge did not carry
    /// it in MuJoCo). Not objects away from the edge either: given the room, re-plans
    /// pushed neighbours over to the new limit, where they blocked the next search.
    ///
    /// [`Table::overhang`]: super::Table::overhang
    pub fn with_start_overhangs(mut self, scene: &Scene) -> Clearances {
        let goal_object = scene.goal.object();
        let support = 1.0 - scene.physics.tipping_margin;
        let kept = std::mem::take(&mut self.overhangs);
        (self.overhangs, self.edge_support) = scene
            .objects
            .iter()
            .zip(&scene.start.objects)
            .enumerate()
            .map(|(i, (object, pose))| {
                let overhang = scene.table.overhang(&object.footprint, pose);
                let room = goal_object != Some(i) && overhang > -AT_EDGE;
                (
                    overhang.max(kept.get(i).copied().unwrap_or(0.0)),
                    room.then(|| object.footprint.scaled_about_centroid(support)),
                )
            })
            .unzip();
        self
    }

    /// Does `table` carry object `i` (its `footprint` at `pose`) as these clearances
    /// allow? Wholly, but for a start observed in the world
    /// ([`Clearances::with_start_overhangs`]).
    pub fn on_table(&self, table: &Table, i: usize, footprint: &Footprint, pose: &Pose2) -> bool {
        let allowed = self.overhangs.get(i).copied().unwrap_or(0.0);
        table.overhang(footprint, pose) <= allowed
            || self
                .edge_support
                .get(i)
                .and_then(Option::as_ref)
                .is_some_and(|support| table.holds(support, pose))
    }

    /// Between objects `i` and `j` (m).
    pub fn between_objects(&self, i: usize, j: usize) -> f64 {
        self.between_objects[i * self.objects + j]
    }

    /// Between object `i` and obstacle `k` (m).
    pub fn to_obstacle(&self, i: usize, k: usize) -> f64 {
        let obstacles = self.to_obstacles.len() / self.objects.max(1);
        self.to_obstacles[i * obstacles + k]
    }
}
