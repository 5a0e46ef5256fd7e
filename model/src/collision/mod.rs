//! Collision geometry and the geometric queries the model needs.
//!
//! Shapes are parry shapes placed by a local pose on a body (link, object, obstacle);
//! queries take world poses. Shapes and queries are kept apart: `geometry` builds
//! shapes, `query` answers questions about pairs of them. Two movable objects are
//! upright prisms on one table, so `footprint` answers their questions in 2D, exactly.

pub mod footprint;
pub mod geometry;
pub mod query;
pub mod section;

pub use geometry::{Geometry, Primitive};
