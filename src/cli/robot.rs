//! `pushplan robot`: a scene's robot as a user writing `start_joints` needs to see it —
//! its joints and limits, the tool pose of a configuration (forward kinematics) and
//! configurations that put the tool on a point of the pushing plane (inverse kinematics).

use nalgebra::{DVector, Isometry3};
use pushplan::random::SplitMix64;
use pushplan::robot::collision_matrix::{collision_matrix, SkipReason, ALWAYS_SHARE};
use pushplan::robot::{IkSettings, Robot};
use pushplan::scene::Scene;
use pushplan::state::State;
use std::path::Path;
use std::process::ExitCode;

/// What `pushplan robot` is asked.
pub struct RobotQuery {
    /// A configuration to report (default: the scene's start).
    pub joints: Option<Vec<f64>>,
    /// A tool target on the pushing plane: x, y (m, world) and optionally yaw (rad).
    pub reach: Option<Vec<f64>>,
    /// Inverse kinematics seeds tried for `reach` (the start first, then random ones).
    pub tries: usize,
    /// Seed of the random IK seeds.
    pub seed: u64,
}

/// Most distinct configurations `--reach` prints.
const MAX_SOLUTIONS: usize = 5;

/// How far inside its limits (rad or m) each joint of a printed solution stays.
const LIMIT_CLEARANCE: f64 = 1e-3;

/// Two IK solutions closer than this in every joint (rad or m) are the same one.
const SAME_SOLUTION: f64 = 1e-3;

