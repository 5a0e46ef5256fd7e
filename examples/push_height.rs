//! How faithful is the planar model at height? One off-centre push of the benchmark's
//! goal box (0.102 m square, 0.215 m tall, 1 kg, mu_g 0.4, mu_c 0.3) by a small round
//! pusher, 1 cm across, at several heights above the table: the planar model's outcome
//! with a uniform support pressure and with the pressure the push loads onto the leading
//! edge (`physics.pressure_shift`, the default), beside the 3D engine's (`pushplan
//! execute`'s world, the pusher driven along the model's motion).
//!
//!   cargo run --release --example push_height -- [OFFSET_M] [TRAVEL_M]
//!
//! OFFSET_M: the push line's distance from the box's centre line (default 0.03 m);
//! TRAVEL_M: how far the pusher moves, at 0.1 m/s (default 0.03 m).

use nalgebra::DVector;
use pushplan::planning::execute::rapier::RapierWorld;
use pushplan::planning::execute::Engine;
use pushplan::planning::path::{simulate, PathControl};
use pushplan::{EeAction, Pose2, Propagator, Scene};
use std::path::Path;

fn scene(height: f64, offset: f64, pressure_shift: bool) -> Scene {
    let yaml = format!(
        "robot:
  type: planar_hand
  shape: {{type: cylinder, radius: 0.005, height: 0.008}}
  start: [0.415, {offset}, 0.0]
  height: {height}
table: {{height: 0.76, x: [0.27, 1.03], y: [-0.6, 0.6]}}
objects:
  - {{name: box, shape: {{type: box, size: [0.102, 0.102, 0.215]}}, pose: [0.4715, 0.0, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.3}}
goal: {{object: box, center: [0.9, 0.3], radius: 0.1}}
physics: {{tipping_margin: 0.0, pressure_shift: {pressure_shift}}}
"
    );
    Scene::from_yaml(&yaml, Path::new("examples/push_height.yaml")).expect("a valid scene")
}

/// The box's pose after the model pushes it `travel` m, and the pusher's joint path.
fn model_push(scene: &Scene, travel: f64) -> Result<(Pose2, Vec<DVector<f64>>), String> {
    let push = PathControl {
        action: EeAction::planar(0.1, 0.0, 0.0),
        steps: (travel / 0.1 / scene.planner.step).round() as usize,
    };
    let path = simulate(&mut Propagator::new(scene), &scene.start, &[push], true);
    match path.stopped_by {
        Some((_, why)) => Err(why.to_string()),
        None => Ok((
            path.final_state().objects[0],
            path.step_states.into_iter().map(|s| s.q).collect(),
        )),
    }
}

fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("numbers: OFFSET_M TRAVEL_M"))
        .collect();
    let offset = args.first().copied().unwrap_or(0.03);
    let travel = args.get(1).copied().unwrap_or(0.03);
    println!("push {travel} m at 0.1 m/s, {offset} m off the box's centre line");
    println!("| pusher height (m) | yaw: uniform / loaded / 3D (rad) | y: uniform / loaded / 3D (mm) | distance from the 3D pose: uniform / loaded (mm) |");
    println!("|---|---|---|---|");
    for height in [0.005, 0.025, 0.05, 0.075, 0.1] {
        let outcome = |shift| model_push(&scene(height, offset, shift), travel);
        let (Ok((uniform, _)), Ok((loaded, path))) = (outcome(false), outcome(true)) else {
            println!("| {height} | the model stops the push | |");
            continue;
        };
        // The same pusher path in 3D.
        let scene = scene(height, offset, true);
        let mut poses = Vec::new();
        scene.robot.chain.forward_kinematics(&path[0], &mut poses);
        let mut world = RapierWorld::new(&scene, &scene.start.objects, &poses);
        world.follow(&scene.robot.chain, &path, scene.planner.step);
        let engine = world.object_pose2(0);
        let off = |p: &Pose2| 1e3 * (p.translation() - engine.translation()).norm();
        println!(
            "| {height} | {:.3} / {:.3} / {:.3} | {:.1} / {:.1} / {:.1} | {:.1} / {:.1} |",
            uniform.theta,
            loaded.theta,
            engine.theta,
            1e3 * uniform.y,
            1e3 * loaded.y,
            1e3 * engine.y,
            off(&uniform),
            off(&loaded)
        );
    }
}
