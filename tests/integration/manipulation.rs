//! The manipulation graph and its two-level Fuzzy PRM (issue 15): the low-level roadmap
//! against a disc obstacle in the plane (closed-form edge probabilities, a refuted edge
//! removed), the upper level's edges and probability updates as the lecture gives them,
//! and a pick-and-place on a shipped scene whose path checks.

use crate::common;

use nalgebra::{dvector, DVector};
use pushplan::planning::manipulation::fuzzy::{edge_probability, FuzzyRoadmap, Query};
use pushplan::planning::manipulation::graph::INITIAL_PROBABILITY;
use pushplan::planning::manipulation::{
    EdgeKind, ManipulationGraph, Motion, PickAndPlace, Settings,
};
use pushplan::{Pose2, Scene};

/// Free unless within 0.3 of (1, 0).
fn outside_disc(q: &DVector<f64>) -> bool {
    (q - dvector![1.0, 0.0]).norm() > 0.3
}

#[test]
fn the_low_level_roadmap_refutes_an_edge_and_certifies_a_detour() {
    let (lambda, resolution) = (1.0, 0.02);
    let mut roadmap = FuzzyRoadmap::new(dvector![0.0, 0.0], dvector![2.0, 0.0], lambda, resolution);
    // CONSTRUCTION: the edge start-goal unchecked, P*(0) = exp(-2 / 1).
    assert!((roadmap.probability(0, 1).unwrap() - (-2.0f64).exp()).abs() < 1e-15);
    // QUERY: its midpoint (1, 0) is inside the disc: the edge goes, the query fails.
    assert_eq!(roadmap.query(outside_disc), Query::Failed);
    assert_eq!(roadmap.probability(0, 1), None);
    assert_eq!(roadmap.checks, 1);
    // A sample above the disc: edges to both ends, each of length max(|dx|, |dy|) = 1.
    roadmap.add_sample(dvector![1.0, 1.0]);
    assert!((roadmap.probability(0, 2).unwrap() - (-1.0f64).exp()).abs() < 1e-15);
    match roadmap.query(outside_disc) {
        Query::Found(path) => assert_eq!(path, vec![0, 2, 1]),
        Query::Failed => panic!("the detour is free"),
    }
    // Both edges certain: checked until their spacing is within the resolution, 1/2^6.
    for (a, b) in [(0, 2), (2, 1)] {
        assert_eq!(roadmap.probability(a, b), Some(1.0));
    }
    assert_eq!(roadmap.checks, 1 + 2 * 63);
    // P* between: one level halves the unchecked spacing.
    let p = edge_probability(1.0, 1, lambda, resolution);
    assert!((p - (-0.5f64).exp()).abs() < 1e-15);
    assert_eq!(edge_probability(1.0, 6, lambda, resolution), 1.0);
}

#[test]
fn an_edge_certified_at_dyadic_points_is_walked_where_every_line_is_checked() {
    // A thin wall across x in [0.039, 0.041]: an edge from 0 to 0.1 is certain at level 3
    // (spacing 0.0125), whose points 0.0125 k all miss the wall; the line's points at the
    // Transit resolution (0.02 k) hit it at 0.04.
    let wall = |q: &DVector<f64>| !(0.039..=0.041).contains(&q[0]);
    let lambda = 1.0;
    let resolution = pushplan::planning::transit::TRANSIT_RESOLUTION;
    let mut dyadic = FuzzyRoadmap::new(dvector![0.0], dvector![0.1], lambda, resolution);
    assert_eq!(
        dyadic.query(wall),
        Query::Found(vec![0, 1]),
        "dyadic points miss the wall"
    );
    let mut walked = FuzzyRoadmap::new(dvector![0.0], dvector![0.1], lambda, resolution);
    let line = |a: &DVector<f64>, b: &DVector<f64>| {
        pushplan::planning::transit::transit_points(a, b).collect()
    };
    assert_eq!(walked.query_walked(wall, line), Query::Failed);
    assert_eq!(walked.probability(0, 1), None, "the refuted edge is gone");
    // Without the wall the walk adds the line's five points to the seven dyadic ones.
    let mut free = FuzzyRoadmap::new(dvector![0.0], dvector![0.1], lambda, resolution);
    assert_eq!(free.query_walked(|_| true, line), Query::Found(vec![0, 1]));
    assert_eq!(free.checks, 7 + 5);
}

fn problem() -> PickAndPlace {
    let scene = Scene::load("scenes/pick_and_place.yaml").unwrap();
    let can = pushplan::planning::reach::graspable_object(&scene, "red_can").unwrap();
    let theta = scene.start.objects[can].theta;
    PickAndPlace::new(
        &scene,
        &scene.start,
        can,
        Pose2::new(0.8, -0.2, theta),
        8,
        1,
    )
    .unwrap()
}

