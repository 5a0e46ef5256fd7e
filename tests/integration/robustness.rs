//! Robustness in the planner's own terms (perturbed re-simulations) and open-loop
//! execution in the 3D engine, on a plan of the planar hand scene.

use pushplan::planning::execute::{execute, ExecuteSettings};
use pushplan::planning::path::PathControl;
use pushplan::planning::plan_file::PlanFile;
use pushplan::planning::robustness::{robustness, robustness_until, Factor, Noise};
use pushplan::{EeAction, Scene};

const SCENE: &str = "tests/data/hand_push_straight.yaml";

/// [`SCENE`] with `from` (text that must be in it) replaced by `to`.
fn scene_with(from: &str, to: &str) -> Scene {
    let yaml = std::fs::read_to_string(SCENE).unwrap();
    assert!(yaml.contains(from), "{from}");
    Scene::from_yaml(&yaml.replace(from, to), std::path::Path::new(SCENE)).unwrap()
}

/// The hand (front face at x 0.42) pushes the box (back face at 0.55) straight along +x
/// at 0.2 m/s for 1.9 s, so the box ends at x 0.85, the goal disc's centre; then it
/// backs off.
fn controls() -> Vec<PathControl> {
    push_then_back_off(0.0)
}

/// [`controls`] with the hand also moving sideways (+y) at `vy` m/s while it pushes.
fn push_then_back_off(vy: f64) -> Vec<PathControl> {
    vec![
        PathControl {
            action: EeAction::planar(0.2, vy, 0.0),
            steps: 190,
        },
        PathControl {
            action: EeAction::planar(-0.2, 0.0, 0.0),
            steps: 20,
        },
    ]
}

#[test]
fn without_noise_every_trial_is_the_plan_and_more_noise_reaches_the_goal_less_often() {
    let scene = Scene::load(SCENE).unwrap();
    let exact = robustness(&scene, &controls(), &Noise::none(), 5, 1);
    assert_eq!(exact.success_rate, 1.0, "{:?}", exact.trials[0]);
    assert_eq!(exact.max_deviation, 0.0);
    let default = robustness(&scene, &controls(), &Noise::default(), 20, 1);
    assert!(default.success_rate >= 0.9, "{}", default.success_rate);
    assert!(default.max_deviation > 0.0 && default.max_deviation < 0.05);
    // Start poses off by up to 10 cm: the box often ends outside the disc.
    let wild = Noise {
        position: 0.1,
        ..Noise::default()
    };
    let report = robustness(&scene, &controls(), &wild, 20, 1);
    assert!(
        report.success_rate < default.success_rate,
        "{}",
        report.success_rate
    );
    // The same seed draws the same trials.
    assert_eq!(report, robustness(&scene, &controls(), &wild, 20, 1));
}

#[test]
fn the_plan_executed_in_3d_reaches_the_goal_and_matches_the_prediction() {
    let scene = Scene::load(SCENE).unwrap();
    let settings = pushplan::planning::plan_file::PlanSettings {
        planner: pushplan::planning::PlannerKind::PcRrt,
        seed: 1,
        k: 3,
        goal_bias: 0.05,
        time_limit: 1.0,
        shortcut: 0.0,
        threads: 1,
        restart_steps: 0,
        fallback_steps: 0,
        intermediate_states: false,
    };
    let plan = PlanFile::build(SCENE, scene.clone(), &settings, &controls(), None).unwrap();
    assert!(plan.solved);
    let report = execute(&scene, &plan, &ExecuteSettings::default()).unwrap();
    assert_eq!(report.trials.len(), 10);
    assert_eq!(report.success_rate, 1.0, "{:?}", report.trials);
    assert_eq!(report.tipped_trials, 0);
    // The nominal trial ends within 1 cm of the model's prediction.
    assert!(
        report.trials[0].final_errors[0] < 0.01,
        "{:?}",
        report.trials[0]
    );
}

#[test]
fn an_unknown_pressure_distribution_makes_a_point_push_fragile_and_leaves_a_flat_push_robust() {
    // The model's noise shifts the centre of friction (the support pressure is not known
    // to be uniform); the world's does not. A flat face pushing the box straight holds
    // it whatever the pressure; a small round pusher through the centroid turns it one
    // way or the other.
    let point = scene_with(
        "shape: {type: box, size: [0.04, 0.12, 0.08]}",
        "shape: {type: cylinder, radius: 0.02, height: 0.08}",
    );
    let rates = |scene: &Scene| {
        let world = robustness(scene, &controls(), &Noise::world(), 40, 3).success_rate;
        let model = robustness(scene, &controls(), &Noise::default(), 40, 3).success_rate;
        (world, model)
    };
    assert_eq!(
        rates(&Scene::load(SCENE).unwrap()),
        (1.0, 1.0),
        "the flat push"
    );
    let (world, model) = rates(&point);
    assert_eq!(world, 1.0, "the point push in the world's noise");
    assert!(model < 0.8, "the point push in the model's noise: {model}");
}

