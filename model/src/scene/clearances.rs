//! The clearances objects keep (`physics.object_clearance`), fixed once per scene from
//! its start state.

use super::Scene;
use crate::collision::footprint;
use crate::collision::query::signed_distance;
use crate::collision::Geometry;
use nalgebra::Isometry3;

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
    /// Per object: how far it may reach past the table's edge (empty: nowhere).
    overhangs: Vec<f64>,
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
        Clearances {
            objects: objects.len(),
            between_objects,
            to_obstacles,
            overhangs: Vec::new(),
        }
    }

    /// These clearances, with each object allowed to reach past the table's edge as far as
    /// it does in `scene`'s start ([`Table::overhang`](super::Table::overhang)), and no
    /// further: a start observed in the world, where an object was pushed partly over the
    /// edge and still stands (its centre on the table), may be planned from, and the
    /// object pushed back, but no plan takes it further over. A scene file's start has
    /// none: every footprint starts wholly on the table.
    pub fn with_start_overhangs(mut self, scene: &Scene) -> Clearances {
        self.overhangs = scene
            .objects
            .iter()
            .zip(&scene.start.objects)
            .map(|(object, pose)| scene.table.overhang(&object.footprint, pose).max(0.0))
            .collect();
        self
    }

    /// How far object `i` may reach past the table's edge (m; zero but for a start
    /// observed hanging over, [`Clearances::with_start_overhangs`]).
    pub fn overhang(&self, i: usize) -> f64 {
        self.overhangs.get(i).copied().unwrap_or(0.0)
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
