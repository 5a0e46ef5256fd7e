//! Planning: the planner kinds, the problem a planner searches ([`Problem`]: Static RRT's
//! pins the clutter), the problem as OMPL sees it ([`Model`]) and the one way a found
//! path is finished ([`finish`]), shared by the CLI, the C++ API and `bench`; the
//! planners' trees' nearest neighbours in the model's metric ([`NearestTree`]).

mod finish;
mod heading;
mod kind;
mod model;
mod nearest;
mod particles;
mod problem;
mod recent_tools;
mod stats;

pub use finish::{
    deadline, finish, FinishSettings, FinishedPath, RobustRequirement, ShortcutReport,
};
pub use heading::{PushHeading, PushTarget};
pub use kind::PlannerKind;
pub use model::Model;
pub use nearest::NearestTree;
pub use particles::ParticleWorlds;
pub use problem::Problem;
pub use stats::{SearchCounter, SearchStats};
