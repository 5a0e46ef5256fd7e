//! Planning: the planner kinds, the problem a planner searches ([`Problem`]: Static RRT's
//! pins the clutter), the problem as OMPL sees it ([`Model`]) and the one way a found
//! path is finished ([`finish`]), shared by the CLI, the C++ API and `bench`.

mod finish;
mod kind;
mod model;
mod problem;

pub use finish::{finish, FinishSettings, FinishedPath, RobustRequirement, ShortcutReport};
pub use kind::PlannerKind;
pub use model::Model;
pub use problem::Problem;
