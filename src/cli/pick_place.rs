//! `pushplan pick-place`: move one object to a placement with the arm's hand through the
//! manipulation graph and its two-level Fuzzy PRM, check the path, write it.

use crate::manipulation::graph::INITIAL_PROBABILITY;
use crate::manipulation::{EdgeKind, ManipulationGraph, Motion, PickAndPlace, Settings};
use crate::math::Pose2;
use crate::robot::wgr::displacement;
use crate::scene::{Goal, Scene};
use serde::Serialize;
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

/// The file `pick-place` writes.
#[derive(Serialize)]
struct PickPlaceFile {
    /// Always "pushplan-pick-place/1".
    format: &'static str,
    scene: String,
    object: String,
    /// Placements `[x, y, yaw]`: the start, the goal.
    placements: Vec<[f64; 3]>,
    /// Grasps: the tool in the object frame, `[x, y, z, roll, pitch, yaw]` (m, rad).
    grasps: Vec<[f64; 6]>,
    segments: Vec<SegmentRecord>,
    graph: GraphRecord,
}

#[derive(Serialize)]
struct SegmentRecord {
    /// "transit" (the object rests at `placement`) or "transfer" (carried in `grasp`
    /// from placement `from` to `to`).
    motion: &'static str,
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

#[derive(Serialize)]
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
    let object = crate::reach::graspable_object(&scene, &run.object)?;
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
    if run.grasps == 0 || run.budget == 0 {
        return Err("--grasps and --budget must be positive".into());
    }
    let problem = PickAndPlace::new(&scene, object, goal, run.grasps, run.seed)?;
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
        format: "pushplan-pick-place/1",
        scene: crate::plan::PlanFile::scene_reference(scene_path, out),
        object: run.object.clone(),
        placements: problem
            .placements
            .iter()
            .map(|p| [p.x, p.y, p.theta])
            .collect(),
        grasps: problem.grasps.iter().map(displacement).collect(),
        segments: segments
            .iter()
            .map(|s| {
                let waypoints = s.waypoints.iter().map(|q| q.as_slice().to_vec()).collect();
                match s.motion {
                    Motion::Transit { placement } => SegmentRecord {
                        motion: "transit",
                        placement: Some(placement),
                        grasp: None,
                        from: None,
                        to: None,
                        waypoints,
                    },
                    Motion::Transfer { grasp, from, to } => SegmentRecord {
                        motion: "transfer",
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
    std::fs::write(out, text + "\n")
        .map_err(|e| format!("{}: cannot write: {e}", out.display()))?;
    println!("pick-and-place path written to {}", out.display());
    if let Some(dir) = &run.render {
        // Frames one Transit step (0.02 rad) apart, drawn 0.02 s apart.
        let (states, control_starts) = problem.states(&segments);
        let film = crate::render::Film {
            contacts: vec![Vec::new(); states.len() - 1],
            states,
            control_starts,
            dt: 0.02,
            scene: problem.scene.clone(),
            executed: Vec::new(),
        };
        let files = crate::render::write_pictures(&film, dir, &[])?;
        for path in [files.snapshots, files.timeline, files.animation] {
            println!("wrote {}", path.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}
