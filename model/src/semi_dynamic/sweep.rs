//! A robot's links as the pushers of the top-down world: each link cut at the objects'
//! heights, moved over a step as its 3D motion moves that cut.
//!
//! Objects fall into height classes (their distinct heights). For every class a link
//! reaches down into, the link's cut between the table and the class's height becomes a
//! kinematic body that meets that class's objects only: a forearm sloping over a short can
//! pushes a tall bottle with the part of it below the bottle's top, and the can not at all.
//! The cut is taken at the step's start and moved by the planar rigid motion that best fits
//! its points' 3D motion (least squares, closed form): exact for a link that moves in the
//! plane, like the planar hand; for a tilting link the cut's change of shape within one
//! step is left out, and the 3D check of the step's end state catches any overlap.

use crate::collision::section::slab_section;
use crate::math::Pose2;
use crate::robot::chain::Link;
use nalgebra::{Isometry3, Point2, Point3, Vector2};
use rapier2d_f64::prelude::SharedShape;

use super::MAX_CLASSES;

/// One pusher over one step: a link's cut for one height class.
#[derive(Clone)]
pub struct Sweep {
    /// The link (index into the robot's links).
    pub link: usize,
    /// The height class of the objects it meets.
    pub class: usize,
    /// The cut's outline, in a frame at its centroid and yaw 0 at the step's start.
    pub shape: SharedShape,
    /// That frame's planar pose at the step's start and end (world).
    pub from: Pose2,
    /// That frame's planar pose at the step's end (world).
    pub to: Pose2,
    /// World height of the cut's lowest point (m): where the link meets an object's side
    /// lowest, the contact a tipping object keeps.
    pub lowest: f64,
}

/// Which heights the links are cut at: the objects' height classes above the table.
#[derive(Clone, Debug)]
pub struct Sweeps {
    /// Table top (m, world z).
    table_top: f64,
    /// Each class's height above the table (m), ascending.
    heights: Vec<f64>,
    /// Each object's class.
    classes: Vec<usize>,
}

impl Sweeps {
    /// Classes for objects of heights `object_heights` (m) on a table at `table_top` (m,
    /// world z): one per distinct height; with more than [`MAX_CLASSES`] distinct heights,
    /// neighbouring heights share a class cut at the tallest of them.
    pub fn new(object_heights: &[f64], table_top: f64) -> Sweeps {
        let mut distinct = object_heights.to_vec();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        let n = distinct.len();
        let class_of_rank = |rank: usize| rank * MAX_CLASSES.min(n) / n.max(1);
        let mut heights = vec![0.0_f64; MAX_CLASSES.min(n)];
        for (rank, h) in distinct.iter().enumerate() {
            let c = class_of_rank(rank);
            heights[c] = heights[c].max(*h);
        }
        let classes = object_heights
            .iter()
            .map(|h| {
                let rank = distinct.partition_point(|d| *d < h - 1e-9);
                class_of_rank(rank)
            })
            .collect();
        Sweeps {
            table_top,
            heights,
            classes,
        }
    }

    /// Each object's height class.
    pub fn object_classes(&self) -> &[usize] {
        &self.classes
    }

    /// The tallest class's height above the table (m; 0 without objects).
    pub fn tallest(&self) -> f64 {
        self.heights.last().copied().unwrap_or(0.0)
    }

    /// The sweeps of `links` moving from link poses `from` to `to` (world frame), into
    /// `out`: for every link and class whose slab (table to class height) the link's
    /// solids reach into at `from`.
    pub fn sweeps(
        &self,
        links: &[Link],
        from: &[Isometry3<f64>],
        to: &[Isometry3<f64>],
        out: &mut Vec<Sweep>,
    ) {
        out.clear();
        let mut points = Vec::new();
        for (index, (link, (x_from, x_to))) in links.iter().zip(from.iter().zip(to)).enumerate() {
            let Some(lowest) = link
                .geometry
                .iter()
                .map(|g| g.aabb(x_from).mins.z)
                .min_by(f64::total_cmp)
            else {
                continue;
            };
            let motion = x_to * x_from.inverse();
            for (class, height) in self.heights.iter().enumerate() {
                let z_max = self.table_top + height;
                if lowest >= z_max {
                    continue;
                }
                points.clear();
                for g in &link.geometry {
                    slab_section(g, x_from, self.table_top, z_max, &mut points);
                }
                if let Some(sweep) = fit(&points, &motion) {
                    out.push(Sweep {
                        link: index,
                        class,
                        ..sweep
                    });
                }
            }
        }
    }
}

/// The cut of `points` (world, at the step's start) as a body, and the planar motion that
/// best fits their 3D `motion`: centroids and the least-squares rotation between the
/// points' top-down projections before and after. `None` for a cut without area.
fn fit(points: &[Point3<f64>], motion: &Isometry3<f64>) -> Option<Sweep> {
    if points.len() < 3 {
        return None;
    }
    let before: Vec<Vector2<f64>> = points.iter().map(|p| p.xy().coords).collect();
    let after: Vec<Vector2<f64>> = points.iter().map(|p| (motion * p).xy().coords).collect();
    let n = points.len() as f64;
    let c_before = before.iter().sum::<Vector2<f64>>() / n;
    let c_after = after.iter().sum::<Vector2<f64>>() / n;
    let (mut dot, mut cross) = (0.0, 0.0);
    for (b, a) in before.iter().zip(&after) {
        let (b, a) = (b - c_before, a - c_after);
        dot += b.dot(&a);
        cross += b.perp(&a);
    }
    let outline: Vec<Point2<f64>> = before.iter().map(|b| Point2::from(b - c_before)).collect();
    Some(Sweep {
        link: 0,
        class: 0,
        shape: SharedShape::convex_hull(&outline)?,
        from: Pose2::new(c_before.x, c_before.y, 0.0),
        to: Pose2::new(c_after.x, c_after.y, cross.atan2(dot)),
        lowest: points.iter().map(|p| p.z).fold(f64::INFINITY, f64::min),
    })
}
