//! The motion of one object pushed at one or more points.
//!
//! Unknowns per contact i: normal force `fn_i`, friction split into `fl_i` (along +t_i)
//! and `fr_i` (along -t_i), and the slip speed `lambda_i`. The object twist is
//! `V = A sum_i (N_i fn_i + T_i (fl_i - fr_i))` with `N_i = J_i^T n_i`, `T_i = J_i^T t_i`.
//! Complementarity per contact:
//!
//! ```text
//! 0 <= fn  ⊥  N^T V - n.v_p + gap/dt >= 0   (no penetration at the end of the step)
//! 0 <= fl  ⊥  T^T V - t.v_p + lambda >= 0   (friction opposes slip)
//! 0 <= fr  ⊥ -T^T V + t.v_p + lambda >= 0
//! 0 <= lambda ⊥ mu fn - fl - fr >= 0        (Coulomb cone)
//! ```
//!
//! The `gap/dt` term lets a contact that closes within the step push for the rest of it,
//! and removes residual penetration. For a single contact at zero gap this is exactly
//! the sticking / sliding / separating solution of `physics.md`.

use super::lcp;
use super::limit_surface::LimitSurface;
use crate::math::Twist2;
use nalgebra::{DMatrix, DVector, Vector2, Vector3};

/// Pushers slower than this (m/s) along the normal are at rest.
pub const REST_SPEED: f64 = 1e-6;

/// A pusher contact on an object, in the object frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarContact {
    /// Contact point on the object's boundary (m).
    pub point: Vector2<f64>,
    /// Unit normal pointing into the object.
    pub normal: Vector2<f64>,
    /// Velocity of the pusher's material point at the contact (m/s).
    pub pusher_velocity: Vector2<f64>,
    /// Distance from pusher to object (m); negative when penetrating.
    pub gap: f64,
}

impl PlanarContact {
    /// Tangent: the normal turned by +90 degrees.
    pub fn tangent(&self) -> Vector2<f64> {
        Vector2::new(-self.normal.y, self.normal.x)
    }

    /// Wrench of a unit force `f` at the contact point about `centre`:
    /// (fx, fy, x fy - y fx) with (x, y) the point relative to the centre.
    fn wrench(&self, f: Vector2<f64>, centre: Vector2<f64>) -> Vector3<f64> {
        wrench(f, self.point, centre)
    }
}

/// Wrench about `centre` of a force `f` at `point`: (fx, fy, r x f), r = point - centre.
pub(super) fn wrench(f: Vector2<f64>, point: Vector2<f64>, centre: Vector2<f64>) -> Vector3<f64> {
    let r = point - centre;
    Vector3::new(f.x, f.y, r.x * f.y - r.y * f.x)
}

/// The pushers hold the object from opposing sides: no motion satisfies every contact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Jammed;

/// The solved motion of a pushed object.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectMotion {
    /// Body twist (m/s, rad/s) of the object frame's origin.
    pub twist: Twist2,
    /// Normal force at each contact (N), scaled so the total wrench lies on the limit surface.
    pub normal_forces: Vec<f64>,
    /// Friction force at each contact along its tangent `t` (N), on the same scale.
    pub friction_forces: Vec<f64>,
}

impl ObjectMotion {
    /// The force contact `i` applies to the object, object frame (N).
    pub fn force(&self, contacts: &[PlanarContact], i: usize) -> Vector2<f64> {
        contacts[i].normal * self.normal_forces[i] + contacts[i].tangent() * self.friction_forces[i]
    }
}

