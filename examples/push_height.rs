//! How faithful is the planar model at height? One off-centre push of the benchmark's
//! goal box (0.102 m square, 0.215 m tall, 1 kg, mu_g 0.4, mu_c 0.3) by a small round
//! pusher, 1 cm across, at several heights above the table: the planar model's outcome
//! beside the 3D engine's (`pushplan execute`'s world, the pusher driven along the
//! model's motion). The planar model has one answer for every height (its support
//! pressure stays uniform); in 3D a push at height loads the box's leading edge.
//!
//!   cargo run --release --example push_height -- [OFFSET_M] [TRAVEL_M]
//!
//! OFFSET_M: the push line's distance from the box's centre line (default 0.03 m);
//! TRAVEL_M: how far the pusher moves, at 0.1 m/s (default 0.03 m).

use nalgebra::DVector;
use pushplan::execute::world::{World, STEP};
use pushplan::{EeAction, Propagator, Scene};
use std::path::Path;

fn scene(height: f64, offset: f64) -> Scene {
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
physics: {{tipping_margin: 0.0}}
"
    );
    Scene::from_yaml(&yaml, Path::new("examples/push_height.yaml")).expect("a valid scene")
}

fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("numbers: OFFSET_M TRAVEL_M"))
        .collect();
    let offset = args.first().copied().unwrap_or(0.03);
    let travel = args.get(1).copied().unwrap_or(0.03);
    let push = EeAction::planar(0.1, 0.0, 0.0);
    println!("push {travel} m at 0.1 m/s, {offset} m off the box's centre line");
    println!("| pusher height (m) | yaw: model (rad) | yaw: 3D (rad) | 3D / model | y: model (mm) | y: 3D (mm) |");
    println!("|---|---|---|---|---|---|");
    for height in [0.005, 0.025, 0.05, 0.075, 0.1] {
        let scene = scene(height, offset);
        // The model, one step at a time, keeping the pusher's path.
        let mut propagator = Propagator::new(&scene);
        let steps = (travel / 0.1 / scene.planner.step).round() as usize;
        let mut state = scene.start.clone();
        let mut path = vec![state.q.clone()];
        for _ in 0..steps {
            let run = propagator.propagate_steps(&state, &push, 1);
            if let Some(why) = run.stopped_by {
                println!("| {height} | stopped: {why} | | | | |");
                break;
            }
            state = run.state;
            path.push(state.q.clone());
        }
        let model = state.objects[0];
        // The same pusher path in 3D, interpolated at the engine's 1 kHz.
        let mut poses = Vec::new();
        scene.robot.chain.forward_kinematics(&path[0], &mut poses);
        let mut world = World::new(&scene, &scene.start.objects, &poses);
        let per_step = (scene.planner.step / STEP).round() as usize;
        for pair in path.windows(2) {
            for j in 1..=per_step {
                let f = j as f64 / per_step as f64;
                let q: DVector<f64> = &pair[0] * (1.0 - f) + &pair[1] * f;
                scene.robot.chain.forward_kinematics(&q, &mut poses);
                world.move_arm(&poses);
                world.step();
            }
        }
        let engine = world.object_pose2(0);
        println!(
            "| {height} | {:.3} | {:.3} | {:.2} | {:.1} | {:.1} |",
            model.theta,
            engine.theta,
            engine.theta / model.theta,
            1e3 * model.y,
            1e3 * engine.y
        );
    }
}