pub fn robot(scene_path: &Path, query: &RobotQuery) -> Result<ExitCode, String> {
    let (scene, start_problem) = Scene::load_any_start(scene_path).map_err(|e| e.to_string())?;
    let robot = &scene.robot;
    let chain = &robot.chain;
    println!(
        "robot: {} joints, end effector '{}'",
        robot.dof(),
        chain.links[robot.ee_link].name
    );
    println!("joints (limits, start):");
    let limits = chain.limits();
    for (i, (lower, upper)) in limits.iter().enumerate() {
        let joint = chain.dof_joint(i);
        println!(
            "  {:<12} [{lower:.4}, {upper:.4}] {}  start {:.4}",
            joint.name,
            unit(robot, i),
            scene.start.q[i]
        );
    }
    let solid: Vec<&str> = robot
        .solid_links()
        .map(|l| chain.links[l].name.as_str())
        .collect();
    println!("links with collision geometry: {}", solid.join(", "));
    println!(
        "pushing plane: tool point at z = {:.4} m ({:.4} m above the table top), tilted as its orientation_rpy",
        robot.plane.height,
        robot.plane.height - scene.table.top
    );

    let q = match &query.joints {
        Some(values) => {
            if values.len() != robot.dof() {
                return Err(format!(
                    "--joints: {} values given, the robot has {} joints",
                    values.len(),
                    robot.dof()
                ));
            }
            if let Some(v) = values.iter().find(|v| !v.is_finite()) {
                return Err(format!("--joints: {v} is not a finite number"));
            }
            println!("\nconfiguration (--joints):");
            DVector::from_column_slice(values)
        }
        None => {
            println!("\nconfiguration (the scene's start, on its plane):");
            if let Some(problem) = &start_problem {
                println!("  the scene's start is refused: {problem}");
            }
            scene.start.q.clone()
        }
    };
    report_configuration(&scene, &q);

    if let Some(reach) = &query.reach {
        let target = reach_target(&scene, reach)?;
        let t = target.translation.vector;
        println!(
            "\nconfigurations with the tool at ({:.4}, {:.4}, {:.4}) m, yaw {:.4} rad:",
            t.x,
            t.y,
            t.z,
            reach.get(2).copied().unwrap_or(0.0)
        );
        let solutions = reach_configurations(&scene, &target, &q, query);
        if solutions.is_empty() {
            println!(
                "  none found from {} seeds: the point may be out of reach at this tilt",
                query.tries
            );
            return Ok(ExitCode::from(1));
        }
        for (q, validity) in &solutions {
            let values: Vec<String> = q.iter().map(|v| format!("{v:.4}")).collect();
            let note = match validity {
                Ok(()) => "valid".to_string(),
                Err(reason) => format!("invalid: {reason}"),
            };
            println!("  start_joints: [{}]   # {note}", values.join(", "));
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn unit(robot: &Robot, dof: usize) -> &'static str {
    match robot.chain.dof_joint(dof).kind {
        pushplan::robot::JointKind::Prismatic => "m",
        _ => "rad",
    }
}

/// The tool pose of `q`, its distance from the pushing plane and its validity with the
/// scene's objects at their start poses.
fn report_configuration(scene: &Scene, q: &DVector<f64>) {
    let robot = &scene.robot;
    if let Err(i) = robot.chain.within_limits(q) {
        println!(
            "  joint '{}' = {:.4} is outside its limits",
            robot.chain.dof_joint(i).name,
            q[i]
        );
    }
    let poses = robot.link_poses(q);
    let tool = robot.tool_pose(&poses);
    let (roll, pitch, yaw) = tool.rotation.euler_angles();
    let p = tool.translation.vector;
    println!(
        "  tool at xyz [{:.4}, {:.4}, {:.4}] m, rpy [{roll:.4}, {pitch:.4}, {yaw:.4}] rad",
        p.x, p.y, p.z
    );
    let (height, tilt) = robot.plane.error(&tool);
    println!("  off the pushing plane by {height:.4} m (height) and {tilt:.4} rad (tilt)");
    match pushplan::validity::check_state(scene, &state_with(scene, q)) {
        Ok(()) => println!("  valid"),
        Err(reason) => println!("  invalid: {reason}"),
    }
}

fn state_with(scene: &Scene, q: &DVector<f64>) -> State {
    State {
        q: q.clone(),
        objects: scene.start.objects.clone(),
    }
}

/// The tool pose on the pushing plane at (x, y) with the plane's tilt turned by yaw.
fn reach_target(scene: &Scene, reach: &[f64]) -> Result<Isometry3<f64>, String> {
    if !(2..=3).contains(&reach.len()) {
        return Err(format!(
            "--reach: X,Y or X,Y,YAW (m, m, rad), got {} values",
            reach.len()
        ));
    }
    if let Some(v) = reach.iter().find(|v| !v.is_finite()) {
        return Err(format!("--reach: {v} is not a finite number"));
    }
    let yaw = reach.get(2).copied().unwrap_or(0.0);
    Ok(scene
        .robot
        .plane
        .tool_pose_at(&pushplan::math::Pose2::new(reach[0], reach[1], yaw)))
}

/// Distinct configurations reaching `target`, from `first` and then random seeds within
/// the limits, valid ones first, each with its validity.
fn reach_configurations(
    scene: &Scene,
    target: &Isometry3<f64>,
    first: &DVector<f64>,
    query: &RobotQuery,
) -> Vec<(DVector<f64>, Result<(), pushplan::Invalid>)> {
    let robot = &scene.robot;
    let limits = robot.chain.limits();
    let mut rng = SplitMix64::new(query.seed);
    let settings = IkSettings::default();
    let mut found: Vec<DVector<f64>> = Vec::new();
    for attempt in 0..query.tries {
        let seed = if attempt == 0 {
            first.clone()
        } else {
            robot.chain.random_configuration(&mut rng)
        };
        let Some(q) = robot.reach_tool_pose(target, &seed, &settings) else {
            continue;
        };
        // As printed (4 decimals), and clear of the limits: a start at a limit cannot move
        // that joint one way, and the loader's projection onto the plane may push it over.
        let q = q.map(|v| (v * 1e4).round() / 1e4);
        let inside = q
            .iter()
            .zip(&limits)
            .all(|(v, (lo, hi))| *v >= lo + LIMIT_CLEARANCE && *v <= hi - LIMIT_CLEARANCE);
        if inside && found.iter().all(|f| (f - &q).amax() > SAME_SOLUTION) {
            found.push(q);
        }
    }
    let mut solutions: Vec<_> = found
        .into_iter()
        .map(|q| {
            let validity = pushplan::validity::check_state(scene, &state_with(scene, &q));
            (q, validity)
        })
        .collect();
    // Valid first; otherwise in the order found (the start's neighbourhood first).
    solutions.sort_by_key(|(_, validity)| validity.is_err());
    solutions.truncate(MAX_SOLUTIONS);
    solutions
}

/// `pushplan robot SCENE --allowed-collisions`: the link pairs to leave out of the
/// self-collision checks, found as MoveIt's Setup Assistant finds them
/// ([`collision_matrix`]), printed as the scene's `allowed_collisions` (YAML to paste,
/// each pair with its reason). Pairs the scene already allows are marked so.
pub fn allowed_collisions_of(
    scene_path: &Path,
    samples: usize,
    seed: u64,
) -> Result<ExitCode, String> {
    let (scene, _) = Scene::load_any_start(scene_path).map_err(|e| e.to_string())?;
    let robot = &scene.robot;
    let names = |l: usize| robot.chain.links[l].name.as_str();
    let started = std::time::Instant::now();
    let matrix = collision_matrix(robot, samples, seed);
    let count = |reason: SkipReason| matrix.skipped.iter().filter(|p| p.reason == reason).count();
    println!(
        "# Self-collision pairs of '{}' ({} links with geometry; adjacent links are never checked),",
        scene_path.display(),
        robot.solid_links().count()
    );
    println!(
        "# as MoveIt's Setup Assistant finds them: of {} pairs, {} collide at the zero configuration,",
        matrix.candidates,
        count(SkipReason::AtZero)
    );
    println!(
        "# {} in at least {:.0} % of {samples} random configurations (seed {seed}), {} in none ({:.1} s).",
        count(SkipReason::Always),
        100.0 * ALWAYS_SHARE,
        count(SkipReason::Never),
        started.elapsed().as_secs_f64()
    );
    println!(
        "# The {} others stay checked. Pairs in none of the samples may still meet in a configuration",
        matrix.candidates - matrix.skipped.len()
    );
    println!("# the samples missed: more --samples make that rarer.");
    if matrix.skipped.is_empty() {
        println!("allowed_collisions: []");
        return Ok(ExitCode::SUCCESS);
    }
    println!("allowed_collisions:");
    let checked = &robot.self_collision_pairs;
    for pair in &matrix.skipped {
        let already = !checked.contains(&(pair.a, pair.b));
        println!(
            "  - [{}, {}]  # {} ({} of {samples}){}",
            names(pair.a),
            names(pair.b),
            pair.reason.name(),
            pair.collisions,
            if already {
                "; the scene allows it already"
            } else {
                ""
            }
        );
    }
    Ok(ExitCode::SUCCESS)
}
