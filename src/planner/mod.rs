//! The search's side of the model: the problem as OMPL's planners see it ([`Model`]),
//! the planners' trees' nearest neighbours in the model's metric ([`NearestTree`]), push
//! headings, perturbed worlds and search statistics. The bridge hands these to C++.

mod heading;
mod model;
mod nearest;
mod particles;
mod recent_tools;
mod stats;

pub use heading::{PushHeading, PushTarget};
pub use model::Model;
pub use nearest::NearestTree;
pub use particles::ParticleWorlds;
pub use stats::{SearchCounter, SearchStats};
