//! Constraint projection (Alg. 2 line 5, Sec. V of the whole-arm paper).
//!
//! An end-effector action `a = (vx, vy, omega_z)` (world frame, m/s and rad/s, about the
//! tool point) becomes the joint step
//!
//! ```text
//! q_new = q + dt (J+ (a + c) + h),   h = (I - J+ J) z
//! ```
//!
//! where `J` is the tool point's 6 x n geometric Jacobian, `J+` its damped
//! pseudoinverse, `z` the action's null-space sample (joint velocities, rad/s) and `c`
//! the correction that keeps the tool on its plane: the height error and the tilt
//! error are removed within the step (vz, wx, wy rows). Yaw about the vertical is free.
//! When the first-order step still leaves the plane by more than the tolerance (near a
//! singularity), a few Newton corrections follow, as in CBiRRT's projection.

use super::Robot;
use crate::math::Pose2;
use nalgebra::{DVector, Isometry3, Matrix6, Translation3, UnitQuaternion, Vector3, Vector6};

/// The manifold the tool is held on: a horizontal plane and a fixed tilt.
#[derive(Clone, Debug)]
pub struct PushingPlane {
    /// World height of the tool point (m).
    pub height: f64,
    /// Tool orientation at yaw 0 (world frame). Only its tilt is constrained.
    pub orientation: UnitQuaternion<f64>,
    /// The world's up axis expressed in the tool frame: constant on the manifold.
    up_in_tool: Vector3<f64>,
}

impl PushingPlane {
    /// The plane at `height` (m above the table top) with the tool's world orientation at
    /// yaw 0.
    pub fn new(height: f64, orientation: UnitQuaternion<f64>) -> Self {
        let up_in_tool = orientation.inverse() * Vector3::z();
        Self {
            height,
            orientation,
            up_in_tool,
        }
    }

    /// Height error (m, signed: plane minus tool) and tilt error (rad, >= 0) of a tool
    /// pose.
    pub fn error(&self, tool: &Isometry3<f64>) -> (f64, f64) {
        let up = tool.rotation * self.up_in_tool;
        (
            self.height - tool.translation.z,
            up.z.clamp(-1.0, 1.0).acos(),
        )
    }

    /// The world pose of a tool on the plane at planar position (x, y) (m) and yaw
    /// `pose.theta` (rad) about the vertical.
    pub fn tool_pose_at(&self, pose: &Pose2) -> Isometry3<f64> {
        Isometry3::from_parts(
            Translation3::new(pose.x, pose.y, self.height),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), pose.theta) * self.orientation,
        )
    }

    /// The planar pose (x, y, yaw) of a tool pose on the plane: the inverse of
    /// [`tool_pose_at`](Self::tool_pose_at) (the tilt is ignored).
    pub fn planar_pose(&self, tool: &Isometry3<f64>) -> Pose2 {
        Pose2::from_isometry(&Isometry3::from_parts(
            tool.translation,
            tool.rotation * self.orientation.inverse(),
        ))
    }

    /// The twist (linear z and angular x, y rows; others zero) that removes the error
    /// in unit time.
    fn correction(&self, tool: &Isometry3<f64>) -> Vector6<f64> {
        let up = tool.rotation * self.up_in_tool;
        let axis = up.cross(&Vector3::z());
        let sin = axis.norm();
        let angle = up.z.clamp(-1.0, 1.0).acos();
        let w = if sin > 1e-12 {
            axis * (angle / sin)
        } else {
            Vector3::zeros()
        };
        Vector6::new(0.0, 0.0, self.height - tool.translation.z, w.x, w.y, 0.0)
    }
}

/// One action: a planar end-effector velocity and a null-space sample.
#[derive(Clone, Debug, PartialEq)]
pub struct EeAction {
    /// (vx, vy) in m/s and omega_z in rad/s, world frame, at the tool point.
    pub velocity: [f64; 3],
    /// Joint velocities (rad/s) projected onto the Jacobian's null space; empty = none.
    pub nullspace: DVector<f64>,
}

impl EeAction {
    /// A planar action: tool velocity (`vx`, `vy`, m/s, world frame) and turn rate
    /// `omega_z` (rad/s), no null-space motion.
    pub fn planar(vx: f64, vy: f64, omega_z: f64) -> Self {
        Self {
            velocity: [vx, vy, omega_z],
            nullspace: DVector::zeros(0),
        }
    }

