//! Holds one end-effector action in a scene and reports what the physics does.
//!
//! ```text
//! cargo run --release --example push -- [SCENE] [VX VY OMEGA_Z DURATION]
//! ```
//! Defaults: the Fig. 1 clutter scene, the hand pushing forward at 0.2 m/s for 2 s.
//! Prints the tool path, which links pushed which objects, and where every object went.

use pushplan::{EeAction, Propagator, Scene};
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scene_path = args
        .first()
        .map_or("scenes/herb_fig1_clutter.yaml", String::as_str);
    let numbers: Result<Vec<f64>, _> = args.iter().skip(1).map(|a| a.parse::<f64>()).collect();
    let numbers = match numbers {
        Ok(n) if n.is_empty() => vec![0.2, 0.0, 0.0, 2.0],
        Ok(n) if n.len() == 4 && n.iter().all(|v| v.is_finite()) && n[3] >= 0.0 => n,
        _ => {
            eprintln!(
                "usage: push [SCENE] [VX VY OMEGA_Z DURATION]  (m/s, m/s, rad/s, s; duration >= 0)"
            );
            return ExitCode::from(2);
        }
    };
    let scene = match Scene::load(scene_path) {
        Ok(scene) => scene,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let action = EeAction::planar(numbers[0], numbers[1], numbers[2]);
    let mut propagator = Propagator::new(&scene);
    let started = std::time::Instant::now();
    let run = propagator.propagate(&scene.start, &action, numbers[3]);
    let elapsed = started.elapsed();

    let robot = &scene.robot;
    let tool = |q| robot.tool_pose(&robot.link_poses(q)).translation.vector;
    let (from, to) = (tool(&scene.start.q), tool(&run.state.q));
    println!(
        "scene '{}': {} objects, action ({}, {}, {}) for {} s",
        scene.name,
        scene.objects.len(),
        numbers[0],
        numbers[1],
        numbers[2],
        numbers[3]
    );
    println!(
        "propagated {} steps ({:.2} s) in {:.2} ms: {}",
        run.steps,
        run.duration,
        elapsed.as_secs_f64() * 1e3,
        run.stopped_by
            .as_ref()
            .map_or("full duration valid".to_string(), |e| format!(
                "stopped: {e}"
            ))
    );
    println!(
        "tool: ({:.3}, {:.3}, {:.3}) -> ({:.3}, {:.3}, {:.3}) m",
        from.x, from.y, from.z, to.x, to.y, to.z
    );
    let mut pairs: Vec<(usize, usize, usize)> = Vec::new(); // link, object, steps
    for push in run.contacts.iter().flatten() {
        match pairs
            .iter_mut()
            .find(|(l, o, _)| *l == push.link && *o == push.object)
        {
            Some(p) => p.2 += 1,
            None => pairs.push((push.link, push.object, 1)),
        }
    }
    for (link, object, steps) in pairs {
        println!(
            "  {} pushed {} for {:.2} s",
            robot.chain.links[link].name,
            scene.objects[object].name,
            steps as f64 * propagator.step_size()
        );
    }
    for (i, object) in scene.objects.iter().enumerate() {
        let (a, b) = (scene.start.objects[i], run.state.objects[i]);
        let moved = (b.translation() - a.translation()).norm();
        println!(
            "  {:<10} ({:.3}, {:.3}, {:+.3}) -> ({:.3}, {:.3}, {:+.3})  moved {:.3} m",
            object.name, a.x, a.y, a.theta, b.x, b.y, b.theta, moved
        );
    }
    let goal = if scene.goal.is_satisfied(&run.state) {
        "reached"
    } else {
        "not reached"
    };
    println!(
        "goal {goal} ({:.3} from the goal region)",
        scene.goal.distance(&run.state).max(0.0)
    );
    ExitCode::SUCCESS
}
