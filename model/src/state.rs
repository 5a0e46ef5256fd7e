//! A state of the world: the robot's configuration and every movable object's pose,
//! `x = (q, o^1, ..., o^M)`.

use crate::math::Pose2;
use nalgebra::DVector;

/// A state `x = (q, o^1, ..., o^M)`: the robot's joints and every movable object's planar
/// pose.
#[derive(Debug, PartialEq)]
pub struct State {
    /// Joint values (rad or m), in the robot's configuration order.
    pub q: DVector<f64>,
    /// Object poses, in the scene's object order (world frame).
    pub objects: Vec<Pose2>,
}

impl Clone for State {
    fn clone(&self) -> Self {
        State {
            q: self.q.clone(),
            objects: self.objects.clone(),
        }
    }

    /// Into the buffers `self` has when the sizes match (propagation keeps states).
    fn clone_from(&mut self, source: &Self) {
        if self.q.len() == source.q.len() {
            self.q.copy_from(&source.q);
        } else {
            self.q = source.q.clone();
        }
        self.objects.clone_from(&source.objects);
    }
}

/// The flat layout in which states cross to OMPL and back:
/// `[q_0 .. q_{dof-1}, x_1, y_1, theta_1, .., x_M, y_M, theta_M]` (rad or m; m, m, rad in
/// the world frame).
impl State {
    /// The number of values of a flat state.
    #[inline]
    pub fn flat_len(dof: usize, objects: usize) -> usize {
        Self::flat_object(dof, objects)
    }

    /// Where object `object`'s x is in a flat state of `dof` joints; its y and yaw follow.
    #[inline]
    pub fn flat_object(dof: usize, object: usize) -> usize {
        dof + 3 * object
    }

    /// The state in the flat layout (`flat_len` values).
    pub fn to_flat(&self) -> Vec<f64> {
        let mut out = vec![0.0; Self::flat_len(self.q.len(), self.objects.len())];
        self.write_flat(&mut out);
        out
    }

    /// Writes the flat state into `out`, which has [`State::flat_len`] values.
    pub fn write_flat(&self, out: &mut [f64]) {
        let dof = self.q.len();
        out[..dof].copy_from_slice(self.q.as_slice());
        for (pose, slot) in self.objects.iter().zip(out[dof..].chunks_exact_mut(3)) {
            slot.copy_from_slice(&[pose.x, pose.y, pose.theta]);
        }
    }

    /// States one after another in a flat array, for `dof` joints and `objects` objects.
    pub fn many_from_flat(flat: &[f64], dof: usize, objects: usize) -> Result<Vec<State>, String> {
        let n = Self::flat_len(dof, objects);
        if flat.len() % n != 0 {
            return Err(format!("{} values are not whole states of {n}", flat.len()));
        }
        Ok(flat.chunks(n).map(|s| Self::from_flat(s, dof)).collect())
    }

    /// The state of joints `q` and object poses flat as in a state (`[x, y, yaw]` each).
    pub fn from_flat_parts(q: &DVector<f64>, objects: &[f64]) -> State {
        State {
            q: q.clone(),
            objects: poses_from_flat(objects),
        }
    }

    /// The state of a flat array for a robot with `dof` joints; the rest are object poses.
    pub fn from_flat(flat: &[f64], dof: usize) -> State {
        State {
            q: DVector::from_column_slice(&flat[..dof]),
            objects: poses_from_flat(&flat[dof..]),
        }
    }
}

/// Object poses from `[x, y, yaw]` triples.
fn poses_from_flat(flat: &[f64]) -> Vec<Pose2> {
    let mut poses = Vec::with_capacity(flat.len() / 3);
    poses_from_flat_into(flat, &mut poses);
    poses
}

/// Object poses from `[x, y, yaw]` triples, into `out` (its old contents dropped): for
/// callers that reuse one buffer.
pub fn poses_from_flat_into(flat: &[f64], out: &mut Vec<Pose2>) {
    out.clear();
    out.extend(flat.chunks_exact(3).map(|c| Pose2::new(c[0], c[1], c[2])));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clone_from_gives_the_source_whatever_the_buffers_held() {
        let source = State::from_flat(&[0.1, -0.2, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0], 2);
        // Same sizes (copied into the buffers), fewer joints and more objects, nothing.
        for flat in [
            &[9.0, 9.0, 9.0, 9.0, 9.0, 9.0, 9.0, 9.0][..],
            &[9.0, 9.0, 9.0, 9.0, 9.0, 9.0, 9.0, 9.0, 9.0, 9.0][..],
            &[][..],
        ] {
            let mut kept = State::from_flat(flat, flat.len().min(1));
            kept.clone_from(&source);
            assert_eq!(kept, source);
        }
    }
}
