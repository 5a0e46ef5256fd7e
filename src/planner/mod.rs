//! The search's side of the model: the planners' trees' nearest neighbours in the model's
//! metric ([`NearestTree`]), push headings, perturbed worlds, the tool points of recent
//! propagations and search statistics. The bridge hands these to C++.

mod heading;
mod nearest;
mod particles;
mod recent_tools;
mod stats;

pub use heading::{PushHeading, PushTarget};
pub use nearest::NearestTree;
pub use particles::ParticleWorlds;
pub use recent_tools::RecentTools;
pub use stats::{SearchCounter, SearchStats};
