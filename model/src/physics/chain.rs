//! Objects pushing objects: the quasistatic motion of a cluster of objects in contact,
//! pushed by the arm at some of them.
//!
//! The single-object model ([`super::pushing`]) with the contacts between objects added
//! as unknowns: a contact between two objects carries equal and opposite forces, and its
//! complementarity conditions hold on the objects' relative motion. Every quantity is in
//! the world frame (m, m/s, rad/s, N).
//!
//! Each object slides as its ellipsoidal limit surface says, `V_b ∝ A_b F_b` with `A_b =
//! diag(1, 1, 1/c_b^2)`, the twist about its centre of friction. One object's force is on
//! its limit surface whatever its speed; several objects' forces are related through
//! their contacts, so the proportionality must be shared: here `V_b = k A_b F_b / f_b`
//! (with `f_b = mu_g m g`), which puts every object's force at `f_b` times its speed over
//! the cluster's scale. That is exact when the objects move at one speed, as a pushed row
//! does (the forces then split in proportion to `f_b`, as sliding requires), and an
//! approximation when one object of the cluster slides much slower than another.

#![allow(non_snake_case)] // frame-named points: p_WC, a centre in the world frame

use super::limit_surface::LimitSurface;
use super::pushing::{coulomb_lcp, wrench, Direction, Jammed, REST_SPEED};
use nalgebra::{Vector2, Vector3};

/// What pushes at a contact: the arm, moving at a known velocity, or another object of
/// the cluster.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pusher {
    /// A link's material point at the contact moving at this velocity (m/s).
    Moving(Vector2<f64>),
    /// The object with this index in the cluster.
    Body(usize),
}

/// A contact of the cluster, world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClusterContact {
    /// The pushed object (index in the cluster).
    pub body: usize,
    /// What pushes: the hand (a link) or another object of the cluster.
    pub pusher: Pusher,
    /// Contact point (m).
    pub point: Vector2<f64>,
    /// Unit normal pointing into the pushed object.
    pub normal: Vector2<f64>,
    /// Distance between the surfaces (m); negative when penetrating.
    pub gap: f64,
    /// Coulomb friction coefficient at the contact.
    pub mu: f64,
}

impl ClusterContact {
    fn tangent(&self) -> Vector2<f64> {
        Vector2::new(-self.normal.y, self.normal.x)
    }
}

/// The solved motion of a cluster.
#[derive(Clone, Debug, PartialEq)]
pub struct ClusterMotion {
    /// Per object: velocity of its centre of friction (m/s) and angular velocity (rad/s),
    /// world frame, as (vx, vy, omega).
    pub twists: Vec<Vector3<f64>>,
    /// Per contact: normal force on the pushed object (N).
    pub normal_forces: Vec<f64>,
    /// Per contact: friction force on the pushed object along the tangent (N).
    pub friction_forces: Vec<f64>,
}

impl ClusterMotion {
    /// The velocity (m/s) of body `b`'s material point at `p_W`, given its centre `p_WC`.
    pub fn point_velocity(&self, b: usize, p_WC: Vector2<f64>, p_W: Vector2<f64>) -> Vector2<f64> {
        let v = self.twists[b];
        let r = p_W - p_WC;
        Vector2::new(v.x - v.z * r.y, v.y + v.z * r.x)
    }
}

/// A unit force along one of a contact's directions, as wrenches on the bodies it acts
/// on: the pushed body, and the pushing one (the opposite wrench) between objects.
struct UnitLoad {
    on_body: (usize, Vector3<f64>),
    on_pusher: Option<(usize, Vector3<f64>)>,
}

impl UnitLoad {
    fn new(c: &ClusterContact, d: Vector2<f64>, surfaces: &[LimitSurface]) -> Self {
        let on = |b: usize| wrench(d, c.point, surfaces[b].centre);
        UnitLoad {
            on_body: (c.body, on(c.body)),
            on_pusher: match c.pusher {
                Pusher::Moving(_) => None,
                Pusher::Body(p) => Some((p, -on(p))),
            },
        }
    }

