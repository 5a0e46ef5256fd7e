//! What the CLI, the C++ API and the benchmark share about planners.

mod kind;

pub use kind::PlannerKind;
