//! The search's side of the model: the planners' trees' nearest neighbours in the model's
//! metric ([`NearestTree`]), push headings, perturbed worlds, the tool points of recent
//! propagations and search statistics, which the bridge hands to C++; and the search
//! the applications call ([`Search`]), which the bridge implements, and a scene planned
//! end to end with it ([`plan_scene`]) and a plan file made again from what it records
//! ([`remake`]).

pub mod closed_loop;
mod heading;
mod nearest;
mod particles;
pub mod plan_scene;
mod recent_tools;
pub mod remake;
mod search;
mod stats;

pub use heading::{PushHeading, PushTarget};
pub use nearest::NearestTree;
pub use particles::ParticleWorlds;
pub use recent_tools::RecentTools;
pub use search::{Found, ReachSettings, Reached, Search, SearchProgress, SearchSummary};
pub use stats::{SearchCounter, SearchStats};
