//! A state of the world: the robot's configuration and every movable object's pose,
//! `x = (q, o^1, ..., o^M)`.

use crate::math::Pose2;
use nalgebra::DVector;

#[derive(Clone, Debug, PartialEq)]
pub struct State {
    /// Joint values (rad or m), in the robot's configuration order.
    pub q: DVector<f64>,
    /// Object poses, in the scene's object order (world frame).
    pub objects: Vec<Pose2>,
}
