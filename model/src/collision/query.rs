//! Pairwise queries between placed shapes.

use super::geometry::Geometry;
use nalgebra::{Isometry3, Point3, Unit, Vector3};
use parry3d_f64::query::{
    self, ContactManifold, DefaultQueryDispatcher, PersistentQueryDispatcher,
};
use parry3d_f64::shape::SupportMap;

/// Do the shapes overlap (touching counts)?
pub fn intersects(
    a: &Geometry,
    pose_a: &Isometry3<f64>,
    b: &Geometry,
    pose_b: &Isometry3<f64>,
) -> bool {
    query::intersection_test(
        &a.world_pose(pose_a),
        a.shape.as_ref(),
        &b.world_pose(pose_b),
        b.shape.as_ref(),
    )
    .unwrap_or(true)
}

/// Signed distance between the shapes (m): positive when apart, minus the penetration
/// depth when overlapping. `None` when they are farther apart than `max_distance`.
///
/// parry's GJK/EPA answer is refined to full precision: for convex shapes the signed
/// distance is the largest gap `-h_A(n) - h_B(-n)` over unit directions `n` (`h` the
/// support functions), and a local ascent from parry's normal finds it. (GJK alone stops
/// up to 1e-5 m short on curved shapes.)
pub fn signed_distance(
    a: &Geometry,
    pose_a: &Isometry3<f64>,
    b: &Geometry,
    pose_b: &Isometry3<f64>,
    max_distance: f64,
) -> Option<f64> {
    let (world_a, world_b) = (a.world_pose(pose_a), b.world_pose(pose_b));
    let c = query::contact(
        &world_a,
        a.shape.as_ref(),
        &world_b,
        b.shape.as_ref(),
        max_distance,
    )
    .ok()??;
    match (a.shape.as_support_map(), b.shape.as_support_map()) {
        (Some(sa), Some(sb)) => Some(refine_gap(
            sa,
            &world_a,
            sb,
            &world_b,
            c.normal1.into_inner(),
            c.dist,
        )),
        _ => Some(c.dist),
    }
}

/// Do the shapes overlap by more than `depth` (m)? Decided exactly: parry's raw answer is
/// taken when it says apart, or overlapping by clearly more than `depth` (its error is
/// below 1e-3 m there); otherwise the refined signed distance decides. A raw "touching" is
/// never taken: for prisms with coplanar faces (two cylinders of one height side by side)
/// parry's EPA answers a depth of about zero where they overlap by centimetres.
pub fn overlaps_beyond(
    a: &Geometry,
    pose_a: &Isometry3<f64>,
    b: &Geometry,
    pose_b: &Isometry3<f64>,
    depth: f64,
) -> bool {
    let (world_a, world_b) = (a.world_pose(pose_a), b.world_pose(pose_b));
    match query::contact(&world_a, a.shape.as_ref(), &world_b, b.shape.as_ref(), 0.0) {
        Ok(None) => false,
        Ok(Some(c)) if c.dist < -depth - RAW_ERROR => true,
        _ => signed_distance(a, pose_a, b, pose_b, 0.0).is_some_and(|d| d < -depth),
    }
}

/// The error of parry's raw signed distance where it is right (m); see [`overlaps_beyond`]
/// for where it is not.
const RAW_ERROR: f64 = 1e-3;

