//! Planar rigid-body math: SE(2) poses and twists of objects on the table.
//!
//! Poses are in the world frame (metres, radians); twists are body twists
//! `(vx, vy, omega)` expressed in the object frame about its origin (the centre of
//! friction), in m/s and rad/s.

use nalgebra::{Isometry3, Matrix2, Translation3, UnitQuaternion, Vector2, Vector3};
use std::f64::consts::PI;

/// Wraps an angle to `(-pi, pi]`.
pub fn wrap_angle(theta: f64) -> f64 {
    // fmod is slow (the metric wraps every object's yaw difference) and changes nothing
    // within a turn, so it runs only beyond one.
    let mut a = if theta.abs() < 2.0 * PI {
        theta
    } else {
        theta % (2.0 * PI)
    };
    if a <= -PI {
        a += 2.0 * PI;
    } else if a > PI {
        a -= 2.0 * PI;
    }
    a
}

/// The point of the segment from `a` to `b` nearest `p` (all in one plane's frame).
pub fn closest_on_segment(p: Vector2<f64>, a: Vector2<f64>, b: Vector2<f64>) -> Vector2<f64> {
    let ab = b - a;
    let length2 = ab.norm_squared();
    if length2 < 1e-24 {
        return a;
    }
    a + ab * ((p - a).dot(&ab) / length2).clamp(0.0, 1.0)
}

/// An object's configuration on the table: position of its origin (m) and yaw (rad), world
/// frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose2 {
    /// x of the origin (m).
    pub x: f64,
    /// y of the origin (m).
    pub y: f64,
    /// Yaw about the world's z (rad).
    pub theta: f64,
}

impl Pose2 {
    /// The pose at (`x`, `y`) (m) with yaw `theta` (rad).
    pub const fn new(x: f64, y: f64, theta: f64) -> Self {
        Self { x, y, theta }
    }

    /// The position of the origin (m).
    pub fn translation(&self) -> Vector2<f64> {
        Vector2::new(self.x, self.y)
    }

    /// Rotation taking object-frame vectors to world-frame vectors.
    pub fn rotation(&self) -> Matrix2<f64> {
        let (s, c) = self.theta.sin_cos();
        Matrix2::new(c, -s, s, c)
    }

    /// World-frame vector expressed in the object frame.
    pub fn vector_to_local(&self, v: Vector2<f64>) -> Vector2<f64> {
        self.rotation().transpose() * v
    }

    /// Object-frame vector expressed in the world frame.
    pub fn vector_to_world(&self, v: Vector2<f64>) -> Vector2<f64> {
        self.rotation() * v
    }

    /// Object-frame point expressed in the world frame.
    pub fn point_to_world(&self, p: Vector2<f64>) -> Vector2<f64> {
        self.translation() + self.rotation() * p
    }

    /// World-frame point expressed in the object frame.
    pub fn point_to_local(&self, p: Vector2<f64>) -> Vector2<f64> {
        self.vector_to_local(p - self.translation())
    }

    /// The composition `self * other`: `other` is a pose in this pose's frame; the result
    /// is that pose in the world.
    pub fn compose(&self, other: &Pose2) -> Pose2 {
        let t = self.translation() + self.rotation() * other.translation();
        Pose2::new(t.x, t.y, wrap_angle(self.theta + other.theta))
    }

    /// The inverse transform: `p.compose(&p.inverse())` is the identity.
    pub fn inverse(&self) -> Pose2 {
        let t = -(self.rotation().transpose() * self.translation());
        Pose2::new(t.x, t.y, wrap_angle(-self.theta))
    }

    /// The pose a fraction `s` (0..1) of the way along the straight line to `to`
    /// (translation linear, yaw the short way round).
    pub fn lerp(&self, to: &Pose2, s: f64) -> Pose2 {
        let turn = wrap_angle(to.theta - self.theta);
        Pose2::new(
            self.x + s * (to.x - self.x),
            self.y + s * (to.y - self.y),
            wrap_angle(self.theta + s * turn),
        )
    }

