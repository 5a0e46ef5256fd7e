//! The model side of the DARRT baseline (the whole-arm paper, Sec. V-A, after Barry,
//! Kaelbling and Lozano-Pérez): its motion primitives and the check of its paths. The
//! planner loop is OMPL's side (`cpp/planners/darrt/darrt.cpp`).
//!
//! - **Transit** ([`crate::planning::transit`]): the arm moves along a straight line in configuration
//!   space, the objects stay where they are; every configuration on the line is a valid
//!   state. RRTTransit chains Transit motions found by OMPL's RRT-Connect.
//! - **Push** ([`cage`], [`carry()`]): the hand cages one object, which then moves rigidly
//!   with the tool along a straight line in SE(2) while the tool stays on its pushing
//!   plane. Nothing but the hand may touch the carried object beyond the usual contact,
//!   and the carried object must stay clear of the other objects and the obstacles.
//! - **PickPlace** ([`pick_place()`]): the hand grasps one object, carries it through the
//!   air and sets it down elsewhere, by the manipulation graph (the paper's suggestion,
//!   Sec. V-A; the planner `darrt_pick`, measured beside DARRT without it).
//!
//! Unlike PC RRT's plans, DARRT's are not pushing-model controls: a caged object follows
//! the hand by assumption, not by the physics. A DARRT path is a sequence of states in
//! which each consecutive pair is one Transit motion, one step of a Push, or a pick-up,
//! carrying line or set-down of a PickPlace, each state saying what the hand holds
//! ([`check::check_path`]).

pub mod cage;
pub mod carry;
pub mod check;
pub mod pick_place;

pub use cage::{approach, Cage};
pub use carry::{carry, check_carrying};
pub use check::{check_path, PrimitivePath};
pub use pick_place::{pick_place, PathState, PickPlaceSettings};

use crate::robot::Robot;
use crate::validity::Invalid;
use std::fmt;

/// Why a primitive cannot be applied.
#[derive(Clone, Debug, PartialEq)]
pub enum PrimitiveFailure {
    /// A state the primitive would pass through is invalid.
    Invalid(Invalid),
    /// No arm configuration puts the hand where the primitive needs it.
    Unreachable,
    /// Following the line would make a joint jump (rad, or m): a singularity or a
    /// branch change of the inverse kinematics.
    JointJump {
        /// The joint (configuration index).
        joint: usize,
        /// How far it would jump (rad or m).
        step: f64,
    },
    /// PickPlace: the manipulation graph found no way within its budget.
    NoPath,
    /// PickPlace: the manipulation graph's way fails the path check (why).
    Refused(String),
}

impl fmt::Display for PrimitiveFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Invalid(reason) => write!(f, "{reason}"),
            Self::Unreachable => write!(f, "the hand cannot reach the object's cage pose"),
            Self::JointJump { joint, step } => {
                write!(f, "joint {joint} would jump {step:.3} in one step")
            }
            Self::NoPath => write!(f, "no way to pick the object up and set it down was found"),
            Self::Refused(why) => write!(f, "the way to pick the object up fails its check: {why}"),
        }
    }
}

impl From<Invalid> for PrimitiveFailure {
    fn from(reason: Invalid) -> Self {
        Self::Invalid(reason)
    }
}

/// The hand: the end-effector link and every link below it (fingers, if any).
pub fn hand_links(robot: &Robot) -> Vec<usize> {
    (0..robot.chain.links.len())
        .filter(|&l| l == robot.ee_link || robot.chain.is_ancestor(robot.ee_link, l))
        .collect()
}
