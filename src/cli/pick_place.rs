//! `pushplan pick-place`: move one object to a placement with the arm's hand through the
//! manipulation graph and its two-level Fuzzy PRM, check the path, write it.

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion};
use pushplan::math::Pose2;
use pushplan::planning::manipulation::graph::INITIAL_PROBABILITY;
use pushplan::planning::manipulation::{
    EdgeKind, ManipulationGraph, Motion, PickAndPlace, Settings,
};
use pushplan::scene::{Goal, Scene};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::process::ExitCode;

/// The `pick-place` command's options.
pub struct PickPlaceOptions {
    pub object: String,
    /// The placement: x, y (m), yaw (rad); default the scene's goal disc centre at the
    /// object's start yaw.
    pub to: Option<Vec<f64>>,
    pub grasps: usize,
    pub seed: u64,
    pub budget: usize,
    /// Also draw the path into this folder.
    pub render: Option<std::path::PathBuf>,
}

/// The format `pick-place` files name.
pub const PICK_PLACE_FORMAT: &str = "pushplan-pick-place/1";

/// The file `pick-place` writes.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct PickPlaceFile {
    /// Always [`PICK_PLACE_FORMAT`].
    format: String,
    scene: String,
    object: String,
    /// Placements `[x, y, yaw]`: the start, the goal.
    placements: Vec<[f64; 3]>,
    /// Grasps: the tool in the object frame, `[x, y, z, qx, qy, qz, qw]` (m; a unit
    /// quaternion: roll, pitch and yaw lose the rotation at a quarter turn of pitch,
    /// where side grasps are).
    grasps: Vec<[f64; 7]>,
    segments: Vec<SegmentRecord>,
    graph: GraphRecord,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SegmentRecord {
    /// "transit" (the object rests at `placement`) or "transfer" (carried in `grasp`
    /// from placement `from` to `to`).
    motion: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    placement: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    grasp: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    from: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    to: Option<usize>,
    /// Joint values joined by straight lines.
    waypoints: Vec<Vec<f64>>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct GraphRecord {
    nodes: usize,
    transfer_edges: usize,
    transit_edges: usize,
    low_level_runs: usize,
    validity_checks: usize,
}

pub fn pick_place(
    scene_path: &Path,
    run: &PickPlaceOptions,
    out: &Path,
) -> Result<ExitCode, String> {
    let scene = Scene::load(scene_path).map_err(|e| e.to_string())?;
    let object = pushplan::planning::reach::graspable_object(&scene, &run.object)?;
    let start = scene.start.objects[object];
    let goal = match (&run.to, &scene.goal) {
        (Some(v), _) => match v.as_slice() {
            [x, y] => Pose2::new(*x, *y, start.theta),
            [x, y, yaw] => Pose2::new(*x, *y, *yaw),
            _ => return Err(format!("--to is X,Y[,YAW], got {} values", v.len())),
        },
        (None, Goal::ObjectInDisc { center, .. }) => Pose2::new(center.x, center.y, start.theta),
        (None, _) => return Err("--to X,Y[,YAW] is needed: the scene's goal is no disc".into()),
    };
    if !(goal.x.is_finite() && goal.y.is_finite() && goal.theta.is_finite()) {
        return Err("--to must be finite".into());
    }
    pushplan::output::check_writable(out)?;
    let problem = PickAndPlace::new(&scene, &scene.start, object, goal, run.grasps, run.seed)?;
    let settings = Settings {
        budget: run.budget,
        seed: run.seed,
        ..Settings::default()
    };
    let started = std::time::Instant::now();
    let mut graph = ManipulationGraph::new(problem.clone(), settings);
    let count = |kind| graph.edges.iter().filter(|e| e.kind == kind).count();
    let (transfers, transits) = (count(EdgeKind::Transfer), count(EdgeKind::Transit));
    eprintln!(
        "manipulation graph: {} nodes (the start, and {} of the {} grasp-placement pairs inverse kinematics reaches validly), {transfers} transfer and {transits} transit edges at probability {INITIAL_PROBABILITY}",
        graph.nodes.len(),
        graph.nodes.len() - 1,
        problem.grasps.len() * problem.placements.len(),
    );
    let found = graph.solve();
    println!(
        "{} in {:.2} s: {} low-level Fuzzy PRM runs, {} validity checks",
        if found.is_some() {
            "solved"
        } else {
            "not solved"
        },
        started.elapsed().as_secs_f64(),
        graph.runs,
        graph.total_time
    );
    let Some(segments) = found else {
        if graph.runs == 0 {
            println!(
                "no path in the manipulation graph: no grasp holds the object validly at both placements (more --grasps may find one)"
            );
        }
        return Ok(ExitCode::FAILURE);
    };
    problem
        .check(&segments)
        .map_err(|why| format!("internal error: the path found does not check: {why}"))?;
    let file = PickPlaceFile {
        format: PICK_PLACE_FORMAT.into(),
        scene: pushplan::planning::plan_file::PlanFile::scene_reference(scene_path, out),
        object: run.object.clone(),
        placements: problem
            .placements
            .iter()
            .map(|p| [p.x, p.y, p.theta])
            .collect(),
        grasps: problem.grasps.iter().map(grasp_record).collect(),
        segments: segments
            .iter()
            .map(|s| {
                let waypoints = s.waypoints.iter().map(|q| q.as_slice().to_vec()).collect();
                match s.motion {
                    Motion::Transit { placement } => SegmentRecord {
                        motion: "transit".into(),
                        placement: Some(placement),
                        grasp: None,
                        from: None,
                        to: None,
                        waypoints,
                    },
                    Motion::Transfer { grasp, from, to } => SegmentRecord {
                        motion: "transfer".into(),
                        placement: None,
                        grasp: Some(grasp),
                        from: Some(from),
                        to: Some(to),
                        waypoints,
                    },
                }
            })
            .collect(),
        graph: GraphRecord {
            nodes: graph.nodes.len(),
            transfer_edges: transfers,
            transit_edges: transits,
            low_level_runs: graph.runs,
            validity_checks: graph.total_time,
        },
    };
    for s in &file.segments {
        println!("  {} through {} waypoints", s.motion, s.waypoints.len());
    }
    println!("checked: every line valid at 0.02 rad, grasps held at both placements");
    let text = serde_json::to_string_pretty(&file).map_err(|e| e.to_string())?;
    pushplan::output::write_whole(out, text + "\n")?;
    println!("pick-and-place path written to {}", out.display());
    if let Some(dir) = &run.render {
        // Frames one Transit step (0.02 rad) apart, drawn 0.02 s apart.
        let (states, control_starts) = problem.states(&segments);
        let film = pushplan::render::Film {
            contacts: vec![Vec::new(); states.len() - 1],
            states,
            control_starts,
            dt: 0.02,
            scene: problem.scene.clone(),
            executed: Vec::new(),
        };
        let files = pushplan::render::write_pictures(&film, dir, &[])?;
        for path in [files.snapshots, files.timeline, files.animation] {
            println!("wrote {}", path.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// `pushplan check` of a pick-and-place file: its path checked again in its scene, as
/// `pick-place` checked it before writing it.
pub fn check_pick_place(path: &Path) -> Result<ExitCode, String> {
    let text = pushplan::input::read_text(path, pushplan::input::MAX_PLAN_BYTES)
        .map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
    let file: PickPlaceFile =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let scene_path = path.parent().unwrap_or(Path::new(".")).join(&file.scene);
    let scene = Scene::load(&scene_path).map_err(|e| e.to_string())?;
    let object = pushplan::planning::reach::graspable_object(&scene, &file.object)?;
    let placement = |i: usize| file.placements.get(i).copied();
    let problem = PickAndPlace {
        object,
        placements: file
            .placements
            .iter()
            .map(|p| Pose2::new(p[0], p[1], p[2]))
            .collect(),
        grasps: file.grasps.iter().map(grasp_of_record).collect(),
        start: scene.start.clone(),
        scene,
    };
    let bad = |i: usize, what: &str| format!("{}: segments[{i}]: {what}", path.display());
    let mut segments = Vec::new();
    for (i, s) in file.segments.iter().enumerate() {
        let motion = match (s.motion.as_str(), s.placement, s.grasp, s.from, s.to) {
            ("transit", Some(placement), None, None, None) => Motion::Transit { placement },
            ("transfer", None, Some(grasp), Some(from), Some(to)) => {
                Motion::Transfer { grasp, from, to }
            }
            _ => {
                return Err(bad(
                    i,
                    "a transit with its placement, or a transfer with grasp, from and to",
                ))
            }
        };
        let indices_exist = match motion {
            Motion::Transit { placement: p } => placement(p).is_some(),
            Motion::Transfer { grasp, from, to } => {
                grasp < problem.grasps.len() && placement(from).is_some() && placement(to).is_some()
            }
        };
        if !indices_exist {
            return Err(bad(i, "names a placement or grasp the file does not have"));
        }
        let dof = problem.scene.robot.dof();
        if s.waypoints
            .iter()
            .any(|q| q.len() != dof || q.iter().any(|v| !v.is_finite()))
        {
            return Err(bad(
                i,
                &format!("waypoints must be {dof} finite joint values"),
            ));
        }
        segments.push(pushplan::planning::manipulation::Segment {
            motion,
            waypoints: s
                .waypoints
                .iter()
                .map(|q| nalgebra::DVector::from_column_slice(q))
                .collect(),
        });
    }
    if problem.placements.len() < 2 || problem.placements[0] != problem.start.objects[object] {
        return Err(format!(
            "{}: placements: the first must be the object's start in the scene, then the goal",
            path.display()
        ));
    }
    match problem.check(&segments) {
        Ok(()) => {
            println!(
                "{}: {} segments; every line valid at 0.02 rad, grasps held at both placements, the object ends at the goal placement\npick-and-place OK",
                path.display(),
                segments.len()
            );
            Ok(ExitCode::SUCCESS)
        }
        Err(why) => {
            println!("{}: {why}\npick-and-place FAILED", path.display());
            Ok(ExitCode::FAILURE)
        }
    }
}

/// A grasp `X_OE` as the file holds it.
fn grasp_record(x: &Isometry3<f64>) -> [f64; 7] {
    let (t, q) = (x.translation.vector, x.rotation.into_inner());
    [t.x, t.y, t.z, q.i, q.j, q.k, q.w]
}

/// A grasp from the file (its quaternion normalised).
fn grasp_of_record(g: &[f64; 7]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(g[0], g[1], g[2]),
        UnitQuaternion::from_quaternion(Quaternion::new(g[6], g[3], g[4], g[5])),
    )
}
