//! FCL behind a cxx bridge: the independent oracle of pushplan's collision tests
//! (`tests/integration/fcl_oracle.rs`). A crate of its own, a dev-dependency of pushplan,
//! so that only test builds compile and link FCL.

#[cxx::bridge(namespace = "pushplan::oracle")]
pub mod fcl {
    /// A shape and its pose, as FCL is given it.
    pub struct FclShape {
        /// box, cylinder, sphere, capsule or prism
        pub kind: String,
        /// box: x y z sizes; cylinder, capsule: radius, length; sphere: radius; prism: height
        pub dims: Vec<f64>,
        /// prism footprint, x y pairs
        pub vertices: Vec<f64>,
        /// x y z qw qx qy qz
        pub pose: Vec<f64>,
    }

    /// FCL's answers for a pair of shapes.
    pub struct FclResult {
        pub collide: bool,
        pub distance: f64,
        pub depth: f64,
    }

    unsafe extern "C++" {
        include!("pushplan-fcl-oracle/src/fcl_oracle.h");
        /// Collision verdict, separation distance and penetration depth of two shapes by FCL.
        fn fcl_query(a: &FclShape, b: &FclShape) -> FclResult;
    }
}