#[test]
fn a_push_that_leans_on_the_arms_friction_is_fragile_in_the_models_noise() {
    // The hand moves at (0.2, 0.05) m/s. In contact with the box's back face (from
    // x 0.55, after 0.13 m) it pushes for 1.25 s. Carrying the box sideways with it
    // (sticking) takes a tangential contact force a quarter of the normal one: the
    // table's friction opposes the box's motion. So the box sticks only while
    // mu_c >= 0.25 and ends at y = 0.05 * 1.25 = 62.5 mm. Sliding, it moves along the
    // friction cone's edge, sideways at 0.2 * mu_c m/s: 37.5 mm with mu_c 0.15.
    let scene = scene_with(
        "goal: {object: box, center: [0.85, 0.0], radius: 0.1}",
        "goal: {object: box, center: [0.85, 0.0625], radius: 0.01, margin: 0.0}",
    );
    let controls = push_then_back_off(0.05);
    let exact = robustness(&scene, &controls, &Noise::none(), 1, 1);
    let end = exact.planned_goal_object.unwrap();
    assert!(
        (end[0] - 0.85).abs() < 2e-3 && (end[1] - 0.0625).abs() < 2e-3,
        "{end:?}"
    );
    let report = |noise: &Noise| robustness(&scene, &controls, noise, 40, 5);
    // The closed form, with mu_c = 0.3 x factor: sideways 1.25 s x min(0.2 mu_c, 0.05).
    for factor in [0.6, 0.7, 0.8, 0.9, 1.0] {
        let fixed = Factor {
            low: factor,
            high: factor,
        };
        let trial = &report(&Noise {
            mu_c: fixed,
            ..Noise::none()
        })
        .trials[0];
        let [x, y, _] = trial.goal_object.unwrap();
        let sideways = 1.25 * (0.2 * 0.3 * factor).min(0.05);
        assert!(
            (x - 0.85).abs() < 1e-3 && (y - sideways).abs() < 1e-3,
            "{factor}: {trial:?}"
        );
    }
    // The scene's mu_c (0.3) x U(0.8, 1.2) is at least 0.24: the box (nearly) always
    // sticks. The model's noise draws mu_c down to 0.15: where it slides, the box falls
    // short of the 10 mm disc sideways.
    let world = report(&Noise::world());
    assert_eq!(world.success_rate, 1.0, "the world's noise");
    let low_mu_c = report(&Noise {
        mu_c: Noise::default().mu_c,
        ..Noise::world()
    });
    assert!(
        low_mu_c.success_rate < 0.9,
        "mu_c down to half: {}",
        low_mu_c.success_rate
    );
    for trial in low_mu_c.trials.iter().filter(|t| !t.reached) {
        let [x, y, _] = trial.goal_object.unwrap();
        assert!(y < 0.0625 - 0.008 && (x - 0.85).abs() < 0.005, "{trial:?}");
    }
    assert!(report(&Noise::default()).success_rate < 0.9);
}

/// A check stopped by a deadline is the full check of the trials it ran: the worlds are
/// drawn in order, so its trials are the first of those asked, and its rate is theirs.
#[test]
fn a_check_cut_short_by_its_deadline_is_the_check_of_the_trials_it_ran() {
    // The round pusher through the centroid: the box turns one way or the other.
    let scene = scene_with(
        "shape: {type: box, size: [0.04, 0.12, 0.08]}",
        "shape: {type: cylinder, radius: 0.02, height: 0.08}",
    );
    let noise = Noise::default();
    let full = robustness(&scene, &controls(), &noise, 40, 7);
    assert_eq!(full.trials.len(), 40);
    let reached = full.trials.iter().filter(|t| t.reached).count();
    assert!(
        (1..40).contains(&reached),
        "the noise leaves some trials short of the goal, not all: {reached}"
    );
    // A deadline already past: one trial, the first.
    let past = std::time::Instant::now();
    let cut = robustness_until(&scene, &controls(), &noise, 40, 7, Some(past));
    assert_eq!(cut.trials, full.trials[..1]);
    assert_eq!(
        cut.success_rate,
        f64::from(u8::from(full.trials[0].reached))
    );
    // Any prefix is the check of that many trials.
    for n in [1, 7, 23] {
        let prefix = robustness(&scene, &controls(), &noise, n, 7);
        assert_eq!(prefix.trials, full.trials[..n]);
        let rate = full.trials[..n].iter().filter(|t| t.reached).count() as f64 / n as f64;
        assert_eq!(prefix.success_rate, rate);
    }
    // A deadline far off: every trial.
    let later = std::time::Instant::now() + std::time::Duration::from_secs(3600);
    let whole = robustness_until(&scene, &controls(), &noise, 40, 7, Some(later));
    assert_eq!(whole, full);
}