/// Solves the object's twist under the given pusher contacts for a step of `dt` seconds.
pub fn object_motion(
    contacts: &[PlanarContact],
    surface: &LimitSurface,
    mu_c: f64,
    dt: f64,
) -> Result<ObjectMotion, Jammed> {
    let m = contacts.len();
    let approach = |c: &PlanarContact| c.normal.dot(&c.pusher_velocity) - c.gap / dt;
    let pushes =
        |c: &PlanarContact| c.normal.dot(&c.pusher_velocity) > REST_SPEED && approach(c) > 0.0;
    if !contacts.iter().any(pushes) {
        // No pusher moves into the object and closes its gap within the step: nothing
        // pushes it. (Residual penetration alone does not move an object at rest.)
        return Ok(ObjectMotion {
            twist: Twist2::ZERO,
            normal_forces: vec![0.0; m],
            friction_forces: vec![0.0; m],
        });
    }

    let a = surface.mobility();
    let centre = surface.centre;
    let normals: Vec<Vector3<f64>> = contacts
        .iter()
        .map(|c| c.wrench(c.normal, centre))
        .collect();
    let tangents: Vec<Vector3<f64>> = contacts
        .iter()
        .map(|c| c.wrench(c.tangent(), centre))
        .collect();

    let gram = |i: usize, di: Direction, j: usize, dj: Direction| {
        let pick = |k: usize, d: Direction| match d {
            Direction::Normal => normals[k],
            Direction::Tangent => tangents[k],
        };
        pick(i, di).dot(&(a * pick(j, dj)))
    };
    let z = coulomb_lcp(
        m,
        |_| mu_c,
        gram,
        |i| approach(&contacts[i]),
        |i| contacts[i].tangent().dot(&contacts[i].pusher_velocity),
    )
    .ok_or(Jammed)?;
    let mut wrench = Vector3::zeros();
    for i in 0..m {
        wrench += normals[i] * z[i] + tangents[i] * (z[m + i] - z[2 * m + i]);
    }
    let v = a * wrench;
    // Scale the solver's forces onto the limit surface: F^T A F / f_max^2 = 1.
    let load = wrench.dot(&v).sqrt();
    let scale = if load > 0.0 {
        surface.f_max / load
    } else {
        0.0
    };
    // The limit surface gives the twist about the centre of friction c; the origin o
    // moves at v_c + omega z x (o - c).
    Ok(ObjectMotion {
        twist: Twist2 {
            vx: v.x + v.z * centre.y,
            vy: v.y - v.z * centre.x,
            omega: v.z,
        },
        normal_forces: (0..m).map(|i| z[i] * scale).collect(),
        friction_forces: (0..m).map(|i| (z[m + i] - z[2 * m + i]) * scale).collect(),
    })
}

/// The direction of a contact's force or relative motion: along its normal or its tangent.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Direction {
    Normal,
    Tangent,
}

/// The complementarity problem of `m` Coulomb contacts (unknowns ordered `fn, fl, fr,
/// lambda`, each block of size `m`, as in the module's doc), solved by Lemke's method.
///
/// `gram(i, di, j, dj)` is the relative velocity along contact `i`'s direction `di` that
/// a unit force along contact `j`'s direction `dj` causes (`u_i^T A u_j` with the bodies'
/// mobility `A`); `approach(i)` the speed at which contact `i` would close without any
/// force, gap included (m/s); `sliding(i)` the pusher's own speed along its tangent.
pub(super) fn coulomb_lcp(
    m: usize,
    mu: impl Fn(usize) -> f64,
    gram: impl Fn(usize, Direction, usize, Direction) -> f64,
    approach: impl Fn(usize) -> f64,
    sliding: impl Fn(usize) -> f64,
) -> Option<DVector<f64>> {
    use Direction::{Normal, Tangent};
    let mut mat = DMatrix::<f64>::zeros(4 * m, 4 * m);
    let mut q = DVector::<f64>::zeros(4 * m);
    for i in 0..m {
        for j in 0..m {
            let nn = gram(i, Normal, j, Normal);
            let nt = gram(i, Normal, j, Tangent);
            let tn = gram(i, Tangent, j, Normal);
            let tt = gram(i, Tangent, j, Tangent);
            mat[(i, j)] = nn;
            mat[(i, m + j)] = nt;
            mat[(i, 2 * m + j)] = -nt;
            mat[(m + i, j)] = tn;
            mat[(m + i, m + j)] = tt;
            mat[(m + i, 2 * m + j)] = -tt;
            mat[(2 * m + i, j)] = -tn;
            mat[(2 * m + i, m + j)] = -tt;
            mat[(2 * m + i, 2 * m + j)] = tt;
        }
        mat[(m + i, 3 * m + i)] = 1.0;
        mat[(2 * m + i, 3 * m + i)] = 1.0;
        mat[(3 * m + i, i)] = mu(i);
        mat[(3 * m + i, m + i)] = -1.0;
        mat[(3 * m + i, 2 * m + i)] = -1.0;

        let vt = sliding(i);
        q[i] = -approach(i);
        q[m + i] = -vt;
        q[2 * m + i] = vt;
    }
    lcp::solve(&mat, &q)
}
