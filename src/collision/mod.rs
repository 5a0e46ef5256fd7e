//! Collision geometry and the geometric queries the model needs.
//!
//! Shapes are parry shapes placed by a local pose on a body (link, object, obstacle);
//! queries take world poses. Shapes and queries are kept apart: `geometry` builds
//! shapes, `query` answers questions about pairs of them.

pub mod geometry;
pub mod query;
pub mod section;

pub use geometry::{Geometry, Primitive};