    /// The action of the flat layout in which controls cross to OMPL and back:
    /// `[vx, vy, omega_z, z_0 .. z_{dof-1}]` (at least three values).
    pub fn from_flat(flat: &[f64]) -> Self {
        Self {
            velocity: [flat[0], flat[1], flat[2]],
            nullspace: DVector::from_column_slice(&flat[3..]),
        }
    }

    /// The flat layout of [`EeAction::from_flat`].
    pub fn flat(&self) -> impl Iterator<Item = f64> + '_ {
        self.velocity
            .into_iter()
            .chain(self.nullspace.iter().copied())
    }
}

/// Limits of the projection.
#[derive(Clone, Debug)]
pub struct ProjectionSettings {
    /// Damping of the pseudoinverse (m); keeps steps bounded near singularities.
    pub damping: f64,
    /// Fastest joint motion a step may ask (rad/s or m/s); faster means a singularity.
    /// A speed, not a step: a step of `dt` may move a joint `max_joint_speed * dt` (at
    /// most [`MAX_JOINT_STEP`]), so that the same action near the same singularity is
    /// refused at any step size (a limit per step let 0.1 ms steps chatter at 190 rad/s:
    /// `physics.max_joint_speed`).
    pub max_joint_speed: f64,
    /// Tolerated distance of the tool from its plane (m).
    pub height_tolerance: f64,
    /// Tolerated tilt of the tool (rad).
    pub tilt_tolerance: f64,
}

impl Default for ProjectionSettings {
    fn default() -> Self {
        Self {
            damping: 1e-3,
            max_joint_speed: 5.0,
            height_tolerance: 1e-3,
            tilt_tolerance: 0.01,
        }
    }
}

impl ProjectionSettings {
    /// Does a tool `height` (m) from its plane and tilted by `tilt` (rad) lie within these
    /// tolerances?
    pub fn admits(&self, height: f64, tilt: f64) -> bool {
        height.abs() <= self.height_tolerance && tilt <= self.tilt_tolerance
    }

    /// These settings with the tolerances a start state is held to: a thousandth of the
    /// propagation's, so that drift is measured from (almost) zero.
    pub fn for_start(&self) -> ProjectionSettings {
        ProjectionSettings {
            height_tolerance: self.height_tolerance * 1e-3,
            tilt_tolerance: self.tilt_tolerance * 1e-3,
            ..self.clone()
        }
    }
}

/// Why a projected step was refused.
#[derive(Clone, Debug, PartialEq)]
pub enum ProjectionFailure {
    /// A joint would move faster than the projection allows (a singularity).
    JointTooFast {
        /// The joint (configuration index).
        joint: usize,
        /// How fast it would move (rad/s or m/s).
        speed: f64,
    },
    /// The tool could not be brought back to its plane.
    OffPlane {
        /// Distance of the tool point from the plane (m).
        height_error: f64,
        /// Tilt of the tool from the plane's orientation (rad).
        tilt_error: f64,
    },
    /// The configuration or the action is not finite (NaN or infinite).
    NotFinite,
}

impl std::fmt::Display for ProjectionFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::JointTooFast { joint, speed } => {
                write!(
                    f,
                    "joint {joint} would move at {speed:.3} per second (singular)"
                )
            }
            Self::OffPlane {
                height_error,
                tilt_error,
            } => write!(
                f,
                // Three significant digits: a start is held to a thousandth of a step's
                // tolerance, and a residual of 2 um printed as "0.0000 m" read as none.
                "the tool stays {:.3e} m / {tilt_error:.3e} rad off its plane after \
                 {NEWTON_ITERATIONS} Newton corrections",
                height_error.abs()
            ),
            Self::NotFinite => write!(f, "the configuration or the action is not finite"),
        }
    }
}

const NEWTON_ITERATIONS: usize = 5;

/// Most a joint may move in one step, at any speed (rad or m): a link a metre out then
/// moves at most 5 cm between two collision checks, as far as the tool may
/// (`scene::load::MAX_STEP_TRAVEL`). It binds at steps longer than the default 10 ms.
pub const MAX_JOINT_STEP: f64 = 0.05;

