//! Quasistatic planar pushing (`shared/docs/physics.md`): the ellipsoidal limit surface,
//! Coulomb friction at every pusher contact, the per-object complementarity problem
//! that decides whether each contact separates, sticks or slides, and whether the table
//! keeps a pushed object flat (tipping); objects pushing objects (chains).
//!
//! Everything here is planar and in the object frame: points in metres, velocities in
//! m/s, angular velocity in rad/s. The 3D-to-planar reduction of arm contacts lives in
//! [`crate::contact`].

pub mod chain;
pub mod lcp;
pub mod limit_surface;
pub mod pushing;
pub mod tipping;

pub use chain::{cluster_motion, ClusterContact, ClusterMotion, Pusher};
pub use limit_surface::{Footprint, LimitSurface, LoadedSupport, SupportGrid};
pub use pushing::{object_motion, Jammed, ObjectMotion, PlanarContact};
pub use tipping::{sliding_push_tips, ContactElevation, PusherForce, SupportBalance};
