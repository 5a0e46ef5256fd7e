//! `robot::collision_matrix`: the self-collision pairs MoveIt's Setup Assistant would
//! leave out, on a robot built so that each verdict follows from its geometry alone.

use crate::common;
use nalgebra::{Isometry3, UnitQuaternion};
use pushplan_model::robot::collision_matrix::{collision_matrix, SkipReason};
use pushplan_model::robot::urdf::load_urdf;
use pushplan_model::robot::{ProjectionSettings, PushingPlane, Robot, RobotKind};

/// base -> a (revolute z, within +-1 mrad) -> b (prismatic z, 1 cm) -> c (prismatic x,
/// [0, 2] m); d hangs from the base (revolute z, held). Geometry (m, link frames):
/// - base: a box over x in [0.9, 1.1], z in [-0.17, -0.07];
/// - a: a box over x in [0.15, 2.0], y and z in [-0.05, 0.05];
/// - b: a sphere of 0.1 at (0, 5, 0), far from everything;
/// - c: a sphere of 0.1 at its origin, (q_c, 0, q_b) in a's frame;
/// - d: a sphere of 0.1 at (0, 0, 0.15).
const ROBOT: &str = "<robot name='matrix'>
  <link name='base'><collision><origin xyz='1.0 0 -0.12'/><geometry><box size='0.2 0.1 0.1'/></geometry></collision></link>
  <link name='a'><collision><origin xyz='1.075 0 0'/><geometry><box size='1.85 0.1 0.1'/></geometry></collision></link>
  <link name='b'><collision><origin xyz='0 5 0'/><geometry><sphere radius='0.1'/></geometry></collision></link>
  <link name='c'><collision><geometry><sphere radius='0.1'/></geometry></collision></link>
  <link name='d'><collision><origin xyz='0 0 0.15'/><geometry><sphere radius='0.1'/></geometry></collision></link>
  <joint name='ja' type='revolute'><parent link='base'/><child link='a'/><axis xyz='0 0 1'/><limit lower='-0.001' upper='0.001' effort='1' velocity='1'/></joint>
  <joint name='jb' type='prismatic'><parent link='a'/><child link='b'/><axis xyz='0 0 1'/><limit lower='0' upper='0.01' effort='1' velocity='1'/></joint>
  <joint name='jc' type='prismatic'><parent link='b'/><child link='c'/><axis xyz='1 0 0'/><limit lower='0' upper='2' effort='1' velocity='1'/></joint>
  <joint name='jd' type='revolute'><parent link='base'/><child link='d'/><axis xyz='0 0 1'/><limit lower='-3' upper='3' effort='1' velocity='1'/></joint>
</robot>";

#[test]
fn pairs_that_collide_at_zero_always_or_never_are_left_out_and_the_others_checked() {
    let scratch = common::Scratch::new("test-collision-matrix");
    let path = scratch.join("matrix.urdf");
    std::fs::write(&path, ROBOT).unwrap();
    let chain = load_urdf(&path, "c", Isometry3::identity()).unwrap();
    let ee = chain.links.iter().position(|l| l.name == "c").unwrap();
    let robot = Robot::new(
        RobotKind::Arm,
        chain,
        ee,
        Isometry3::identity(),
        PushingPlane::new(0.0, UnitQuaternion::identity()),
        ProjectionSettings::default(),
    );
    let samples = 4000;
    let matrix = collision_matrix(&robot, samples, 7);
    let name = |l: usize| robot.chain.links[l].name.as_str();
    let verdict = |x: &str, y: &str| {
        matrix
            .skipped
            .iter()
            .find(|p| {
                let pair = (name(p.a), name(p.b));
                pair == (x, y) || pair == (y, x)
            })
            .map(|p| (p.reason, p.collisions))
    };
    // Adjacent pairs are no candidates: base-a, a-b, b-c, base-d. The other six are.
    assert_eq!(matrix.candidates, 6);
    // c overlaps a's box once q_c + 0.1 > 0.15: in 97.5 % of q_c in [0, 2] (>= 95 %),
    // and not at q_c = 0.
    let (reason, n) = verdict("a", "c").expect("a-c is left out");
    assert_eq!(reason, SkipReason::Always);
    let share = n as f64 / samples as f64;
    assert!((share - 0.975).abs() < 0.01, "{share}");
    // c's sphere and d's meet at the zero configuration (0.15 m apart, radii 0.1 + 0.1),
    // and only for q_c below about 0.13: rarely, but at zero.
    let (reason, n) = verdict("c", "d").expect("c-d is left out");
    assert_eq!(reason, SkipReason::AtZero);
    assert!(n > 0 && (n as f64) < 0.1 * samples as f64, "{n}");
    // b is 5 m out; d's sphere stays 0.18 m from a's box: never.
    for (x, y) in [("base", "b"), ("b", "d"), ("a", "d")] {
        assert_eq!(verdict(x, y), Some((SkipReason::Never, 0)), "{x}-{y}");
    }
    // c reaches the base's box only for q_c near 1 m (about a sixth of the samples):
    // checked.
    assert_eq!(verdict("base", "c"), None);
    assert_eq!(matrix.skipped.len(), 5);
    // The same seed gives the same matrix.
    assert_eq!(collision_matrix(&robot, samples, 7), matrix);
}