    fn parts(&self) -> impl Iterator<Item = &(usize, Vector3<f64>)> {
        std::iter::once(&self.on_body).chain(&self.on_pusher)
    }
}

/// Solves the twists of a cluster of objects, given their limit surfaces (each `centre`,
/// the centre of friction, in the world frame), under its contacts for a step of `dt`
/// seconds: no contact penetrates at the end of the step, friction opposes slip within
/// each contact's cone. `Jammed` when no motion satisfies every contact.
pub fn cluster_motion(
    surfaces: &[LimitSurface],
    contacts: &[ClusterContact],
    dt: f64,
) -> Result<ClusterMotion, Jammed> {
    let m = contacts.len();
    let still = || ClusterMotion {
        twists: vec![Vector3::zeros(); surfaces.len()],
        normal_forces: vec![0.0; m],
        friction_forces: vec![0.0; m],
    };
    let arm_speed = |c: &ClusterContact| match c.pusher {
        Pusher::Moving(v) => v,
        Pusher::Body(_) => Vector2::zeros(),
    };
    let approach = |c: &ClusterContact| c.normal.dot(&arm_speed(c)) - c.gap / dt;
    let pushes = |c: &ClusterContact| {
        matches!(c.pusher, Pusher::Moving(v) if c.normal.dot(&v) > REST_SPEED) && approach(c) > 0.0
    };
    if !contacts.iter().any(pushes) {
        return Ok(still());
    }

    let normals: Vec<UnitLoad> = contacts
        .iter()
        .map(|c| UnitLoad::new(c, c.normal, surfaces))
        .collect();
    let tangents: Vec<UnitLoad> = contacts
        .iter()
        .map(|c| UnitLoad::new(c, c.tangent(), surfaces))
        .collect();
    // Mobility per body: A_b / f_b.
    let mobility: Vec<Vector3<f64>> = surfaces
        .iter()
        .map(|s| s.mobility().diagonal() / s.f_max)
        .collect();
    let pick = |k: usize, d: Direction| match d {
        Direction::Normal => &normals[k],
        Direction::Tangent => &tangents[k],
    };
    let gram = |i: usize, di: Direction, j: usize, dj: Direction| {
        let (ui, uj) = (pick(i, di), pick(j, dj));
        let mut sum = 0.0;
        for (bi, wi) in ui.parts() {
            for (_, wj) in uj.parts().filter(|(bj, _)| bj == bi) {
                sum += wi.component_mul(&mobility[*bi]).dot(wj);
            }
        }
        sum
    };
    let z = coulomb_lcp(
        m,
        |k| contacts[k].mu,
        gram,
        |k| approach(&contacts[k]),
        |k| contacts[k].tangent().dot(&arm_speed(&contacts[k])),
    )
    .ok_or(Jammed)?;

    let mut wrenches = vec![Vector3::zeros(); surfaces.len()];
    for k in 0..m {
        let (fl, fr) = (z[m + k], z[2 * m + k]);
        for (load, force) in [(&normals[k], z[k]), (&tangents[k], fl - fr)] {
            for (b, w) in load.parts() {
                wrenches[*b] += w * force;
            }
        }
    }
    let twists: Vec<Vector3<f64>> = wrenches
        .iter()
        .zip(&mobility)
        .map(|(w, a)| w.component_mul(a))
        .collect();
    // Scale the forces so the most loaded object's wrench lies on its limit surface
    // (F^T A F = f_max^2); the others are on the same scale.
    let load = wrenches
        .iter()
        .zip(surfaces)
        .map(|(w, s)| w.dot(&(s.mobility() * w)).sqrt() / s.f_max)
        .fold(0.0, f64::max);
    let scale = if load > 0.0 { 1.0 / load } else { 0.0 };
    Ok(ClusterMotion {
        twists,
        normal_forces: (0..m).map(|k| z[k] * scale).collect(),
        friction_forces: (0..m).map(|k| (z[m + k] - z[2 * m + k]) * scale).collect(),
    })
}