    /// The pose reached by holding the body twist `twist` for `dt` seconds
    /// (exact exponential map of SE(2)).
    pub fn integrate(&self, twist: &Twist2, dt: f64) -> Pose2 {
        let dtheta = twist.omega * dt;
        let (vx, vy) = (twist.vx * dt, twist.vy * dt);
        // Body-frame displacement of exp([v, w] dt).
        let (dx, dy) = if dtheta.abs() < 1e-9 {
            (vx - 0.5 * vy * dtheta, vy + 0.5 * vx * dtheta)
        } else {
            let (s, c) = dtheta.sin_cos();
            let a = s / dtheta;
            let b = (1.0 - c) / dtheta;
            (a * vx - b * vy, b * vx + a * vy)
        };
        let world = self.rotation() * Vector2::new(dx, dy);
        Pose2::new(
            self.x + world.x,
            self.y + world.y,
            wrap_angle(self.theta + dtheta),
        )
    }

    /// The 3D pose of the object's frame when its base rests at height `z` (m).
    pub fn to_isometry(&self, z: f64) -> Isometry3<f64> {
        Isometry3::from_parts(
            Translation3::new(self.x, self.y, z),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), self.theta),
        )
    }

    /// The planar pose of a 3D pose: its x, y and the yaw of its x axis (the inverse of
    /// [`to_isometry`](Self::to_isometry); height and tilt are dropped).
    pub fn from_isometry(pose: &Isometry3<f64>) -> Pose2 {
        let x_axis = pose.rotation * Vector3::x();
        Pose2::new(
            pose.translation.x,
            pose.translation.y,
            x_axis.y.atan2(x_axis.x),
        )
    }
}

/// A planar body twist: velocity of the object's origin and angular velocity,
/// in the object frame (m/s, rad/s).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Twist2 {
    /// Velocity of the origin along the object's x (m/s).
    pub vx: f64,
    /// Velocity of the origin along the object's y (m/s).
    pub vy: f64,
    /// Angular velocity about z (rad/s).
    pub omega: f64,
}

impl Twist2 {
    /// At rest.
    pub const ZERO: Twist2 = Twist2 {
        vx: 0.0,
        vy: 0.0,
        omega: 0.0,
    };

    /// Is every component exactly zero?
    pub fn is_zero(&self) -> bool {
        self.vx == 0.0 && self.vy == 0.0 && self.omega == 0.0
    }
}

/// A pose given by translation (m) and URDF-style roll/pitch/yaw (rad).
pub fn isometry_from_xyz_rpy(xyz: [f64; 3], rpy: [f64; 3]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(xyz[0], xyz[1], xyz[2]),
        UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_angle_stays_in_range() {
        assert!((wrap_angle(3.0 * PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(-PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(0.5) - 0.5).abs() < 1e-15);
        assert!((wrap_angle(-7.0) - (-7.0 + 2.0 * PI)).abs() < 1e-12);
    }

    #[test]
    fn composing_with_the_inverse_is_the_identity() {
        let p = Pose2::new(0.3, -0.2, 2.5);
        let q = Pose2::new(-0.1, 0.4, -1.0);
        let id = p.compose(&p.inverse());
        assert!(id.x.abs() < 1e-15 && id.y.abs() < 1e-15 && id.theta.abs() < 1e-15);
        // Composition agrees with the 3D isometries.
        let iso = p.to_isometry(0.0) * q.to_isometry(0.0);
        let c = p.compose(&q);
        assert!((iso.translation.x - c.x).abs() < 1e-15 && (iso.translation.y - c.y).abs() < 1e-15);
        assert!((iso.rotation.angle() - c.theta.abs()).abs() < 1e-12);
        // Halfway from yaw 3 to yaw -3 goes through pi, not 0.
        let half = Pose2::new(0.0, 0.0, 3.0).lerp(&Pose2::new(1.0, 0.0, -3.0), 0.5);
        assert!((half.x - 0.5).abs() < 1e-15 && (half.theta.abs() - PI).abs() < 1e-12);
    }

    #[test]
    fn integrating_a_pure_rotation_about_an_offset_point_traces_a_circle() {
        // Twist of a body rotating at 1 rad/s about the body point (0, -1):
        // v = -omega x r = (-1, 0) at the origin.
        let twist = Twist2 {
            vx: -1.0,
            vy: 0.0,
            omega: 1.0,
        };
        let p = Pose2::new(0.0, 0.0, 0.0).integrate(&twist, PI / 2.0);
        // Origin swings a quarter turn about (0, -1): ends at (-1, -1), yaw pi/2.
        assert!((p.x + 1.0).abs() < 1e-12 && (p.y + 1.0).abs() < 1e-12);
        assert!((p.theta - PI / 2.0).abs() < 1e-12);
    }
}
