//! Tipping: does the table keep a pushed prism flat? (`physics.md`, "Tipping")
//!
//! Frame `O` is the object frame with its origin on the table plane (z up). The table
//! carries the object with a normal force `N` at the centre of pressure `P` and friction
//! in the table plane, whose moment is vertical. Balance of the horizontal moments about
//! `O` under the weight `m g` (at the footprint centroid `G`) and the pusher forces `f_k`
//! (at points `p_k`, heights `h_k` above the table) fixes `P`:
//!
//! ```text
//! N = m g - sum_k f_k,z
//! N p_OP = m g p_OG + sum_k ( h_k f_k,xy - f_k,z p_k,xy )
//! ```
//!
//! The height of the centre of mass does not enter: the balance is quasistatic. The
//! object stays flat while `N > 0` and `P` lies inside the footprint; otherwise it tips
//! about the footprint's edge. A box of half-width `b` pushed flat-on through its centre
//! line while it slides (`|f| = mu_g m g`) tips above `h = b / mu_g`.
//!
//! Names follow Drake's monograms: `p_OC` is the position of point C in frame O.
#![allow(non_snake_case)]

use super::limit_surface::{Footprint, GRAVITY};
use super::pushing::{ObjectMotion, PlanarContact};
use nalgebra::{Vector2, Vector3};

/// Where a planar contact sits in 3D: what the planar model drops and tipping needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactElevation {
    /// Height above the table top of the contact's lowest point (m). A pushed face
    /// about to tip turns away from the pusher at the top, so the force settles there.
    pub height: f64,
    /// Downward slope of the contact normal force, `tan(alpha) = n_z / |n_xy|` for the 3D
    /// normal `n` out of the object (positive: the pusher presses down, as on a rim).
    pub slope: f64,
}

impl ContactElevation {
    /// Vertical force on the object per newton of horizontal normal force (positive:
    /// up). A contact that pushes up lifts by its own slope. A pusher pressing down (on a
    /// rim, a top edge) is not counted on at all: friction in the 3D contact, which the
    /// planar model leaves open, may cancel the press, and in the 3D engine boxes pressed
    /// down by a sloping forearm tipped where counting on the press beyond the friction
    /// angle said they would not (BENCHMARKS.md, "Plans that work in the world").
    pub fn lift(&self) -> f64 {
        (-self.slope).max(0.0)
    }
}

/// A pusher force on the object, object frame `O`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PusherForce {
    /// Point of application; z is the height above the table top (m).
    pub p_OC: Vector3<f64>,
    /// Force on the object (N).
    pub f: Vector3<f64>,
}

/// How the table carries the object.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SupportBalance {
    /// Support normal force (N).
    pub normal: f64,
    /// Centre of pressure on the table plane, object frame (m).
    pub p_OP: Vector2<f64>,
}

/// The support balance of an object of `mass` (kg) with footprint centroid `p_OG` under
/// the pusher forces.
pub fn support_balance<'a>(
    mass: f64,
    p_OG: Vector2<f64>,
    forces: impl IntoIterator<Item = &'a PusherForce>,
) -> SupportBalance {
    let weight = mass * GRAVITY;
    let mut normal = weight;
    let mut moment = p_OG * weight;
    for PusherForce { p_OC, f } in forces {
        normal -= f.z;
        moment += f.xy() * p_OC.z - p_OC.xy() * f.z;
    }
    SupportBalance {
        normal,
        p_OP: if normal > 0.0 {
            moment / normal
        } else {
            Vector2::repeat(f64::INFINITY)
        },
    }
}

impl SupportBalance {
    /// Does the object stay flat? `margin` in [0, 1) shrinks the footprint about its
    /// centroid by that fraction first (0.3: the centre of pressure must stay within
    /// 70 % of the way from the centroid to the edge), a reserve for unknown friction.
    pub fn stays_flat(&self, footprint: &Footprint, margin: f64) -> bool {
        let centroid = footprint.centroid();
        self.normal > 0.0 && footprint.contains(centroid + (self.p_OP - centroid) / (1.0 - margin))
    }
}

/// The pusher forces of a solved push, object frame: each planar contact's force at its
/// point and elevation.
pub fn pusher_forces(
    contacts: &[PlanarContact],
    elevations: &[ContactElevation],
    motion: &ObjectMotion,
    out: &mut Vec<PusherForce>,
) {
    out.clear();
    out.extend(
        contacts
            .iter()
            .zip(elevations)
            .enumerate()
            .map(|(i, (c, e))| {
                let f = motion.force(contacts, i);
                PusherForce {
                    p_OC: Vector3::new(c.point.x, c.point.y, e.height),
                    f: Vector3::new(f.x, f.y, e.lift() * motion.normal_forces[i]),
                }
            }),
    );
}

/// The force with the largest tipping moment `h |f_xy|` (the pusher to blame).
pub fn largest_tipping_moment(forces: &[PusherForce]) -> Option<usize> {
    let moment = |f: &PusherForce| f.p_OC.z * f.f.xy().norm();
    (0..forces.len()).max_by(|&a, &b| moment(&forces[a]).total_cmp(&moment(&forces[b])))
}

/// Would a push at this contact tip the object if it alone pushed hard enough to slide
/// it (`|f_xy| = mu_g m g` along the contact normal, the largest push the table's
/// friction resists)? An arm that passes or first touches an object only where this is
/// false does not tip it whichever way the touch turns out (`physics.md`, "Tipping").
pub fn sliding_push_tips(
    mass: f64,
    mu_g: f64,
    footprint: &Footprint,
    contact: &PlanarContact,
    elevation: &ContactElevation,
    margin: f64,
) -> bool {
    let push = mu_g * mass * GRAVITY;
    let force = PusherForce {
        p_OC: Vector3::new(contact.point.x, contact.point.y, elevation.height),
        f: Vector3::new(
            push * contact.normal.x,
            push * contact.normal.y,
            elevation.lift() * push,
        ),
    };
    !support_balance(mass, footprint.centroid(), [&force]).stays_flat(footprint, margin)
}
