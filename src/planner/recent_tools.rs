//! The tool point at the states propagation reached last. A projection-based planner
//! (KPIECE1, Push KPIECE) projects every state of a motion right after propagating it, and
//! the projection's first coordinates are the tool's xy: the propagator knew them already
//! (its link poses), so the projection need not run forward kinematics again.

#![allow(non_snake_case)] // p_WT: the tool point in the world frame

use nalgebra::Vector2;

/// A ring of the last `capacity` propagated states (flat, bit for bit) with the tool
/// point's world xy (m) at each.
#[derive(Clone, Debug, Default)]
pub struct RecentTools {
    /// `capacity` flat states of `len` values each, one per slot.
    states: Vec<f64>,
    tools: Vec<Vector2<f64>>,
    len: usize,
    /// The slot the next state goes to.
    next: usize,
    /// How many slots hold a state.
    filled: usize,
}

impl RecentTools {
    /// Room for `capacity` states of `len` values.
    pub fn new(capacity: usize, len: usize) -> RecentTools {
        RecentTools {
            states: vec![0.0; capacity * len],
            tools: vec![Vector2::zeros(); capacity],
            len,
            next: 0,
            filled: 0,
        }
    }

    /// Remembers that the tool stands at `p_WT` in `state` (the oldest state is dropped).
    pub fn push(&mut self, state: &[f64], p_WT: Vector2<f64>) {
        let capacity = self.tools.len();
        if capacity == 0 || state.len() != self.len {
            return;
        }
        let slot = self.next;
        self.states[slot * self.len..(slot + 1) * self.len].copy_from_slice(state);
        self.tools[slot] = p_WT;
        self.next = (slot + 1) % capacity;
        self.filled = (self.filled + 1).min(capacity);
    }

    /// The tool point's world xy at `state`, if it is one of the remembered states (the
    /// same bits). Looks from the oldest: a motion's states are projected in the order
    /// they were propagated.
    pub fn get(&self, state: &[f64]) -> Option<Vector2<f64>> {
        if state.len() != self.len {
            return None;
        }
        let capacity = self.tools.len();
        let oldest = (self.next + capacity - self.filled) % capacity.max(1);
        (0..self.filled)
            .map(|i| (oldest + i) % capacity)
            .find(|&slot| {
                let stored = &self.states[slot * self.len..(slot + 1) * self.len];
                stored
                    .iter()
                    .zip(state)
                    .all(|(a, b)| a.to_bits() == b.to_bits())
            })
            .map(|slot| self.tools[slot])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn it_finds_the_remembered_states_and_forgets_the_oldest() {
        let mut recent = RecentTools::new(2, 2);
        recent.push(&[1.0, 2.0], Vector2::new(0.1, 0.2));
        recent.push(&[3.0, 4.0], Vector2::new(0.3, 0.4));
        assert_eq!(recent.get(&[1.0, 2.0]), Some(Vector2::new(0.1, 0.2)));
        assert_eq!(recent.get(&[3.0, 4.0]), Some(Vector2::new(0.3, 0.4)));
        recent.push(&[5.0, 6.0], Vector2::new(0.5, 0.6));
        assert_eq!(recent.get(&[1.0, 2.0]), None, "the oldest is dropped");
        assert_eq!(recent.get(&[5.0, 6.0]), Some(Vector2::new(0.5, 0.6)));
        // Bit for bit: -0.0 is not 0.0, and a state of another length is never found.
        recent.push(&[0.0, 1.0], Vector2::new(0.7, 0.8));
        assert_eq!(recent.get(&[-0.0, 1.0]), None);
        assert_eq!(recent.get(&[3.0]), None);
    }
}
