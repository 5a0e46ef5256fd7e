//! The 3D execution engines' setup, checked against closed forms in both (rapier and
//! MuJoCo): a box or a glass pushed flat-on below `b / mu_g` slides upright and tips above
//! it; a sliding object stops after `v^2 / (2 mu_g g)`; an object pushed past the table's
//! edge has fallen off.

use crate::common;

use nalgebra::{DVector, Vector3};
use pushplan::planning::execute::rapier::{RapierWorld, SolverSettings};
use pushplan::planning::execute::TIPPED_TILT;
use pushplan::planning::execute::{Engine, EngineKind, STEP};
use pushplan::planning::trajectory::{Playback, Trajectory};
use pushplan::Scene;
use std::path::Path;

/// A world of `scene` in `engine`, its objects at their start and the arm at `poses`.
fn world(engine: EngineKind, scene: &Scene, poses: &[nalgebra::Isometry3<f64>]) -> Box<dyn Engine> {
    engine
        .world(
            scene,
            &scene.start.objects,
            poses,
            &SolverSettings::default(),
        )
        .unwrap()
}

/// A 1 cm tall planar hand at `height` in front of a 0.1 m box (0.3 m tall) on a table
/// with support friction `mu_g`.
fn scene(height: f64, mu_g: f64) -> Scene {
    scene_with(height, mu_g, "{type: box, size: [0.1, 0.1, 0.3]}")
}

fn scene_with(height: f64, mu_g: f64, shape: &str) -> Scene {
    common::thin_hand_scene("box", shape, 0.4705, height, mu_g, "")
}

/// Drives the planar hand of `scene` through `hand(t)` (its joints at t s) for `duration`
/// seconds in `engine`; returns the world and the first object's largest tilt (rad).
fn drive(
    engine: EngineKind,
    scene: &Scene,
    hand: impl Fn(f64) -> DVector<f64>,
    duration: f64,
) -> (Box<dyn Engine>, f64) {
    let mut poses = Vec::new();
    scene.robot.chain.forward_kinematics(&hand(0.0), &mut poses);
    let mut world = world(engine, scene, &poses);
    let mut tilt: f64 = 0.0;
    for n in 1..=(duration / STEP).round() as usize {
        scene
            .robot
            .chain
            .forward_kinematics(&hand(n as f64 * STEP), &mut poses);
        world.move_arm(&poses);
        world.step();
        tilt = tilt.max(world.object_tilt(0));
    }
    (world, tilt)
}

/// Pushes along +x: the hand speeds up to 0.1 m/s over 0.5 s, then holds that speed for
/// 1.5 s. Returns the box's largest tilt (rad) and its final x (m).
fn push(engine: EngineKind, scene: &Scene) -> (f64, f64) {
    let (ramp, speed) = (0.5, 0.1);
    let hand = |t: f64| {
        let x = if t < ramp {
            0.4 + 0.5 * speed / ramp * t * t
        } else {
            0.4 + 0.5 * speed * ramp + speed * (t - ramp)
        };
        DVector::from_vec(vec![x, 0.0, 0.0])
    };
    let (world, tilt) = drive(engine, scene, hand, 2.0);
    (tilt, world.object_pose2(0).x)
}

#[test]
fn a_box_pushed_flat_on_below_the_tipping_height_slides_and_above_it_tips() {
    // b / mu_g = 0.05 / 0.4 = 0.125 m.
    let h_max = 0.05 / 0.4;
    for engine in EngineKind::ALL {
        let (tilt, x) = push(engine, &scene(0.8 * h_max, 0.4));
        assert!(
            tilt < 0.02,
            "{engine}: slides upright below h_max: tilt {tilt}"
        );
        // The hand travels 0.175 m and starts 0.5 mm from the box.
        assert!(
            (x - (0.4705 + 0.175 - 0.0005)).abs() < 0.01,
            "{engine}: pushed along: x = {x}"
        );
        let (tilt, _) = push(engine, &scene(1.25 * h_max, 0.4));
        assert!(
            tilt > TIPPED_TILT,
            "{engine}: tips above h_max: tilt {tilt}"
        );
        // Above h_max, on a slipperier table (h_max = 0.167 m) it slides.
        let (tilt, _) = push(engine, &scene(1.15 * h_max, 0.3));
        assert!(
            tilt < 0.02,
            "{engine}: slides on a slipperier table: tilt {tilt}"
        );
    }
}

#[test]
fn a_glass_pushed_flat_on_slides_below_r_over_mu_g_and_tips_above() {
    // R / mu_g = 0.035 / 0.4 = 0.0875 m. rapier lets contacts sink up to 1 mm, so a
    // glass pushed at 0.9 of it leans on its loaded rim by a few hundredths of a radian
    // (the lean `physics.tipping_margin` reserves against), and slides.
    let h_max = 0.035 / 0.4;
    let glass = |height: f64| {
        let shape = "{type: cylinder, radius: 0.035, height: 0.15}";
        common::thin_hand_scene("glass", shape, 0.4555, height, 0.4, "")
    };
    for engine in EngineKind::ALL {
        let (tilt, x) = push(engine, &glass(0.9 * h_max));
        assert!(
            tilt < 0.1,
            "{engine}: slides upright below h_max: tilt {tilt}"
        );
        assert!(
            (x - (0.4555 + 0.175 - 0.0005)).abs() < 0.01,
            "{engine}: pushed along: x = {x}"
        );
        // MuJoCo's soft contacts let the loaded rim sink and slip a little: there it tips
        // between 1.1 and 1.2 h_max (rapier: between 1.0 and 1.1).
        let (tilt, _) = push(engine, &glass(1.25 * h_max));
        assert!(
            tilt > TIPPED_TILT,
            "{engine}: tips above h_max: tilt {tilt}"
        );
    }
}

/// The thin hand (1 cm tall, at 5 cm) at x = 0.4 on a table of `extent` (`x: [..], y:
/// [..]`), with `objects` (YAML list items) and `goal` (its YAML map).
fn hand_on_table(extent: &str, objects: &str, goal: &str, file: &str) -> Scene {
    let yaml = format!(
        "robot:
  type: planar_hand
  shape: {{type: box, size: [0.04, 0.12, 0.01]}}
  start: [0.4, 0.0, 0.0]
  height: 0.05
table: {{height: 0.76, {extent}}}
objects:
{objects}goal: {goal}
"
    );
    Scene::from_yaml(&yaml, Path::new(file)).unwrap()
}

/// The hand's path of these tests: 0.2 m along +x in 101 poses (2 s, 20 ms apart).
fn push_path() -> Vec<DVector<f64>> {
    (0..=100)
        .map(|k| DVector::from_vec(vec![0.4 + 0.002 * k as f64, 0.0, 0.0]))
        .collect()
}

#[test]
fn a_box_pushed_over_the_table_edge_has_fallen_off_and_a_tipped_one_has_not() {
    // The thin hand's push, on a table that ends 4 cm beyond the box's far face.
    let scene = hand_on_table(
        "x: [0.27, 0.56], y: [-0.6, 0.6]",
        "  - {name: box, shape: {type: box, size: [0.1, 0.1, 0.3]}, pose: [0.4705, 0.0, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.3}\n",
        "{object: box, center: [0.4, 0.3], radius: 0.1}",
        "scenes/short-table-test.yaml",
    );
    let hand = |x: f64| DVector::from_vec(vec![x, 0.0, 0.0]);
    let mut poses = Vec::new();
    for engine in EngineKind::ALL {
        scene.robot.chain.forward_kinematics(&hand(0.4), &mut poses);
        let mut world = world(engine, &scene, &poses);
        assert!(
            !world.object_fell_off(0),
            "{engine}: it starts on the table"
        );
        let path = push_path();
        world.follow(&scene.robot.chain, &path, 0.02);
        assert!(
            world.object_fell_off(0),
            "{engine}: pushed over the edge: {}",
            world.object_pose(0)
        );
        // Tipped over on a long table, it lies on it.
        let tall = scene_with(1.25 * 0.125, 0.4, "{type: box, size: [0.1, 0.1, 0.3]}");
        scene.robot.chain.forward_kinematics(&hand(0.4), &mut poses);
        let mut world = self::world(engine, &tall, &poses);
        world.follow(&tall.robot.chain, &path, 0.02);
        assert!(
            world.object_tilt(0) > TIPPED_TILT && !world.object_fell_off(0),
            "{engine}: tipped on the table: {}",
            world.object_pose(0)
        );
    }
}