/// Maximises the support gap over unit directions by pattern search from `normal`.
fn refine_gap(
    a: &dyn SupportMap,
    pose_a: &Isometry3<f64>,
    b: &dyn SupportMap,
    pose_b: &Isometry3<f64>,
    normal: Vector3<f64>,
    fallback: f64,
) -> f64 {
    let gap = |n: &Vector3<f64>| {
        let ha = n.dot(&a.support_point(pose_a, n).coords);
        let hb = (-n).dot(&b.support_point(pose_b, &-n).coords);
        -ha - hb
    };
    let Some(mut best) = Unit::try_new(normal, 1e-12).map(Unit::into_inner) else {
        return fallback;
    };
    let mut best_gap = gap(&best);
    if fallback < RAW_ERROR {
        // Overlapping, or touching by parry's word (which may hide an overlap of
        // centimetres): the gap is not concave and EPA's normal may sit in the wrong
        // basin; start from the best of it and 256 evenly spread directions.
        let count = 256;
        for i in 0..count {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / count as f64;
            let r = (1.0 - z * z).sqrt();
            let phi = 2.399_963_229_728_653 * i as f64;
            let n = Vector3::new(r * phi.cos(), r * phi.sin(), z);
            let g = gap(&n);
            if g > best_gap {
                (best, best_gap) = (n, g);
            }
        }
    }
    // A wide first step: overlapping shapes make the gap non-concave, and EPA's normal
    // can start in a neighbouring basin.
    let mut step = 0.3;
    let mut turn = 0.0f64;
    while step > 1e-11 {
        let helper = if best.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let u = best.cross(&helper).normalize();
        let v = best.cross(&u);
        // Twelve probes, turned by the golden angle each round: the gap has ridges
        // (kinks of polytope supports) that a fixed probe pattern can stall on.
        turn += 2.399_963_229_728_653;
        let mut improved = false;
        for k in 0..12 {
            let angle = turn + k as f64 * std::f64::consts::PI / 6.0;
            let n = (best + (u * angle.cos() + v * angle.sin()) * step).normalize();
            let g = gap(&n);
            if g > best_gap {
                (best, best_gap, improved) = (n, g, true);
            }
        }
        if !improved {
            step *= 0.5;
        }
    }
    best_gap
}

/// One point of a contact manifold between shapes `a` and `b`, world frame.
#[derive(Clone, Copy, Debug)]
pub struct ContactPoint {
    /// Point on the surface of `a` (m).
    pub point_a: Point3<f64>,
    /// Point on the surface of `b` (m).
    pub point_b: Point3<f64>,
    /// Unit normal pointing out of `a`, towards `b`.
    pub normal_a: Unit<Vector3<f64>>,
    /// Signed distance (m): negative when penetrating.
    pub distance: f64,
}

/// All contact points between `a` and `b` closer than `prediction` (m), appended to `out`.
///
/// Face-to-face contacts come back as several points (the corners of the touching patch),
/// which is what lets a flat pusher push a box straight. A fresh manifold is used every
/// call so the answer depends on the poses only (no history), keeping propagation
/// deterministic.
pub fn contact_points(
    a: &Geometry,
    pose_a: &Isometry3<f64>,
    b: &Geometry,
    pose_b: &Isometry3<f64>,
    prediction: f64,
    out: &mut Vec<ContactPoint>,
) {
    let world_a = a.world_pose(pose_a);
    let world_b = b.world_pose(pose_b);
    let pos12 = world_a.inv_mul(&world_b);
    let mut manifold: ContactManifold<(), ()> = ContactManifold::new();
    let supported = DefaultQueryDispatcher
        .contact_manifold_convex_convex(
            &pos12,
            a.shape.as_ref(),
            b.shape.as_ref(),
            None,
            None,
            prediction,
            &mut manifold,
        )
        .is_ok();
    if supported && !manifold.points.is_empty() {
        let normal_a = Unit::new_normalize(world_a.rotation * manifold.local_n1);
        for p in &manifold.points {
            if p.dist <= prediction {
                out.push(ContactPoint {
                    point_a: world_a * p.local_p1,
                    point_b: world_b * p.local_p2,
                    normal_a,
                    distance: p.dist,
                });
            }
        }
        return;
    }
    // Pairs without a manifold generator fall back to the single closest-point contact.
    if let Ok(Some(c)) = query::contact(
        &world_a,
        a.shape.as_ref(),
        &world_b,
        b.shape.as_ref(),
        prediction,
    ) {
        out.push(ContactPoint {
            point_a: c.point1,
            point_b: c.point2,
            normal_a: c.normal1,
            distance: c.dist,
        });
    }
}
