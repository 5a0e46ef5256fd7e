//! Propagation steps per second for the WAM with 1, 7 and 20 objects, in free space and
//! while the hand pushes a box with a two-point (face) contact (with the support pressure
//! the push loads, and with a uniform one); and the WAM with primitive collision shapes
//! against the same WAM with tessellated meshes (`robots/wam7_mesh.urdf`); and a push
//! into a neighbour with objects pushing objects (`physics.object_pushing`).
//!
//! Run: `cargo bench --bench propagation`. Each measured iteration holds one action for 50
//! steps from the same state; criterion reports time per step (throughput: steps/s).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use pushplan::{EeAction, Propagator, Scene, State};

#[path = "../model/tests/model/common.rs"]
mod common;

const STEPS: usize = 50;

/// `first` (the goal object) and `count - 1` cylinders on a grid in the half of the
/// table the arm does not sweep here.
fn objects(first: String, count: usize) -> String {
    let grid = (0..5)
        .flat_map(|i| (0..5).map(move |j| [0.35 + 0.15 * i as f64, -0.25 - 0.15 * j as f64, 0.0]));
    let cylinder = "{type: cylinder, radius: 0.04, height: 0.12}";
    grid.take(count - 1)
        .enumerate()
        .fold(first, |yaml, (k, pose)| {
            yaml + &common::object(&format!("c{k}"), cylinder, pose)
        })
}

/// The goal box right in front of the hand, pushed straight along +x.
fn pushed_box() -> String {
    common::object(
        "goal",
        "{type: box, size: [0.1, 0.1, 0.14]}",
        [0.72, 0.15, 0.0],
    )
}

/// The goal box far from the hand.
fn parked_box() -> String {
    common::object(
        "goal",
        "{type: box, size: [0.1, 0.1, 0.14]}",
        [0.9, 0.6, 0.0],
    )
}

/// Advances until the hand pushes the box, so the benchmark starts in contact.
fn in_contact(scene: &Scene, action: &EeAction) -> State {
    let mut p = Propagator::new(scene);
    let mut state = scene.start.clone();
    for _ in 0..200 {
        let run = p.propagate_steps(&state, action, 1);
        state = run.state;
        if run.contacts.first().is_some_and(|s| !s.is_empty()) {
            return state;
        }
    }
    panic!("the hand never reached the box");
}

fn propagation(c: &mut Criterion) {
    let mut group = c.benchmark_group("wam_step");
    group.throughput(Throughput::Elements(STEPS as u64));
    for count in [1, 7, 20] {
        // Free space: the hand moves away from all objects.
        let scene =
            common::herb_scene(common::HAND_NEAR, &objects(parked_box(), count), "").unwrap();
        let free = EeAction::planar(0.1, 0.1, 0.2);
        let mut p = Propagator::new(&scene);
        assert!(p
            .propagate_steps(&scene.start, &free, STEPS)
            .stopped_by
            .is_none());
        group.bench_with_input(BenchmarkId::new("free", count), &scene, |b, scene| {
            b.iter(|| p.propagate_steps(&scene.start, &free, STEPS))
        });

        // Sustained contact: the hand's face pushes a box (two contact points), with the
        // support pressure the push loads (the default) and with a uniform one.
        for (name, physics) in [
            ("pushing", ""),
            (
                "pushing_uniform_pressure",
                "physics: {pressure_shift: false}",
            ),
        ] {
            let scene =
                common::herb_scene(common::HAND_NEAR, &objects(pushed_box(), count), physics)
                    .unwrap();
            let push = EeAction::planar(0.1, 0.0, 0.0);
            let start = in_contact(&scene, &push);
            let mut p = Propagator::new(&scene);
            let check = p.propagate_steps(&start, &push, STEPS);
            assert!(check.stopped_by.is_none(), "{:?}", check.stopped_by);
            assert!(
                check.contacts.iter().all(|s| !s.is_empty()),
                "contact lost: {:?}",
                check.contacts
            );
            group.bench_with_input(BenchmarkId::new(name, count), &start, |b, start| {
                b.iter(|| p.propagate_steps(start, &push, STEPS))
            });
        }
    }
    group.finish();

    // The same arm with primitive links and with mesh links (simplified convex hulls),
    // 7 objects, free and pushing.
    let mut group = c.benchmark_group("wam_links");
    group.throughput(Throughput::Elements(STEPS as u64));
    for urdf in ["wam7.urdf", "wam7_mesh.urdf"] {
        let name = urdf.trim_end_matches(".urdf");
        let scene =
            common::herb_scene_with_robot(urdf, common::HAND_NEAR, &objects(parked_box(), 7), "")
                .unwrap();
        let free = EeAction::planar(0.1, 0.1, 0.2);
        let mut p = Propagator::new(&scene);
        group.bench_with_input(BenchmarkId::new("free", name), &scene, |b, scene| {
            b.iter(|| p.propagate_steps(&scene.start, &free, STEPS))
        });
        let scene =
            common::herb_scene_with_robot(urdf, common::HAND_NEAR, &objects(pushed_box(), 7), "")
                .unwrap();
        let push = EeAction::planar(0.1, 0.0, 0.0);
        let start = in_contact(&scene, &push);
        let mut p = Propagator::new(&scene);
        group.bench_with_input(BenchmarkId::new("pushing", name), &start, |b, start| {
            b.iter(|| p.propagate_steps(start, &push, STEPS))
        });
    }
    group.finish();
}

/// Pushing the goal box into a second box 2 mm ahead of it, 3 cm to the side (objects
/// push objects: a cluster solved every step), beside the same push with the second box
/// away, with the rule on and off: what perturbed worlds pay for pushing chains.
fn object_pushing(c: &mut Criterion) {
    let mut group = c.benchmark_group("object_pushing");
    group.throughput(Throughput::Elements(STEPS as u64));
    // A light neighbour (0.3 kg), and no tipping margin as in perturbed worlds: the
    // goal box pushed at the hand's height with a 1 kg box ahead of it tips.
    let neighbour = |x: f64, y: f64| {
        format!(
            "  - {{name: neighbour, shape: {{type: box, size: [0.1, 0.1, 0.14]}}, \
             pose: [{x}, {y}, 0.0], mass: 0.3, mu_g: 0.4, mu_c: 0.3}}\n"
        )
    };
    let physics = |on: bool| format!("physics: {{object_pushing: {on}, tipping_margin: 0.0}}");
    for (name, second, physics) in [
        ("alone", neighbour(0.9, -0.5), physics(false)),
        ("alone_rule_on", neighbour(0.9, -0.5), physics(true)),
        ("into_a_neighbour", neighbour(0.822, 0.18), physics(true)),
    ] {
        let objects = objects(pushed_box() + &second, 7);
        let scene = common::herb_scene(common::HAND_NEAR, &objects, &physics).unwrap();
        let push = EeAction::planar(0.1, 0.0, 0.0);
        let start = in_contact(&scene, &push);
        let mut p = Propagator::new(&scene);
        let check = p.propagate_steps(&start, &push, STEPS);
        assert!(check.stopped_by.is_none(), "{name}: {:?}", check.stopped_by);
        let moved = check.state.objects[1] != start.objects[1];
        assert_eq!(
            moved,
            name == "into_a_neighbour",
            "{name}: the neighbour moved: {moved}"
        );
        group.bench_with_input(BenchmarkId::new("push", name), &start, |b, start| {
            b.iter(|| p.propagate_steps(start, &push, STEPS))
        });
    }
    group.finish();
}

criterion_group!(benches, propagation, object_pushing);
criterion_main!(benches);