impl Robot {
    /// Joint velocity that realises the task twist `task` (6 rows) plus the null-space
    /// part of `z` (empty for none), at the configuration with link poses `poses`.
    pub(super) fn joint_velocity(
        &self,
        poses: &[Isometry3<f64>],
        task: &Vector6<f64>,
        z: &DVector<f64>,
        damping: f64,
    ) -> Result<DVector<f64>, ProjectionFailure> {
        let tool = self.tool_pose(poses);
        let jac = self
            .chain
            .point_jacobian(poses, self.ee_link, &tool.translation.vector.into());
        // J J^T + damping^2 I and J z, column by column on the stack: this runs every
        // step, and the dynamic products allocated a packing buffer each time.
        let mut jjt = Matrix6::identity() * damping.powi(2);
        let mut jz = Vector6::zeros();
        for k in 0..jac.ncols() {
            let column = jac.fixed_view::<6, 1>(0, k);
            jjt += column * column.transpose();
            if !z.is_empty() {
                jz += column * z[k];
            }
        }
        // Damped J J^T is positive definite for finite J; NaN input ends here, not in a panic.
        let chol = jjt.cholesky().ok_or(ProjectionFailure::NotFinite)?;
        let mut qdot = jac.tr_mul(&chol.solve(task));
        if !z.is_empty() {
            qdot += z - jac.tr_mul(&chol.solve(&jz));
        }
        Ok(qdot)
    }

    /// Projects one step of `action` held for `dt` seconds from `q` (link poses `poses`)
    /// onto the pushing plane, within the robot's projection settings. Writes the new
    /// configuration and its link poses.
    pub fn project_step(
        &self,
        q: &DVector<f64>,
        poses: &[Isometry3<f64>],
        action: &EeAction,
        dt: f64,
        q_new: &mut DVector<f64>,
        poses_new: &mut Vec<Isometry3<f64>>,
    ) -> Result<(), ProjectionFailure> {
        let settings = &self.projection;
        let tool = self.tool_pose(poses);
        let [vx, vy, wz] = action.velocity;
        let task = Vector6::new(vx, vy, 0.0, 0.0, 0.0, wz) + self.plane.correction(&tool) / dt;
        if !task
            .iter()
            .chain(action.nullspace.iter())
            .all(|v| v.is_finite())
        {
            return Err(ProjectionFailure::NotFinite);
        }
        let qdot = self.joint_velocity(poses, &task, &action.nullspace, settings.damping)?;
        q_new.copy_from(q);
        q_new.axpy(dt, &qdot, 1.0);
        self.check_step(q, q_new, settings, dt)?;
        self.chain.forward_kinematics(q_new, poses_new);
        self.restore_plane(q_new, poses_new, settings)?;
        self.check_step(q, q_new, settings, dt)
    }

    /// Brings the tool of `q` onto its pushing plane as a start state's is held
    /// ([`ProjectionSettings::for_start`]).
    pub fn start_on_plane(&self, q: &mut DVector<f64>) -> Result<(), ProjectionFailure> {
        let mut poses = self.link_poses(q);
        self.restore_plane(q, &mut poses, &self.projection.for_start())
    }

    /// Newton corrections back onto the plane, if the tool has drifted beyond tolerance.
    pub fn restore_plane(
        &self,
        q: &mut DVector<f64>,
        poses: &mut Vec<Isometry3<f64>>,
        settings: &ProjectionSettings,
    ) -> Result<(), ProjectionFailure> {
        let within = |poses: &[Isometry3<f64>]| {
            let (h, t) = self.plane.error(&self.tool_pose(poses));
            (settings.admits(h, t), h, t)
        };
        let empty = DVector::zeros(0);
        for _ in 0..NEWTON_ITERATIONS {
            if within(poses).0 {
                return Ok(());
            }
            let correction = self.plane.correction(&self.tool_pose(poses));
            let dq = self.joint_velocity(poses, &correction, &empty, settings.damping)?;
            *q += dq;
            self.chain.forward_kinematics(q, poses);
        }
        match within(poses) {
            (true, _, _) => Ok(()),
            (false, height_error, tilt_error) => Err(ProjectionFailure::OffPlane {
                height_error,
                tilt_error,
            }),
        }
    }

    /// Refuses a step of `dt` seconds from `q` to `q_new` that moves a joint faster than
    /// `settings.max_joint_speed`, or farther than [`MAX_JOINT_STEP`].
    fn check_step(
        &self,
        q: &DVector<f64>,
        q_new: &DVector<f64>,
        settings: &ProjectionSettings,
        dt: f64,
    ) -> Result<(), ProjectionFailure> {
        let largest = (settings.max_joint_speed * dt).min(MAX_JOINT_STEP);
        for i in 0..q.len() {
            let step = (q_new[i] - q[i]).abs();
            if step.is_nan() || step > largest {
                return Err(ProjectionFailure::JointTooFast {
                    joint: i,
                    speed: step / dt,
                });
            }
        }
        Ok(())
    }
}