/// Nodes hold their grasp where they say; transfer edges join nodes of one grasp at two
/// placements, transit edges nodes of one placement; every edge starts at 0.9999. A
/// low-level run that finds no path leaves its edge at 1 - time(e) / total_time, one that
/// does at 1.
#[test]
fn the_manipulation_graph_updates_edge_probabilities_as_the_lecture_says() {
    let problem = problem();
    let settings = Settings {
        samples_per_round: 1,
        ..Settings::default()
    };
    let mut graph = ManipulationGraph::new(problem.clone(), settings);
    assert!(graph.nodes.len() >= 3, "{} nodes", graph.nodes.len());
    for e in &graph.edges {
        let (a, b) = (&graph.nodes[e.a], &graph.nodes[e.b]);
        match e.kind {
            EdgeKind::Transfer => {
                assert!(a.grasp.is_some() && a.grasp == b.grasp && a.placement != b.placement)
            }
            EdgeKind::Transit => assert_eq!(a.placement, b.placement),
        }
        assert_eq!(e.probability, INITIAL_PROBABILITY);
    }
    for node in &graph.nodes[1..] {
        let motion = Motion::Transit {
            placement: node.placement,
        };
        assert!(problem.valid(motion, &node.q));
    }
    // Low-level runs, one sample each, on every edge of the most probable path, until one
    // fails and one succeeds.
    let (mut failed, mut succeeded) = (false, false);
    for _ in 0..200 {
        let path = graph.most_probable_path().expect("a path in the graph");
        for (e, _) in path {
            if graph.edges[e].probability == 1.0 {
                continue;
            }
            graph.run_low_level(e);
            let edge = &graph.edges[e];
            if edge.probability == 1.0 {
                succeeded = true;
            } else {
                let expected = 1.0 - edge.time as f64 / graph.total_time as f64;
                assert!((edge.probability - expected.max(f64::MIN_POSITIVE)).abs() < 1e-15);
                failed = true;
            }
        }
        if failed && succeeded {
            break;
        }
    }
    assert!(
        failed && succeeded,
        "failed {failed}, succeeded {succeeded}"
    );
}

/// The pick-and-place of the shipped scene: solved, checked independently (every line at
/// the Transit resolution, grasps held at both placements), a transfer in it; a path
/// carried straight through the tall box does not check.
#[test]
fn pick_and_place_moves_the_can_into_the_disc() {
    let problem = problem();
    let mut graph = ManipulationGraph::new(problem.clone(), Settings::default());
    let segments = graph.solve().expect("solved");
    problem.check(&segments).unwrap();
    let transfer = segments
        .iter()
        .position(|s| matches!(s.motion, Motion::Transfer { from: 0, to: 1, .. }))
        .expect("the can is carried");

    let mut straight = segments.clone();
    let w = &mut straight[transfer].waypoints;
    let (first, last) = (w[0].clone(), w.last().unwrap().clone());
    *w = vec![first, last];
    let why = problem.check(&straight).unwrap_err();
    assert!(why.contains("invalid"), "{why}");
    let mut broken = segments.clone();
    broken.truncate(transfer);
    assert!(problem
        .check(&broken)
        .unwrap_err()
        .contains("goal placement"));
}

/// The command: solved, written, drawn; the same seed writes the same file; `check`
/// checks it again and refuses a broken or malformed one.
#[test]
fn pick_place_writes_draws_and_checks_its_path() {
    let scratch = common::Scratch::new("pick-place");
    let run = |out: &std::path::Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_pushplan"))
            .args([
                "pick-place",
                "scenes/pick_and_place.yaml",
                "--object",
                "red_can",
                "--out",
            ])
            .arg(out)
            .output()
            .unwrap()
    };
    let (a, b) = (scratch.join("a.json"), scratch.join("b.json"));
    let pictures = scratch.join("pictures");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_pushplan"))
        .args([
            "pick-place",
            "scenes/pick_and_place.yaml",
            "--object",
            "red_can",
            "--render",
        ])
        .arg(&pictures)
        .arg("--out")
        .arg(&a)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let animation = std::fs::read_to_string(pictures.join("animation.html")).unwrap();
    assert!(animation.contains("red_can"));
    assert!(String::from_utf8_lossy(&out.stdout).contains("transfer through"));
    assert!(run(&b).status.success());
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    let text = std::fs::read_to_string(&a).unwrap();
    assert!(text.contains("\"format\": \"pushplan-pick-place/1\""));

    // `check` checks the file again; a transfer cut short of its placement does not check;
    // a segment naming a grasp the file lacks is refused as malformed.
    let check = |file: &std::path::Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_pushplan"))
            .arg("check")
            .arg(file)
            .output()
            .unwrap()
    };
    let checked = check(&a);
    assert!(
        checked.status.success(),
        "{}",
        String::from_utf8_lossy(&checked.stdout)
    );
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let transfer = json["segments"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|s| s["motion"] == "transfer")
        .unwrap();
    let waypoints = transfer["waypoints"].as_array_mut().unwrap();
    waypoints.pop();
    let short = scratch.join("short.json");
    std::fs::write(&short, json.to_string()).unwrap();
    let refused = check(&short);
    assert_eq!(refused.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&refused.stdout).contains("does not hold grasp"));
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    json["segments"][0]["placement"] = serde_json::json!(7);
    let malformed = scratch.join("malformed.json");
    std::fs::write(&malformed, json.to_string()).unwrap();
    let refused = check(&malformed);
    assert_eq!(refused.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("segments[0]"));
    let missing = std::process::Command::new(env!("CARGO_BIN_EXE_pushplan"))
        .args([
            "pick-place",
            "scenes/pick_and_place.yaml",
            "--object",
            "tall_box",
        ])
        .output()
        .unwrap();
    assert_eq!(missing.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&missing.stderr).contains("objects with grasps: 'red_can'"));
}