#[test]
fn a_box_hanging_over_an_edge_as_far_as_a_replan_allows_is_pushed_along_it_upright() {
    // A re-plan from an observed start lets a box (not the goal's) hang over the table's
    // edge until the footprint the tipping check keeps the support pressure in (shrunk by
    // the 30 % margin: a 7 cm square) reaches it (`Clearances::with_start_overhangs`).
    // Here the table's side edge runs 3.5 cm from the box's centre line (15 mm of the box
    // over), and the hand pushes the box 15 cm along it below the tipping height (b /
    // mu_g = 0.125 m): in both engines it slides on, upright and on the table.
    let file = hand_on_table(
        "x: [0.27, 1.03], y: [-0.6, 0.0351]",
        "  - {name: box, shape: {type: box, size: [0.1, 0.1, 0.3]}, pose: [0.4705, -0.5, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.3}
  - {name: goal, shape: {type: box, size: [0.1, 0.1, 0.2]}, pose: [0.9, -0.5, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.3}\n",
        "{object: goal, center: [0.8, -0.3], radius: 0.1}",
        "scenes/edge-test.yaml",
    );
    // The box observed at the edge: the model plans from there.
    let mut observed = file.start.clone();
    observed.objects[0].y = 0.0;
    let scene = file
        .with_start(&observed, Path::new("observed.json"))
        .unwrap();
    // The model takes the push along: the box 15 cm on, as far over the edge.
    let mut pushed = scene.start.clone();
    pushed.objects[0].x += 0.15;
    pushplan::validity::check_state(&scene, &pushed).unwrap();
    let path = push_path();
    for engine in EngineKind::ALL {
        let mut poses = Vec::new();
        scene.robot.chain.forward_kinematics(&path[0], &mut poses);
        let mut world = world(engine, &scene, &poses);
        let mut tilt: f64 = 0.0;
        for pair in path.windows(2) {
            world.follow(&scene.robot.chain, pair, 0.02);
            tilt = tilt.max(world.object_tilt(0));
        }
        let pose = world.object_pose2(0);
        assert!(
            !world.object_fell_off(0) && tilt < 0.1,
            "{engine}: on the table and upright: {pose:?}, largest tilt {tilt}"
        );
        // Pushed along by the hand's 0.2 m less the 5 mm gap, less a few mm of a soft
        // contact; turned a little by the support the edge cuts off.
        assert!(
            pose.x > 0.4705 + 0.15 && pose.y.abs() < 0.02 && pose.theta.abs() < 0.2,
            "{engine}: pushed along the edge: {pose:?}"
        );
    }
}

#[test]
fn a_sliding_object_stops_after_v_squared_over_two_mu_g_g() {
    // Low objects: a tall box braking on the table pitches forward (mu_g h_com > b) and
    // rocks on its edge, which this closed form leaves out.
    let low_box = "{type: box, size: [0.1, 0.1, 0.05]}";
    let puck = "{type: cylinder, radius: 0.05, height: 0.1}";
    let cases = [(0.5, 0.4, low_box), (0.3, 0.2, low_box), (0.4, 0.3, puck)];
    for (engine, (v, mu_g, shape)) in EngineKind::ALL
        .into_iter()
        .flat_map(|e| cases.map(|c| (e, c)))
    {
        let scene = scene_with(0.05, mu_g, shape);
        let mut poses = Vec::new();
        // The hand far behind, out of the way.
        scene
            .robot
            .chain
            .forward_kinematics(&DVector::from_vec(vec![0.3, 0.4, 0.0]), &mut poses);
        let mut world = world(engine, &scene, &poses);
        // Let the box settle on the table, then launch it.
        for _ in 0..100 {
            world.step();
        }
        let x0 = world.object_pose2(0).x;
        world.set_object_velocity(0, Vector3::new(v, 0.0, 0.0));
        for _ in 0..(2.0 / STEP) as usize {
            world.step();
        }
        let travelled = world.object_pose2(0).x - x0;
        let expected = v * v / (2.0 * mu_g * 9.81);
        assert!(
            (travelled - expected).abs() < 0.02 * expected,
            "{engine}: {shape}, v {v}, mu_g {mu_g}: {travelled} m, expected {expected} m"
        );
        assert!(world.object_velocity(0).norm() < 1e-3);
    }
}

#[test]
fn an_off_centre_push_turns_a_box_in_3d_as_the_planar_model_predicts() {
    // A narrow pusher (1 cm wide) pushes a 0.1 m box 3 cm off its centre line, slowly,
    // for 0.15 m. The planar model (ellipsoidal limit surface, uniform pressure) and the
    // 3D engine (feet spread over the footprint, Coulomb friction) should turn it alike.
    let yaml = "robot:
  type: planar_hand
  shape: {type: box, size: [0.04, 0.01, 0.01]}
  start: [0.4, 0.03, 0.0]
  height: 0.03
table: {height: 0.76, x: [0.27, 1.03], y: [-0.6, 0.6]}
objects:
  - {name: box, shape: {type: box, size: [0.1, 0.1, 0.05]}, pose: [0.4705, 0.0, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.6}
goal: {object: box, center: [0.9, 0.3], radius: 0.1}
";
    let scene = Scene::from_yaml(yaml, Path::new("scenes/execute-test.yaml")).unwrap();
    let speed = 0.05;
    let duration = 3.0;
    let mut propagator = pushplan::Propagator::new(&scene);
    let run = propagator.propagate(
        &scene.start,
        &pushplan::EeAction::planar(speed, 0.0, 0.0),
        duration,
    );
    assert!(run.stopped_by.is_none(), "{:?}", run.stopped_by);
    let model = run.state.objects[0];

    let pushed = |kind: EngineKind| {
        let hand = |t: f64| DVector::from_vec(vec![0.4 + speed * t, 0.03, 0.0]);
        drive(kind, &scene, hand, duration).0.object_pose2(0)
    };
    assert!(model.theta < -0.1, "the model turns it: {model:?}");
    // MuJoCo stands the box on its four corners, 71 mm from its centre, where the uniform
    // pressure's friction acts at 38 mm on average: it resists turning more, and turns the
    // box the same way by less (0.67 of the model's angle when this was written).
    let mujoco = pushed(EngineKind::Mujoco);
    assert!(
        mujoco.theta < 0.5 * model.theta && mujoco.theta > model.theta,
        "yaw: MuJoCo {mujoco:?}, model {model:?}"
    );
    let engine = pushed(EngineKind::Rapier);
    assert!(
        (engine.theta - model.theta).abs() < 0.25 * model.theta.abs(),
        "yaw: engine {engine:?}, model {model:?}"
    );
    // Within 10 % of the pusher's 0.15 m travel.
    assert!(
        (engine.translation() - model.translation()).norm() < 0.015,
        "engine {engine:?}, model {model:?}"
    );
}

#[test]
fn the_feet_spread_the_support_as_the_scene_says() {
    use pushplan::physics::Footprint;
    use pushplan::planning::execute::rapier::support_points;
    let mean = |points: &[nalgebra::Vector2<f64>]| {
        points.iter().map(|p| p.norm()).sum::<f64>() / points.len() as f64
    };
    // Uniform pressure on a disc of radius 0.08: mean distance within 12 % of 2R/3, rim
    // included.
    let disc = Footprint::Circle { radius: 0.08 };
    let uniform = support_points(&disc, disc.characteristic_length());
    let c = 2.0 * 0.08 / 3.0;
    assert!((mean(&uniform) - c).abs() < 0.12 * c, "{}", mean(&uniform));
    assert!(uniform.iter().all(|p| p.norm() <= 0.08 + 1e-12));
    assert!(uniform.iter().any(|p| (p.norm() - 0.08).abs() < 1e-12));
    // A bowl loaded on its rim (c = 0.07): the feet's mean distance is c.
    let rim = support_points(&disc, 0.07);
    assert!((mean(&rim) - 0.07).abs() < 1e-9, "{}", mean(&rim));
    // A box: the corners are feet, so the support polygon is the footprint.
    let b = 0.05;
    let square = Footprint::Polygon {
        vertices: vec![
            nalgebra::Vector2::new(-b, -b),
            nalgebra::Vector2::new(b, -b),
            nalgebra::Vector2::new(b, b),
            nalgebra::Vector2::new(-b, b),
        ],
    };
    let feet = support_points(&square, square.characteristic_length());
    assert_eq!(feet.len(), 49 + 4);
    let c = b * (2f64.sqrt() + 1f64.asinh()) / 3.0;
    assert!((mean(&feet) - c).abs() < 0.12 * c, "{}", mean(&feet));
    assert!(feet
        .iter()
        .any(|p| (p.x - b).abs() < 1e-12 && (p.y - b).abs() < 1e-12));
}

/// A recorded arm trajectory (`tests/data/*.json`: its scene, and the joints `q` at
/// `times`).
struct Recorded {
    scene: Scene,
    trajectory: Trajectory,
}

impl Recorded {
    fn read(file: &str) -> Recorded {
        let text = std::fs::read_to_string(file).unwrap();
        let data: serde_json::Value = serde_json::from_str(&text).unwrap();
        let numbers = |v: &serde_json::Value| -> Vec<f64> {
            v.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        };
        let times = numbers(&data["times"]);
        Recorded {
            scene: Scene::load(data["scene"].as_str().unwrap()).unwrap(),
            trajectory: Trajectory {
                rate: 1.0 / (times[1] - times[0]),
                q: data["q"].as_array().unwrap().iter().map(numbers).collect(),
                objects: Vec::new(),
                times,
            },
        }
    }

    /// The arm's link poses at the start.
    fn start_poses(&self) -> Vec<nalgebra::Isometry3<f64>> {
        let mut poses = Vec::new();
        self.scene
            .robot
            .chain
            .forward_kinematics(&Playback::new(&self.trajectory).at(0.0), &mut poses);
        poses
    }

    /// Drives the arm of `world` along the trajectory as a controller plays it
    /// ([`Playback`]); returns the first object's planar pose every 0.1 s.
    fn play(&self, world: &mut dyn Engine) -> Vec<[f64; 3]> {
        let mut playback = Playback::new(&self.trajectory);
        let mut poses = Vec::new();
        let mut path = Vec::new();
        for n in 1..=(playback.end() / STEP) as usize {
            self.scene
                .robot
                .chain
                .forward_kinematics(&playback.at(n as f64 * STEP), &mut poses);
            world.move_arm(&poses);
            world.step();
            if n % 100 == 0 {
                let p = world.object_pose2(0);
                path.push([p.x, p.y, p.theta]);
            }
        }
        path
    }
}

/// Plays the arm trajectory of `tests/data/scene_04_turning_push.json` (the hand turns
/// the goal box with several contacts at once) with `solver`; returns the box's planar
/// pose every 0.1 s.
fn turning_push(solver: &SolverSettings) -> Vec<[f64; 3]> {
    let recorded = Recorded::read("tests/data/scene_04_turning_push.json");
    let scene = &recorded.scene;
    let mut world =
        RapierWorld::with_solver(scene, &scene.start.objects, &recorded.start_poses(), solver);
    recorded.play(&mut world)
}

#[test]
fn the_engine_is_converged_on_a_push_with_several_contacts() {
    // The engine is the plans' judge, so its answer must not hinge on the solver's
    // effort: doubling the iterations, or the Gauss-Seidel sweeps, barely moves the box
    // anywhere along the way. (With one sweep per iteration, the setting before, doubling
    // the iterations turned the box 0.47 rad differently.)
    let base = SolverSettings::default();
    let reference = turning_push(&base);
    let more = [
        SolverSettings {
            iterations: 2 * base.iterations,
            ..base
        },
        SolverSettings {
            pgs_iterations: 2 * base.pgs_iterations,
            ..base
        },
    ];
    for solver in more {
        let path = turning_push(&solver);
        let pairs = || path.iter().zip(&reference);
        let moved = pairs()
            .map(|(p, r)| (p[0] - r[0]).hypot(p[1] - r[1]))
            .fold(0.0, f64::max);
        let turned = pairs()
            .map(|(p, r)| (p[2] - r[2]).abs())
            .fold(0.0, f64::max);
        assert!(
            moved < 0.01 && turned < 0.15,
            "{solver:?}: {moved} m, {turned} rad from the default solver's path"
        );
    }
    // The hand did push the box: it turned by more than a radian on the way.
    let yaw: Vec<f64> = reference.iter().map(|p| p[2]).collect();
    let span =
        yaw.iter().cloned().fold(f64::MIN, f64::max) - yaw.iter().cloned().fold(f64::MAX, f64::min);
    assert!(span > 1.0, "{span}");
}

#[test]
fn both_engines_turn_the_box_alike_where_the_tilted_hand_pushes_it_at_one_point() {
    // Scene 32's first push (tests/data/scene_32_first_push.json): the WAM's tilted hand
    // touches the goal box's face at one point and turns it 0.4 rad while carrying it
    // 0.14 m. Rapier (Coulomb friction at every contact point) and MuJoCo (soft contacts,
    // elliptic cones) are independent of each other and of the planning model; they
    // agree within 2 mm. With rapier's default "simplified" friction (per contact manifold
    // one friction constraint and a twist constraint that resists turning up to
    // `mu sum(lambda_i d_i)` whether or not the box slides, a torsional friction Coulomb
    // has not), the box's face resting on the table held the box from turning: 0.2 rad,
    // and rapier's box ended 37 mm from MuJoCo's.
    let recorded = Recorded::read("tests/data/scene_32_first_push.json");
    let scene = &recorded.scene;
    let end = |engine: EngineKind| {
        let mut world = world(engine, scene, &recorded.start_poses());
        *recorded.play(world.as_mut()).last().unwrap()
    };
    let (rapier, mujoco) = (end(EngineKind::Rapier), end(EngineKind::Mujoco));
    let start = scene.start.objects[0];
    assert!(
        (rapier[0] - start.x).hypot(rapier[1] - start.y) > 0.1 && rapier[2] - start.theta < -0.3,
        "the hand carries the box 0.14 m and turns it 0.4 rad: {rapier:?} from {start:?}"
    );
    assert!(
        (rapier[0] - mujoco[0]).hypot(rapier[1] - mujoco[1]) < 0.008
            && (rapier[2] - mujoco[2]).abs() < 0.05,
        "rapier {rapier:?}, MuJoCo {mujoco:?}"
    );
}

#[test]
fn pushed_at_height_the_model_with_the_loaded_edge_ends_where_the_3d_engine_does() {
    use pushplan::planning::path::{simulate, PathControl};
    use pushplan::{EeAction, Propagator};
    // A small round pusher (1 cm across) pushes the benchmark's goal box (0.102 m square,
    // 0.215 m tall) 0.1 m along +x, 3 or 4.5 cm off its centre line, high up. In 3D the
    // table carries such a push mostly under the box's leading edge; with the support
    // pressure uniform the planar model ends 15-26 mm from the engine's box, with the
    // pressure the push loads (the default) within 5 mm (`examples/push_height`).
    let scene = |height: f64, offset: f64, pressure_shift: bool| {
        let yaml = format!(
            "robot: {{type: planar_hand, shape: {{type: cylinder, radius: 0.005, height: 0.008}}, \
               start: [0.415, {offset}, 0.0], height: {height}}}
table: {{height: 0.76, x: [0.27, 1.03], y: [-0.6, 0.6]}}
objects:
  - {{name: box, shape: {{type: box, size: [0.102, 0.102, 0.215]}}, pose: [0.4715, 0.0, 0.0], \
      mass: 1.0, mu_g: 0.4, mu_c: 0.3}}
goal: {{object: box, center: [0.9, 0.3], radius: 0.1}}
physics: {{tipping_margin: 0.0, pressure_shift: {pressure_shift}}}"
        );
        Scene::from_yaml(&yaml, Path::new("tests/push-at-height.yaml")).unwrap()
    };
    for (height, offset) in [(0.075, 0.03), (0.1, 0.03), (0.075, 0.045), (0.1, 0.045)] {
        let push = |scene: &Scene| {
            let control = PathControl {
                action: EeAction::planar(0.1, 0.0, 0.0),
                steps: 100,
            };
            let path = simulate(&mut Propagator::new(scene), &scene.start, &[control], true);
            assert!(path.valid(), "{:?}", path.stopped_by);
            path
        };
        let (uniform, loaded) = (
            push(&scene(height, offset, false)),
            push(&scene(height, offset, true)),
        );
        let world_scene = scene(height, offset, true);
        let joints: Vec<DVector<f64>> = loaded.step_states.iter().map(|s| s.q.clone()).collect();
        let mut poses = Vec::new();
        world_scene
            .robot
            .chain
            .forward_kinematics(&joints[0], &mut poses);
        let mut world = RapierWorld::new(&world_scene, &world_scene.start.objects, &poses);
        world.follow(&world_scene.robot.chain, &joints, world_scene.planner.step);
        let engine = world.object_pose2(0).translation();
        let off = |path: &pushplan::planning::path::SimulatedPath| {
            (path.final_state().objects[0].translation() - engine).norm()
        };
        assert!(
            off(&loaded) < 0.006 && off(&loaded) < 0.5 * off(&uniform),
            "height {height}, offset {offset}: loaded {:.1} mm, uniform {:.1} mm from the 3D box",
            1e3 * off(&loaded),
            1e3 * off(&uniform)
        );
    }
}

/// The closed-loop tests' executor, re-planning with `planner`: searches of 10 s at most,
/// shortcut for 0.5 s and polished for 2 s of work, seed 1, `max_replans` searches and 60 s of searching per trial at most, the default
/// tolerance and execution (rapier), repairs searched ahead and no mends (as by default).
fn closed_loop(
    planner: pushplan::planning::PlannerKind,
    max_replans: usize,
) -> pushplan::planner::closed_loop::ClosedLoop {
    use pushplan::planner::closed_loop::{ClosedLoop, ClosedLoopSettings};
    use pushplan::planning::execute::{ExecuteSettings, DRIFT};
    ClosedLoop {
        search: &pushplan::bridge::OmplSearch,
        settings: ClosedLoopSettings {
            planner,
            replan_time: 10.0,
            replan_threads: 1,
            replan_shortcut: 0.5,
            polish: 2.0,
            seed: 1,
            max_replans,
            search_budget: 60.0,
            tolerance: DRIFT,
            leg: 0.1,
            repair_ahead: true,
            mend: 0.0,
        },
        execution: ExecuteSettings::default(),
    }
}

/// The plan `pushplan plan` makes of the scene file at `scene_path` on one thread, written
/// to `plan_path`, and its scene.
fn planned(
    scene_path: &Path,
    plan_path: &Path,
) -> (pushplan::planning::plan_file::PlanFile, Scene) {
    common::plan_solved(scene_path.to_str().unwrap(), plan_path, &["--threads", "1"]);
    let plan = pushplan::planning::plan_file::PlanFile::read(plan_path).unwrap();
    let scene = plan.load_scene(plan_path).unwrap();
    (plan, scene)
}

/// Closed loop against a world that is not the model: the box stands 10 cm to the side of
/// where the scene says and grips the table twice as hard (6 cm left it inside the disc
/// less the goal margin of 6 cm, 9 cm 8 mm inside the disc). Played open loop, the plan
/// pushes past it and misses; closed loop, the first observation finds the box where it
/// is, the rest of the plan is re-simulated from there and misses, and the plan searched
/// from the observed state brings the box into the goal disc. Where the rest is still
/// valid but ends short, it is kept and only an ending searched (a repair).
#[test]
fn closed_loop_reaches_the_goal_where_the_world_differs_and_open_loop_misses() {
    use pushplan::planner::closed_loop::{ClosedLoop, ClosedLoopSettings};
    use pushplan::planning::execute::{execute_in_world, ExecuteSettings};
    let scratch = common::Scratch::new("closed-loop");
    let plan_path = scratch.join("plan.json");
    let scene_path = "scenes/planar_hand_single_object.yaml";
    let (plan, scene) = planned(Path::new(scene_path), &plan_path);
    let mut world = scene.clone();
    // Sideways of the push (the hand starts at y = 0 behind the box, the goal lies at +y).
    world.start.objects[0].y -= 0.1;
    world.objects[0].mu_g *= 2.0;

    let open = execute_in_world(&world, &scene, &plan, &ExecuteSettings::default()).unwrap();
    assert!(!open.reached, "open loop misses: {open:?}");

    let closed_loop = closed_loop(plan.settings.planner, 10);
    let closed = closed_loop
        .execute(&scene, &plan.path_controls(), &world)
        .unwrap();
    assert!(closed.reached, "closed loop reaches the goal: {closed:?}");
    assert!(closed.replans >= 1, "it re-planned: {closed:?}");
    assert!(
        closed.repairs >= 1 && closed.repairs <= closed.replans,
        "some re-plans kept the rest and added an ending: {closed:?}"
    );
    assert!(
        closed.tipped.is_empty() && closed.stopped.is_none(),
        "{closed:?}"
    );
    // Pushed below its tipping height, the box rocks no more than a hundredth of a radian.
    assert!(closed.tilt_onsets.is_empty(), "{:?}", closed.tilt_onsets);
    assert!(
        closed.search_time > 0.0 && closed.search_time < 60.0,
        "{closed:?}"
    );

    // With no search time to spend the same trial stops, saying why, where the rest first
    // misses.
    let thoughtless = ClosedLoop {
        settings: ClosedLoopSettings {
            search_budget: 1e-9,
            ..closed_loop.settings.clone()
        },
        ..closed_loop
    };
    let stopped = thoughtless
        .execute(&scene, &plan.path_controls(), &world)
        .unwrap();
    assert!(!stopped.reached, "{stopped:?}");
    assert!(
        stopped
            .stopped
            .as_deref()
            .is_some_and(|why| why.contains("s of search time are spent")),
        "{stopped:?}"
    );
}

/// A closed loop mends the rest where it fails, with no search: the planar hand of
/// `tests/data/hand_round_a_stick.yaml` swings out and back (to y = 0.08 m) on its way
/// to push the box into the goal disc, where the world has a thin stick the scene has
/// elsewhere. From the first observation the rest stops being valid (the hand closes in
/// on the stick where a push would tip it); a detour round it, then the rest's pushes as
/// planned, reaches the goal in rapier with the stick untouched (0.2 s of work). With no
/// mend (the default), the executor must search instead.
#[test]
fn a_closed_loop_mends_the_rest_round_an_object_the_plan_did_not_expect() {
    use pushplan::planner::closed_loop::{ClosedLoop, ClosedLoopSettings};
    use pushplan::planning::path::PathControl;
    use pushplan::EeAction;
    let scene = Scene::load("tests/data/hand_round_a_stick.yaml").unwrap();
    let control = |vx: f64, vy: f64| PathControl {
        action: EeAction::planar(vx, vy, 0.0),
        steps: 20,
    };
    let mut plan = vec![control(0.2, 0.2), control(0.2, 0.2)];
    plan.extend([control(0.2, -0.2), control(0.2, -0.2)]);
    plan.extend((0..7).map(|_| control(0.2, 0.0)));
    let mut world = scene.clone();
    world.start.objects[1] = pushplan::Pose2::new(0.45, 0.11, 0.0);

    let searching = closed_loop(pushplan::planning::PlannerKind::PushKpiece, 10);
    let closed_loop = ClosedLoop {
        settings: ClosedLoopSettings {
            mend: 0.2,
            ..searching.settings.clone()
        },
        execution: searching.execution.clone(),
        ..searching
    };
    let mended = closed_loop.execute(&scene, &plan, &world).unwrap();
    assert!(mended.reached, "{mended:?}");
    assert!(mended.mends >= 1, "{mended:?}");
    assert!(
        mended.invalid_rest_details[0].contains("'stick'"),
        "{mended:?}"
    );
    // No search: the mend alone got round the stick, which never tipped.
    assert_eq!(
        (mended.replans, mended.failed_replans, mended.search_time),
        (0, 0, 0.0),
        "{mended:?}"
    );
    assert!(
        mended.tipped.is_empty() && mended.tilt_onsets.is_empty(),
        "{mended:?}"
    );

    let unmended = searching.execute(&scene, &plan, &world).unwrap();
    assert_eq!(unmended.mends, 0);
    assert!(unmended.search_time > 0.0, "{unmended:?}");
}

/// A trial names the control during which an object tipped in the world. The 1 cm tall
/// hand of `common::thin_hand_yaml` pushes a 0.1 m box (0.3 m tall) at 0.08 m. The
/// model's table grips it with `mu_g` 0.4: sliding it takes 0.4 m g, whose moment about
/// the box's far bottom edge (0.032 m m g) stays within its weight's at the half width
/// shrunk by the tipping margin (0.7 x 0.05 m), so the model has it slide. The world's grips it with `mu_g` 1.0
/// and the hand is slippery (`mu_c` 0.05): 0.08 m m g against 0.05 m m g for the weight
/// and 0.005 for the hand's friction holding the near face down (0.05 of the push, 0.1 m
/// out), so the first push tips it. It cannot tip before the hand first touches it: not
/// before the first control the model moves it in.
#[test]
fn a_closed_loop_trial_names_the_control_an_object_tipped_in() {
    let scratch = common::Scratch::new("closed-loop-tipped");
    let (scene_path, world_path) = (scratch.join("scene.yaml"), scratch.join("world.yaml"));
    let tall_box = |mu_g| {
        common::thin_hand_yaml(
            "box",
            "{type: box, size: [0.1, 0.1, 0.3]}",
            0.55,
            0.08,
            mu_g,
            "",
        )
    };
    std::fs::write(&scene_path, tall_box(0.4)).unwrap();
    let slippery_hand = tall_box(1.0).replace("mu_c: 0.3", "mu_c: 0.05");
    std::fs::write(&world_path, slippery_hand).unwrap();
    let (plan, scene) = planned(&scene_path, &scratch.join("plan.json"));
    let world = Scene::load(&world_path).unwrap();
    let controls = plan.path_controls();
    let model = pushplan::planning::Problem::new(scene.clone(), plan.settings.planner)
        .simulate(&controls, false);
    let start = scene.start.objects[0];
    // The first control (counted from 1) at whose end the model has moved the box.
    let first_push = 1 + model.states[1..]
        .iter()
        .position(|s| (s.objects[0].translation() - start.translation()).norm() > 1e-4)
        .expect("the plan pushes the box");

    let mut closed_loop = closed_loop(plan.settings.planner, 4);
    closed_loop.settings.search_budget = 10.0;
    let closed = closed_loop.execute(&scene, &controls, &world).unwrap();
    assert_eq!(closed.tipped, ["box"], "{closed:?}");
    let during = closed.tipped_during[0];
    assert!(
        during >= first_push && during <= closed.controls_played,
        "tipped during control {during}, the first push is control {first_push}: {closed:?}"
    );
    assert!(!closed.reached, "{closed:?}");

    // It started to tip under the hand: the world when it first tilted beyond the onset,
    // in `replan --observed`'s format, has the hand touching the box (parry's distance
    // between the hand's plate and the box stood upright at its recorded planar pose; a
    // tilt of 0.02 rad moves the box's face by 1.6 mm at the hand's 8 cm).
    use pushplan::planner::closed_loop::TILT_ONSET;
    use pushplan::planning::execute::TIPPED_TILT;
    let [onset] = closed.tilt_onsets.as_slice() else {
        panic!("one object started to tip: {:?}", closed.tilt_onsets)
    };
    assert_eq!(onset.object, "box");
    assert!(
        onset.control >= first_push && onset.control <= during,
        "{onset:?}, tipped during control {during}"
    );
    assert!(
        onset.tilt > TILT_ONSET && onset.tilt < TIPPED_TILT,
        "{onset:?}"
    );
    let state = onset.world.state(&scene, Path::new("onset")).unwrap();
    let (q, b) = (&state.q, state.objects[0]);
    use parry3d_f64::{math::Isometry, math::Vector, query, shape::Cuboid};
    let at =
        |x: f64, y: f64, z: f64, yaw: f64| Isometry::new(Vector::new(x, y, z), Vector::z() * yaw);
    let plate = Cuboid::new(Vector::new(0.02, 0.06, 0.005));
    let tall_box = Cuboid::new(Vector::new(0.05, 0.05, 0.15));
    let gap = query::distance(
        &at(q[0], q[1], 0.08, q[2]),
        &plate,
        &at(b.x, b.y, 0.15, b.theta),
        &tall_box,
    )
    .unwrap();
    assert!(gap < 0.005, "the hand {gap} m from the box: {onset:?}");
    // The onset names it: the hand first, at the box within the plate's height span
    // (0.075 to 0.085 m above the table), as far from it as parry says.
    let touch = &onset.touching[0];
    assert_eq!(touch.link, "hand", "{onset:?}");
    assert!((0.075..=0.085).contains(&touch.height), "{onset:?}");
    assert!(
        (touch.distance.max(0.0) - gap).abs() < 1e-3,
        "parry: {gap} m; {onset:?}"
    );
}

/// A world with an obstacle on the plan's way that the model's scene has out of the way:
/// the planar hand's scene with a glass too slender to push upright (it tips below the
/// hand's height) off the plan's way, planned on one thread in `scratch`; in the world the
/// glass stands where the hand passes three quarters of the way through the controls after
/// the second. The plan, its scene and the world.
fn glass_on_the_plans_way(
    scratch: &common::Scratch,
) -> (pushplan::planning::plan_file::PlanFile, Scene, Scene) {
    use pushplan::planning::Problem;
    let scene_path = scratch.join("scene.yaml");
    let base = std::fs::read_to_string("scenes/planar_hand_single_object.yaml").unwrap();
    // r / mu_g = 0.015 / 0.4 = 0.0375 m, below the hand's 0.05 m: pushing it tips it.
    let glass = "  - name: glass\n    shape: {type: cylinder, radius: 0.015, height: 0.12}\n    pose: [0.32, -0.5, 0.0]\n    mass: 0.2\n    mu_g: 0.4\n    mu_c: 0.3\ngoal:";
    std::fs::write(&scene_path, base.replacen("goal:", glass, 1)).unwrap();
    let plan_path = scratch.join("plan.json");
    let (plan, scene) = planned(&scene_path, &plan_path);
    let controls = plan.path_controls();
    assert!(controls.len() >= 4, "{} controls", controls.len());

    // Where the hand is (its centre, x and y are its first joints) half way through the
    // plan's second half; the glass in the world stands there.
    let simulated = Problem::new(scene.clone(), plan.settings.planner).simulate(&controls, true);
    assert!(simulated.valid());
    let steps: usize = controls[..2].iter().map(|c| c.steps).sum();
    let at = steps + 3 * (simulated.step_states.len() - 1 - steps) / 4;
    let hand = &simulated.step_states[at].q;
    let mut world = scene.clone();
    world.start.objects[1].x = hand[0];
    world.start.objects[1].y = hand[1];
    (plan, scene, world)
}

/// Closed loop in `glass_on_the_plans_way`'s world, where the glass stands where the hand
/// passes in the plan's third control or later. The first observation finds the rest of
/// the plan invalid there; the rest is kept up to where it stops being valid and only an
/// ending is searched from there (a repair), not a new plan from the start: every re-plan
/// is a repair.
#[test]
fn closed_loop_keeps_the_rest_up_to_where_it_stops_being_valid_and_repairs_from_there() {
    use pushplan::planning::Problem;
    let scratch = common::Scratch::new("closed-loop-invalid-rest");
    let (plan, scene, world) = glass_on_the_plans_way(&scratch);
    let controls = plan.path_controls();
    let playing = Problem::new(world.clone(), plan.settings.planner).simulate(&controls, false);
    let invalid_from = playing.stopped_by.as_ref().map(|s| s.0);
    assert!(
        invalid_from.is_some_and(|i| i >= 2),
        "the plan is invalid in the world from its third control or later: {:?}",
        playing.stopped_by
    );

    // Two re-plans allowed: the repair searched ahead is taken up at the first observation
    // after it has taken no longer than the controls played meanwhile (wall clock against
    // the execution's pace), after the first control on a fast machine, later on a slow
    // one; from there the world (rapier) has drifted some nanometres from the model's
    // prediction the ending was searched from, and where the ending passes close by the
    // glass that can flip a rule (the hand closing in 0.2 mm from it): the rest is then
    // kept up to there and a second ending searched.
    let mut closed_loop = closed_loop(plan.settings.planner, 2);
    // Legs of 0.3 m: the valid part ends within a leg of the goal (the box starts 0.17 m
    // out), so its repair is searched ahead.
    closed_loop.settings.leg = 0.3;
    let closed = closed_loop.execute(&scene, &controls, &world).unwrap();
    assert!(closed.invalid_rests >= 1, "{closed:?}");
    // Counted by the rule the rest broke: the first observation is the world's start, where
    // the model's re-simulation above stopped.
    let rule = playing.stopped_by.as_ref().unwrap().1.kind();
    assert!(
        closed.invalid_rest_rules.get(rule).is_some_and(|&n| n >= 1),
        "{rule}: {closed:?}"
    );
    assert_eq!(
        closed.invalid_rest_rules.values().sum::<usize>(),
        closed.invalid_rests,
        "{closed:?}"
    );
    // Each verdict in full, in order: the first, from the world's start, names the glass.
    assert_eq!(closed.invalid_rest_details.len(), closed.invalid_rests);
    assert!(
        closed.invalid_rest_details[0].contains("'glass'"),
        "{closed:?}"
    );
    assert!(
        (1..=2).contains(&closed.replans) && closed.repairs == closed.replans,
        "every re-plan kept the valid part and searched an ending: {closed:?}"
    );
    assert!(closed.controls_played >= 2, "{closed:?}");
    assert!(
        closed.tipped.is_empty(),
        "the glass is not tipped: {closed:?}"
    );
    // The repair was searched while the arm played the valid part: the arm waited for less
    // of it than it took (none of it, where the controls played meanwhile lasted longer).
    let repair = &closed.searches[0];
    assert!(repair.ahead && repair.seconds > 0.0, "{repair:?}");
    assert!(repair.waited < repair.seconds, "{repair:?}");
    // Searched with the arm waiting, the same repair, and the latency counts its search.
    closed_loop.settings.repair_ahead = false;
    let waiting = closed_loop.execute(&scene, &controls, &world).unwrap();
    assert!(
        (1..=2).contains(&waiting.replans) && waiting.repairs == waiting.replans,
        "{waiting:?}"
    );
    let repair = &waiting.searches[0];
    assert!(
        !repair.ahead && repair.waited == repair.seconds,
        "{repair:?}"
    );
    assert!(waiting.replan_latencies[0] >= repair.seconds, "{waiting:?}");
    // Where the valid part ends more than a leg from the goal (a leg of 1 mm here), the
    // repair is not searched ahead but from where the arm stands, as with the arm waiting.
    closed_loop.settings.repair_ahead = true;
    closed_loop.settings.leg = 0.001;
    let far = closed_loop.execute(&scene, &controls, &world).unwrap();
    assert!(
        (1..=2).contains(&far.replans) && far.repairs == far.replans,
        "{far:?}"
    );
    assert!(!far.searches[0].ahead, "{far:?}");
}

/// The executor of `closed_loop` fed the model's own predictions as its observations,
/// from `scene`'s start along `controls`: how it ended, the controls played, the last
/// observation and the trial.
fn played_on_predictions(
    closed_loop: &pushplan::planner::closed_loop::ClosedLoop,
    scene: &Scene,
    controls: &[pushplan::planning::path::PathControl],
) -> (
    pushplan::planner::closed_loop::Step,
    usize,
    pushplan::State,
    pushplan::planner::closed_loop::ClosedLoopTrial,
) {
    played_on_observations(closed_loop, scene, controls, |_, predicted| predicted)
}

/// As [`played_on_predictions`], the world observed after each control as `world(controls
/// played, the model's prediction)` says.
fn played_on_observations(
    closed_loop: &pushplan::planner::closed_loop::ClosedLoop,
    scene: &Scene,
    controls: &[pushplan::planning::path::PathControl],
    world: impl Fn(usize, pushplan::State) -> pushplan::State,
) -> (
    pushplan::planner::closed_loop::Step,
    usize,
    pushplan::State,
    pushplan::planner::closed_loop::ClosedLoopTrial,
) {
    use pushplan::planner::closed_loop::Step;
    let mut executor = closed_loop.executor(scene, controls);
    let mut observed = scene.start.clone();
    let mut played = 0;
    let end = loop {
        match executor.step(&observed) {
            Step::Play { predicted, .. } => {
                played += 1;
                observed = world(played, predicted);
            }
            other => break other,
        }
    };
    (end, played, observed, executor.trial().clone())
}

/// An observation with the hand 25 mm inside the box, deeper than the 20 mm an
/// observation may be off (the model has no state near it), is met by retracing the
/// control just played: its trajectory backwards, ending where it began, the box held where
/// it was seen; once, so the same observation again stops the execution. From where the
/// arm retreated to, the box 5 mm clear of the hand, the execution goes on.
#[test]
fn a_link_deep_in_an_object_retraces_the_control_just_played() {
    use pushplan::planner::closed_loop::Step;
    let scene = thin_hand_and_box(0.05, 0.8, "");
    let push = straight_ahead(11, 30);
    let closed_loop = closed_loop(pushplan::planning::PlannerKind::PushKpiece, 0);
    let mut executor = closed_loop.executor(&scene, &push);
    let Step::Play {
        trajectory: first,
        predicted,
        ..
    } = executor.step(&scene.start)
    else {
        panic!("the first control is played");
    };
    // The hand's front face 3 cm on (0.45 m), the box's near face 25 mm behind it.
    assert!((predicted.q[0] - 0.43).abs() < 1e-6, "{:?}", predicted.q);
    let mut deep = predicted.clone();
    deep.objects[0].x = 0.45 + RESERVE_BOX.0 - 0.025;
    assert!(
        scene.with_start(&deep, Path::new("deep")).is_err(),
        "the model refuses the observation"
    );
    let Step::Play {
        control,
        trajectory,
        predicted: back,
    } = executor.step(&deep)
    else {
        panic!("the arm retraces the control: {:?}", executor.trial());
    };
    assert_eq!(executor.trial().backoffs, 1);
    assert_eq!(
        executor.trial().backoffs_at,
        [2],
        "the second control played"
    );
    assert_eq!(control.action.velocity, [-0.1, 0.0, 0.0]);
    assert_eq!(trajectory.q.first().unwrap(), predicted.q.as_slice());
    assert_eq!(trajectory.q.last(), first.q.first());
    let lasting =
        |t: &pushplan::planning::trajectory::Trajectory| t.times.last().unwrap() - t.times[0];
    assert!((lasting(&trajectory) - lasting(&first)).abs() < 1e-9);
    assert!(trajectory.times.windows(2).all(|t| t[0] < t[1]));
    let held = [deep.objects[0].x, 0.0, 0.0];
    assert!(trajectory.objects.iter().all(|o| o[0] == held));
    assert_eq!(back.q, scene.start.q);
    assert_eq!(back.objects, deep.objects);
    // Once: the same observation again (the arm not retreated) stops.
    let mut again = executor_after_one_backoff(&closed_loop, &scene, &push, &deep);
    assert!(
        matches!(again.step(&deep), Step::Stopped(why) if why.contains("no valid start")),
        "{:?}",
        again.trial()
    );
    // Retreated: the box stands 5 mm clear of the hand, and the executor goes on.
    assert!(
        matches!(executor.step(&back), Step::Play { .. }),
        "{:?}",
        executor.trial()
    );
}

/// The retrace is for what moving the arm back undoes. An observation the model refuses
/// for something else is not retraced, even where a link is also deep in an object: the
/// box 10 mm into the hand (which the model takes as touching it, moved out) and
/// standing 2 cm into a post beside the push (which no arm motion mends) stops the
/// execution at once, with the reason.
#[test]
fn an_observation_refused_for_what_a_retrace_cannot_mend_stops_without_one() {
    use pushplan::planner::closed_loop::Step;
    use pushplan::validity::{check_state, Invalid};
    // A post of 3 cm radius beside the push, 2 cm clear of the box's path.
    let post = "obstacles:\n  - {name: post, shape: {type: cylinder, radius: 0.03, height: 0.3}, pose: {xyz: [0.49, 0.1, 0.91]}}";
    let scene = thin_hand_and_box(0.05, 0.8, post);
    let push = straight_ahead(11, 30);
    let closed_loop = closed_loop(pushplan::planning::PlannerKind::PushKpiece, 0);
    let mut executor = closed_loop.executor(&scene, &push);
    let Step::Play { predicted, .. } = executor.step(&scene.start) else {
        panic!("the first control is played: {:?}", executor.trial());
    };
    // The hand's front face at 0.45 m: the box's near face 10 mm behind it, the box's
    // side (y up to 0.09) 2 cm into the post (y from 0.07).
    let mut observed = predicted.clone();
    observed.objects[0].x = 0.45 + RESERVE_BOX.0 - 0.010;
    observed.objects[0].y = 0.04;
    assert!(
        matches!(
            check_state(&scene, &observed),
            Err(Invalid::ArmPenetratesObject { .. })
        ),
        "the first rule the raw observation breaks is the hand's: {:?}",
        check_state(&scene, &observed)
    );
    let refused = scene
        .with_start(&observed, Path::new("observed"))
        .unwrap_err();
    assert!(
        matches!(
            refused,
            pushplan::Error::InvalidStart {
                rule: Invalid::ObjectHitsObstacle { .. },
                ..
            }
        ),
        "the box taken out of the hand still stands in the post: {refused}"
    );
    assert!(
        matches!(executor.step(&observed), Step::Stopped(why) if why.contains("overlaps obstacle 'post'")),
        "{:?}",
        executor.trial()
    );
    assert_eq!(executor.trial().backoffs, 0);
}

/// An executor of `push` in `scene` that has played its first control and retraced it
/// after the observation `deep`.
fn executor_after_one_backoff(
    closed_loop: &pushplan::planner::closed_loop::ClosedLoop,
    scene: &Scene,
    push: &[pushplan::planning::path::PathControl],
    deep: &pushplan::State,
) -> pushplan::planner::closed_loop::Executor {
    use pushplan::planner::closed_loop::Step;
    let mut executor = closed_loop.executor(scene, push);
    assert!(matches!(executor.step(&scene.start), Step::Play { .. }));
    assert!(matches!(executor.step(deep), Step::Play { .. }));
    executor
}

/// `n` controls moving the planar hand straight ahead (+x) at 0.1 m/s, `steps` each.
fn straight_ahead(n: usize, steps: usize) -> Vec<pushplan::planning::path::PathControl> {
    use pushplan::planning::path::PathControl;
    use pushplan::robot::EeAction;
    (0..n)
        .map(|_| PathControl {
            action: EeAction::planar(0.1, 0.0, 0.0),
            steps,
        })
        .collect()
}

/// Half-width (m) and support friction of the box the reserve tests push or close in on.
const RESERVE_BOX: (f64, f64) = (0.05, 0.4);

/// The thin hand (1 cm thick), its lowest point `lowest` m above the table, a box of
/// [`RESERVE_BOX`] 20 cm tall at x = 0.6 (its near face 0.13 m ahead of the hand's front
/// face at 0.42, above the hand's top), the goal disc centred at (`goal_x`, 0) and
/// `physics` (a scene's `physics:` line).
fn thin_hand_and_box(lowest: f64, goal_x: f64, physics: &str) -> Scene {
    let (b, mu_g) = RESERVE_BOX;
    let hand = 0.01;
    let shape = format!("{{type: box, size: [{}, {}, 0.2]}}", 2.0 * b, 2.0 * b);
    // The thin hand's frame half its thickness above its lowest point.
    let mut scene = common::thin_hand_scene("box", &shape, 0.6, lowest + 0.5 * hand, mu_g, physics);
    if let pushplan::scene::Goal::ObjectInDisc { center, .. } = &mut scene.goal {
        *center = nalgebra::Vector2::new(goal_x, 0.0);
    }
    scene
}

/// The rest of a plan is judged with the planner's whole tipping margin
/// (`physics.tipping_margin`, 0.3), where the object clearance is half spent. A box of
/// half-width b = 0.05 m on mu_g = 0.4, pushed flat on through its centre by a hand whose
/// lowest point is h above the table, slides with the table's whole friction mu_g m g,
/// which shifts its support pressure's centre by mu_g h (closed form): it tips beyond
/// h = b / mu_g = 0.125 m, and with the margin m the model refuses h > (1 - m) b / mu_g,
/// 0.0875 m with the whole margin (0.106 m with half of it, the rule before: a world with
/// 1.2 times the support friction tips the box beyond 0.104 m). A straight push into the
/// goal disc at h = 0.080 m is accepted by the planner's model and played to the goal by
/// the executor without a search; at h = 0.097 m the planner's model refuses it, and the
/// executor refuses it too, before the first control.
#[test]
fn the_rest_is_judged_with_the_whole_tipping_margin() {
    use pushplan::planner::closed_loop::Step;
    use pushplan::planning::{PlannerKind, Problem};
    let ((b, mu_g), margin) = (RESERVE_BOX, 0.3);
    let whole = (1.0 - margin) * b / mu_g;
    // The goal disc straight ahead.
    let physics = format!("physics: {{tipping_margin: {margin}}}");
    let scene_at = |lowest: f64| thin_hand_and_box(lowest, 0.8, &physics);
    // Straight ahead at 0.1 m/s: 0.13 m to the box, then 0.2 m pushing it, its centre to
    // the goal's.
    let push = straight_ahead(11, 30);
    let planner = PlannerKind::PushKpiece;
    // No re-plans: a rest refused stops the execution.
    let closed_loop = closed_loop(planner, 0);
    for (lowest, kept) in [(0.080, true), (0.097, false)] {
        assert!((lowest < whole) == kept && lowest < (1.0 - 0.5 * margin) * b / mu_g);
        let scene = scene_at(lowest);
        // The planner's model accepts the push below the margin and refuses it above.
        let planned = Problem::new(scene.clone(), planner).simulate(&push, false);
        let refused = planned.stopped_by.as_ref().map(|(_, rule)| rule.kind());
        if kept {
            assert!(refused.is_none(), "h = {lowest}: {refused:?}");
        } else {
            assert!(
                matches!(refused, Some("tips" | "closes in at tipping height")),
                "h = {lowest}: {refused:?}"
            );
        }
        // The executor fed the model's own predictions.
        let (end, played, observed, trial) = played_on_predictions(&closed_loop, &scene, &push);
        if kept {
            assert!(
                end == Step::Finished && played == push.len() && trial.invalid_rests == 0,
                "h = {lowest}: {end:?} {trial:?}"
            );
            assert!(trial.searches.is_empty(), "{trial:?}");
            assert!(scene.goal.task_distance(&observed) < 0.0, "{observed:?}");
        } else {
            let rules: Vec<&String> = trial.invalid_rest_rules.keys().collect();
            assert!(
                matches!(end, Step::Stopped(_))
                    && played == 0
                    && trial.invalid_rests == 1
                    && rules
                        .iter()
                        .all(|r| ["tips", "closes in at tipping height"].contains(&r.as_str())),
                "h = {lowest}: {end:?} {trial:?}"
            );
        }
    }
}

/// The rest of a plan is judged with the whole arm clearance (`physics.arm_clearance`,
/// 10 mm) for an object the world has moved, and with half of it for an object that
/// stands where it was first observed: the clearance is a tipping reserve against an
/// object being a few millimetres elsewhere, which an untouched object observed where it
/// stands is not. The thin hand, its lowest point at 0.115 m (where a push that slid the
/// box would tip it within the tipping margin: the previous test's closed form), moves
/// straight at a box that already stands in the goal disc, 1 mm a step, in two controls
/// (60 steps, then the rest), and stops short of it. Stopping 7 mm short, between the half
/// and the whole clearance, the planner's model refuses it ("closes in at tipping
/// height"); the executor plays it to its end where the box is observed where it stood,
/// and refuses the rest after the first control where the box is observed 5 mm to the
/// side (its face as far from the hand: only the world's having moved it differs).
/// Stopping 3 mm short, within half the clearance, the executor refuses it before the
/// first control.
#[test]
fn the_rest_keeps_the_whole_arm_clearance_from_objects_the_world_moved_and_half_from_others() {
    use pushplan::planner::closed_loop::Step;
    use pushplan::planning::path::PathControl;
    use pushplan::planning::{PlannerKind, Problem};
    let ((b, mu_g), clearance, lowest) = (RESERVE_BOX, 0.01, 0.115);
    let physics = format!("physics: {{arm_clearance: {clearance}}}");
    // The goal disc around the box.
    let scene = thin_hand_and_box(lowest, 0.6, &physics);
    // Above the height where a sliding push tips the box within the tipping margin.
    assert!(lowest > (1.0 - scene.physics.tipping_margin) * b / mu_g);
    assert!(scene.goal.task_distance(&scene.start) < 0.0);
    let planner = PlannerKind::PushKpiece;
    // No re-plans: a rest refused stops the execution.
    let closed_loop = closed_loop(planner, 0);
    let approach = |short_mm: usize| -> Vec<PathControl> {
        [60, 70 - short_mm]
            .iter()
            .flat_map(|&steps| straight_ahead(1, steps))
            .collect()
    };
    let planned = Problem::new(scene.clone(), planner).simulate(&approach(7), false);
    assert_eq!(
        planned.stopped_by.as_ref().map(|(_, rule)| rule.kind()),
        Some("closes in at tipping height")
    );
    // (mm short, the box's sideways shift (m) in the observation after the first control,
    // controls played, the rest kept to the end)
    for (short_mm, shift, played_expected, kept) in
        [(7, 0.0, 2, true), (7, 0.005, 1, false), (3, 0.0, 0, false)]
    {
        let case = format!("{short_mm} mm short, the box shifted {shift} m");
        let world = |played: usize, mut predicted: pushplan::State| {
            if played == 1 {
                predicted.objects[0].y += shift;
            }
            predicted
        };
        let (end, played, observed, trial) =
            played_on_observations(&closed_loop, &scene, &approach(short_mm), world);
        assert_eq!(played, played_expected, "{case}: {end:?} {trial:?}");
        if kept {
            assert!(
                end == Step::Finished && trial.invalid_rests == 0 && trial.searches.is_empty(),
                "{case}: {end:?} {trial:?}"
            );
            // The hand stopped short: the box did not move.
            assert_eq!(observed.objects[0], scene.start.objects[0]);
        } else {
            assert!(
                matches!(end, Step::Stopped(_))
                    && trial.invalid_rests == 1
                    && trial.invalid_rest_rules.get("closes in at tipping height") == Some(&1),
                "{case}: {end:?} {trial:?}"
            );
        }
    }
}

/// `pushplan replan PLAN --observed` on `observation` (written to the scratch folder) with
/// `more` options, the new plan to `replanned.json` there: exit status, stdout, stderr.
fn replan_observed(
    scratch: &common::Scratch,
    plan_path: &Path,
    observation: &pushplan::planning::observed::ObservedState,
    more: &[&str],
) -> (i32, String, String) {
    let observed = scratch.join("observed.json");
    std::fs::write(&observed, observation.to_json()).unwrap();
    let out = scratch.join("replanned.json");
    let args = [
        &[
            "replan",
            plan_path.to_str().unwrap(),
            "--observed",
            observed.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        more,
    ]
    .concat();
    common::pushplan_in(Path::new("."), &args)
}

/// An observation the model refuses as a start stops the trial, and the trial keeps it in
/// `replan --observed`'s format: `replan` on it refuses it the same way, without the
/// engine, so a refusal seen in a long run can be replayed and traced.
#[test]
fn a_refused_observation_is_kept_in_the_trial_and_replays_through_replan() {
    let scratch = common::Scratch::new("closed-loop-refused");
    let scene_path = Path::new("scenes/planar_hand_single_object.yaml");
    let plan_path = scratch.join("plan.json");
    let (plan, scene) = planned(scene_path, &plan_path);
    // The world's box stands 25 mm into the hand's front face (x = 0.42; the box is 10 cm
    // wide): deeper than an observation may be off (20 mm).
    let mut world = scene.clone();
    world.start.objects[0] = pushplan::Pose2::new(0.42 + 0.05 - 0.025, 0.0, 0.0);
    let trial = closed_loop(plan.settings.planner, 1)
        .execute(&scene, &plan.path_controls(), &world)
        .unwrap();
    assert!(!trial.reached && trial.controls_played == 0, "{trial:?}");
    assert!(
        trial
            .stopped
            .as_deref()
            .is_some_and(|why| why.starts_with("the observed state is no valid start")),
        "{trial:?}"
    );
    let refused = trial
        .refused_observation
        .expect("the refused observation kept");
    let observed_box = refused.objects["box"];
    assert!(
        (observed_box[0] - 0.445).abs() < 1e-3 && observed_box[1].abs() < 1e-3,
        "where the world has the box: {observed_box:?}"
    );
    let (code, stdout, stderr) = replan_observed(&scratch, &plan_path, &refused, &["--at", "0"]);
    assert_eq!(code, 2, "{stdout}{stderr}");
    assert!(
        stderr.contains("objects.box") && stderr.contains("an observation may be off"),
        "{stderr}"
    );
}

/// A search that finds no plan to the scene's goal: from anywhere (`goal_from_within`
/// None: the executor's path where searching fails, made certain; the real search finds
/// one in this scene within milliseconds), or from farther than the given distance (m)
/// from the centre of the goal disc (a hard scene's search from far off, made certain).
/// Any other goal (a leg's) it searches with the real search.
struct FindsNothing {
    goal_from_within: Option<(nalgebra::Vector2<f64>, f64)>,
}

impl pushplan::planner::Search for FindsNothing {
    fn solve(
        &self,
        scene: &pushplan::Scene,
        settings: &pushplan::planning::RunSettings,
        progress: Option<fn(&pushplan::planner::SearchProgress, &str)>,
    ) -> Result<pushplan::planner::Found, String> {
        let searched = match (&scene.goal, self.goal_from_within) {
            (_, None) => false,
            (pushplan::scene::Goal::ObjectInDisc { object, center, .. }, Some((goal, near))) => {
                let from = (scene.start.objects[*object].translation() - center).norm();
                (center - goal).norm() > 1e-12 || from <= near
            }
            _ => false,
        };
        if searched {
            return pushplan::bridge::OmplSearch.solve(scene, settings, progress);
        }
        Ok(pushplan::planner::Found {
            summary: Default::default(),
            search: Default::default(),
            controls: Vec::new(),
            states: Vec::new(),
            robustness: None,
        })
    }

    fn reach(
        &self,
        _scene: &pushplan::Scene,
        _object: &str,
        _from: Option<&pushplan::State>,
        _settings: &pushplan::planner::ReachSettings,
    ) -> Result<pushplan::planner::Reached, String> {
        Err("not asked for here".into())
    }

    fn benchmark(
        &self,
        _scene: &Path,
        _settings: &pushplan::planning::RunSettings,
        _run: u32,
        _log: &Path,
    ) -> Result<(), String> {
        Err("not asked for here".into())
    }
}

/// A trial whose searches found nothing keeps the observation the last one started from,
/// in `replan --observed`'s format: `replan` on it, with the real search, searches from
/// there again and finds the plan, without the engine. What the sessions that traced
/// benchmark 34's lost trials had to print by hand.
#[test]
fn the_observation_a_search_failed_from_is_kept_and_searches_again_through_replan() {
    let scratch = common::Scratch::new("closed-loop-failed-search");
    let scene_path = Path::new("scenes/planar_hand_single_object.yaml");
    let plan_path = scratch.join("plan.json");
    let (plan, scene) = planned(scene_path, &plan_path);
    // The world of `closed_loop_reaches_the_goal_where_the_world_differs_and_open_loop_misses`:
    // the rest misses the goal from the first observation on.
    let mut world = scene.clone();
    world.start.objects[0].y -= 0.1;
    world.objects[0].mu_g *= 2.0;
    let mut executor = closed_loop(plan.settings.planner, 2);
    executor.search = &FindsNothing {
        goal_from_within: None,
    };
    let trial = executor
        .execute(&scene, &plan.path_controls(), &world)
        .unwrap();
    assert!(
        !trial.reached && trial.replans == 0 && trial.failed_replans == 2,
        "{trial:?}"
    );
    assert!(
        trial.searches.len() == 2
            && trial
                .searches
                .iter()
                .all(|r| r.found == pushplan::planner::closed_loop::SearchFound::Nothing),
        "{trial:?}"
    );
    let failed_from = trial
        .failed_search_from
        .expect("the observation of the last failed search kept");
    // The world's box is where the observation has it, 6 cm to the side of the scene's
    // start (the arm has pushed it since, along its first controls, if at all: not back).
    let observed_box = failed_from.objects["box"];
    assert!(
        observed_box[1] < scene.start.objects[0].y - 0.03,
        "{observed_box:?} against the scene's {:?}",
        scene.start.objects[0]
    );
    let (code, stdout, stderr) =
        replan_observed(&scratch, &plan_path, &failed_from, &["--threads", "1"]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let replanned =
        pushplan::planning::plan_file::PlanFile::read(&scratch.join("replanned.json")).unwrap();
    assert!(replanned.solved, "{stdout}{stderr}");
}

/// With nothing valid left to play near the goal disc, the arm waits on searches of eight
/// times `replan_time` from the first, and two of them finding nothing stop the trial. In
/// `glass_on_the_plans_way`'s world no search finds a plan: the arm plays the rest as far
/// as it is valid, its searches meanwhile getting `replan_time` and more, then waits. Legs
/// are off, so no search is a leg first.
#[test]
fn near_the_disc_the_arm_waits_on_two_full_length_searches_at_most() {
    let scratch = common::Scratch::new("closed-loop-waiting-near");
    let (plan, scene, world) = glass_on_the_plans_way(&scratch);
    let controls = plan.path_controls();

    let mut executor = closed_loop(plan.settings.planner, 10);
    executor.settings.replan_time = 2.0;
    executor.settings.leg = 0.0;
    executor.search = &FindsNothing {
        goal_from_within: None,
    };
    let trial = executor.execute(&scene, &controls, &world).unwrap();
    assert!(!trial.reached && trial.controls_played >= 2, "{trial:?}");
    let (playing, waiting): (Vec<_>, Vec<_>) =
        trial.searches.iter().partition(|r| r.rest_valid > 0);
    assert_eq!(playing.first().map(|r| r.time), Some(2.0), "{trial:?}");
    let waiting: Vec<f64> = waiting.iter().map(|r| r.time).collect();
    assert_eq!(waiting, [16.0, 16.0], "{trial:?}");
    assert!(
        trial
            .stopped
            .as_deref()
            .is_some_and(|why| why.contains("2 searches found nothing while the arm waited")),
        "{trial:?}"
    );
}

/// Where no search from the observed state finds the goal (here: none from farther than
/// 15 cm), legs bring the goal object along the plan's way, a decimetre at a time, until a
/// search does; without legs the trial stops short. In the world the box stands 20 cm to
/// the side of the plan's way, where the plan's hand passes it by.
#[test]
fn where_no_search_finds_the_goal_legs_along_the_plans_way_bring_the_object_near() {
    use pushplan::planner::closed_loop::SearchFound;
    let scratch = common::Scratch::new("closed-loop-legs");
    let scene_path = Path::new("scenes/planar_hand_single_object.yaml");
    let plan_path = scratch.join("plan.json");
    let (plan, scene) = planned(scene_path, &plan_path);
    let pushplan::scene::Goal::ObjectInDisc { center, .. } = scene.goal else {
        panic!("an object goal")
    };
    let mut world = scene.clone();
    world.start.objects[0].y -= 0.2;
    let hard_from_far = FindsNothing {
        goal_from_within: Some((center, 0.15)),
    };
    let mut executor = closed_loop(plan.settings.planner, 40);
    executor.search = Box::leak(Box::new(hard_from_far));
    let with_legs = executor
        .execute(&scene, &plan.path_controls(), &world)
        .unwrap();
    assert!(with_legs.reached && with_legs.legs >= 1, "{with_legs:?}");
    assert!(with_legs.tipped.is_empty(), "{with_legs:?}");
    // Every search is on the trial's record, in order: the legs from beyond 15 cm of the
    // goal's centre (the first searched before the goal: it aims off the disc), the box
    // nearer after them, then a plan found from within.
    let records = &with_legs.searches;
    let counted =
        |kinds: &[SearchFound]| records.iter().filter(|r| kinds.contains(&r.found)).count();
    let legs_first = counted(&[SearchFound::LegFirst]);
    assert!(legs_first >= 1, "{records:?}");
    assert_eq!(
        records.len(),
        with_legs.replans + with_legs.failed_replans + legs_first,
        "{records:?}"
    );
    assert_eq!(
        counted(&[
            SearchFound::LegFirst,
            SearchFound::Leg,
            SearchFound::LegOntoTheDisc
        ]),
        with_legs.legs
    );
    assert_eq!(
        counted(&[SearchFound::Replan, SearchFound::Repair]),
        with_legs.replans
    );
    let seconds: f64 = records.iter().map(|r| r.seconds).sum();
    assert!(
        (seconds - with_legs.search_time).abs() < 1e-9,
        "{seconds} against {}",
        with_legs.search_time
    );
    let pushplan::scene::Goal::ObjectInDisc { radius, .. } = scene.goal else {
        unreachable!()
    };
    let first_leg = records
        .iter()
        .find(|r| r.found == SearchFound::LegFirst)
        .unwrap();
    let last = records.last().unwrap();
    assert!(
        first_leg.goal_distance > 0.15 - radius && last.goal_distance < first_leg.goal_distance,
        "{records:?}"
    );
    assert!(
        records
            .windows(2)
            .all(|w| w[0].after_controls <= w[1].after_controls),
        "{records:?}"
    );

    executor.settings.leg = 0.0;
    let without = executor
        .execute(&scene, &plan.path_controls(), &world)
        .unwrap();
    assert!(!without.reached && without.legs == 0, "{without:?}");
}

/// `execute --closed-loop` through the command line: every trial reported, with its
/// re-plans and the latency figures, in the text and in the JSON report.
#[test]
fn execute_closed_loop_reports_trials_replans_and_latency() {
    let scratch = common::Scratch::new("closed-loop-cli");
    let plan = scratch.join("plan.json");
    common::plan_solved(
        "scenes/planar_hand_single_object.yaml",
        &plan,
        &["--threads", "1"],
    );
    let json = scratch.join("report.json");
    // `execute --closed-loop` with `more` options, its JSON report to `json`.
    let closed_loop = |more: &[&str]| {
        let (code, stdout, stderr) = common::pushplan_in(
            Path::new("."),
            &[
                &["execute", plan.to_str().unwrap(), "--closed-loop"],
                more,
                &["--json", json.to_str().unwrap()],
            ]
            .concat(),
        );
        assert_eq!(code, 0, "{stdout}{stderr}");
        (stdout, stderr)
    };
    let (stdout, stderr) = closed_loop(&["--trials", "2"]);
    assert!(stdout.contains("executed 2 times closed loop"), "{stdout}");
    assert!(stdout.contains("re-planning latency median"), "{stdout}");
    // Each trial is told on stderr as it ends (long runs show their progress), in order,
    // and in the report again.
    let told: Vec<&str> = stderr
        .lines()
        .filter(|l| l.contains("controls played"))
        .collect();
    assert_eq!(told.len(), 2, "{stderr}");
    assert!(
        told[0].trim_start().starts_with("trial 0 (nominal): "),
        "{stderr}"
    );
    assert!(told[1].trim_start().starts_with("trial 1: "), "{stderr}");
    for line in &told {
        assert!(line.contains(" s in all"), "{line}");
        assert!(stdout.contains(line), "{line} not in the report: {stdout}");
    }
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(report["trials"].as_array().unwrap().len(), 2);
    for trial in report["trials"].as_array().unwrap() {
        assert!(trial["wall_time"].as_f64().unwrap() > 0.0, "{trial}");
    }
    for field in [
        "success_rate",
        "replans_per_trial",
        "decision_latency_median",
        "replan_latency_median",
        "replan_latency_p95",
    ] {
        assert!(report[field].is_number(), "{field}: {report}");
    }
    // Re-plans search on one thread per core unless told otherwise, as `plan` does.
    let cores = std::thread::available_parallelism().unwrap().get() as u64;
    assert_eq!(report["replan_threads"].as_u64(), Some(cores), "{report}");
    closed_loop(&["--trials", "1", "--replan-threads", "3"]);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(report["replan_threads"].as_u64(), Some(3), "{report}");
    // Rendering is for open-loop executions.
    let (code, _, stderr) = common::pushplan_in(
        Path::new("."),
        &[
            "execute",
            plan.to_str().unwrap(),
            "--closed-loop",
            "--render",
            "x",
        ],
    );
    assert_eq!(code, 2, "{stderr}");
    // Re-planning times that are no time are refused, naming the flag.
    for (flag, value) in [
        ("--replan-time", "0"),
        ("--replan-budget", "-1"),
        ("--replan-budget", "nan"),
        ("--replan-polish", "-1"),
        ("--replan-threads", "0"),
    ] {
        let (code, _, stderr) = common::pushplan_in(
            Path::new("."),
            &[
                "execute",
                plan.to_str().unwrap(),
                "--closed-loop",
                &format!("{flag}={value}"),
            ],
        );
        assert_eq!(code, 2, "{flag} {value}: {stderr}");
        assert!(stderr.contains(flag), "{stderr}");
    }
}

#[test]
fn a_prism_off_its_frame_stands_where_the_scene_puts_it_in_both_engines() {
    // A right triangle about its centroid, its principal axes at 45 degrees to its frame's:
    // MuJoCo turns a mesh onto its principal axes when it compiles the model, and the world
    // must turn it back.
    let (a, b) = (-0.1 / 3.0, 0.2 / 3.0);
    let shape =
        format!("{{type: polygon, vertices: [[{a}, {a}], [{b}, {a}], [{a}, {b}]], height: 0.05}}");
    let scene = common::thin_hand_scene("prism", &shape, 0.5, 0.02, 0.4, "");
    let mut poses = Vec::new();
    let out_of_the_way = DVector::from_vec(vec![0.3, 0.4, 0.0]);
    scene
        .robot
        .chain
        .forward_kinematics(&out_of_the_way, &mut poses);
    for engine in EngineKind::ALL {
        let mut world = world(engine, &scene, &poses);
        for _ in 0..500 {
            world.step();
        }
        let pose = world.object_pose2(0);
        let start = scene.start.objects[0];
        assert!(
            (pose.translation() - start.translation()).norm() < 1e-3
                && (pose.theta - start.theta).abs() < 1e-2
                && world.object_tilt(0) < 1e-2,
            "{engine}: {pose:?}, tilt {}",
            world.object_tilt(0)
        );
    }
}

#[test]
fn a_push_at_45_degrees_slides_along_the_friction_cone_in_rapier_and_less_in_mujoco() {
    // A wide hand moves at 45 degrees into a box's face, (0.05, 0.05) m/s for 2 s. With
    // mu_c < 1 the contact slides, the hand's force lies on the cone's edge, (1, mu_c), and
    // the box (translating on isotropic table friction) moves along it: 0.1 m in x,
    // 0.1 mu_c in y (closed form). MuJoCo's soft contacts slide at low slip speeds with
    // less than Coulomb's force: there the box is dragged less far sideways (0.79 and 0.56
    // of it when this was written); the planning model is Coulomb's. (With MuJoCo's
    // default pyramidal cones the drag hardly depended on mu_c: 44 and 49 mm.)
    for mu_c in [0.3, 0.8] {
        let yaml = format!(
            "robot:
  type: planar_hand
  shape: {{type: box, size: [0.04, 0.3, 0.01]}}
  start: [0.4, 0.0, 0.0]
  height: 0.04
table: {{height: 0.76, x: [0.27, 1.03], y: [-0.6, 0.6]}}
objects:
  - {{name: box, shape: {{type: box, size: [0.1, 0.1, 0.1]}}, pose: [0.4705, 0.0, 0.0], mass: 1.0, mu_g: 0.4, mu_c: {mu_c}}}
goal: {{object: box, center: [0.9, 0.3], radius: 0.1}}
"
        );
        let scene = Scene::from_yaml(&yaml, Path::new("scenes/drag-test.yaml")).unwrap();
        let hand = |t: f64| DVector::from_vec(vec![0.4 + 0.05 * t, 0.05 * t, 0.0]);
        let dragged = |engine: EngineKind| drive(engine, &scene, hand, 2.0).0.object_pose2(0);
        let expected = 0.1 * mu_c;
        let rapier = dragged(EngineKind::Rapier);
        assert!(
            (rapier.y - expected).abs() < 0.05 * expected && (rapier.x - 0.5695).abs() < 0.002,
            "rapier, mu_c {mu_c}: {rapier:?}, y expected {expected}"
        );
        let mujoco = dragged(EngineKind::Mujoco);
        assert!(
            mujoco.y > 0.4 * expected
                && mujoco.y < 0.9 * expected
                && (mujoco.x - 0.5695).abs() < 0.002,
            "MuJoCo, mu_c {mu_c}: {mujoco:?}, Coulomb's y {expected}"
        );
    }
}
