//! Planning: the planner kinds, the problem as OMPL sees it ([`Model`]) and the one way
//! a found path is finished ([`finish`]), shared by the CLI, the C++ API and `bench`.

mod finish;
mod kind;
mod model;

pub use finish::{finish, FinishSettings, FinishedPath, RobustRequirement, ShortcutReport};
pub use kind::PlannerKind;
pub use model::{guarded, Model};
