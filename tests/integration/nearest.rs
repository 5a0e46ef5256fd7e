//! The planners' nearest-neighbour tree against a linear scan of every state (the
//! independent oracle: no boxes, no bounds), and the metric's box bound against the
//! distances of states drawn inside the box.

use pushplan::planner::NearestTree;
use pushplan::DistanceMetric;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

const DOF: usize = 3;

/// Three objects, the first the goal object (weight 20), as the scenes weigh them.
fn metric() -> DistanceMetric {
    DistanceMetric {
        robot_weight: 1.0,
        object_weights: vec![20.0, 1.0, 1.0],
        rotation_length: 0.1,
    }
}

fn uniform(rng: &mut ChaCha8Rng) -> Vec<f64> {
    let mut s: Vec<f64> = (0..DOF).map(|_| rng.random_range(-2.0..2.0)).collect();
    for _ in 0..3 {
        s.extend([
            rng.random_range(0.3..1.0),
            rng.random_range(-0.9..0.9),
            rng.random_range(-PI..PI),
        ]);
    }
    s
}

/// A tree's states: a random walk from a start (objects mostly still, as clutter is),
/// yaws crossing +-pi, some written beyond a half turn as a raw angle may be.
fn tree_states(rng: &mut ChaCha8Rng, n: usize) -> Vec<Vec<f64>> {
    let mut states = vec![uniform(rng)];
    for _ in 1..n {
        let mut s = states[rng.random_range(0..states.len())].clone();
        for q in &mut s[..DOF] {
            *q += rng.random_range(-0.2..0.2);
        }
        let object = rng.random_range(0..6);
        if object < 3 {
            let k = DOF + 3 * object;
            s[k] += rng.random_range(-0.03..0.03);
            s[k + 1] += rng.random_range(-0.03..0.03);
            s[k + 2] += rng.random_range(-0.5..0.5);
            if s[k + 2] > PI + 0.3 || s[k + 2] < -PI - 0.3 {
                s[k + 2] = -s[k + 2].signum() * (2.0 * PI - s[k + 2].abs());
            }
        }
        states.push(s);
    }
    states
}

/// Every state's (index, distance), nearest first, ties by index.
fn scan(
    metric: &DistanceMetric,
    states: &[Vec<f64>],
    removed: &[bool],
    q: &[f64],
) -> Vec<(usize, f64)> {
    let mut all: Vec<(usize, f64)> = states
        .iter()
        .enumerate()
        .filter(|(i, _)| !removed[*i])
        .map(|(i, s)| (i, metric.distance_flat(q, s)))
        .collect();
    all.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
    all
}

#[test]
fn exact_answers_are_a_linear_scans() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let states = tree_states(&mut rng, 3000);
    let mut tree = NearestTree::new(metric(), DOF, 0);
    for (i, s) in states.iter().enumerate() {
        assert_eq!(tree.add(s), i);
    }
    let mut removed = vec![false; states.len()];
    for round in 0..2 {
        for _ in 0..200 {
            // Queries far away (uniform, as the planner's samples) and near the tree.
            let q = if rng.random_bool(0.5) {
                uniform(&mut rng)
            } else {
                let mut q = states[rng.random_range(0..states.len())].clone();
                q[0] += 0.01;
                q
            };
            let oracle = scan(&metric(), &states, &removed, &q);
            assert_eq!(tree.nearest(&q), Some(oracle[0]), "round {round}");
            assert_eq!(tree.nearest_k(&q, 7), oracle[..7].to_vec());
            let radius = oracle[20].1;
            let within: Vec<_> = oracle.iter().copied().filter(|c| c.1 <= radius).collect();
            assert_eq!(tree.nearest_r(&q, radius), within);
        }
        // Then without every third state.
        if round == 0 {
            for i in (0..states.len()).step_by(3) {
                assert!(tree.remove(i));
                removed[i] = true;
            }
            assert!(!tree.remove(0), "removed twice");
        }
        assert_eq!(tree.len(), removed.iter().filter(|r| !**r).count());
    }
}

#[test]
fn a_budgeted_query_answers_with_a_held_state_at_its_true_distance() {
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    let states = tree_states(&mut rng, 5000);
    let mut budgeted = NearestTree::new(metric(), DOF, 64);
    let mut unlimited = NearestTree::new(metric(), DOF, states.len());
    for s in &states {
        budgeted.add(s);
        unlimited.add(s);
    }
    let removed = vec![false; states.len()];
    let (mut excess, mut exact) = (0.0, 0);
    for _ in 0..300 {
        let q = uniform(&mut rng);
        let oracle = scan(&metric(), &states, &removed, &q);
        // A budget as large as the tree visits what an exact search must.
        assert_eq!(unlimited.nearest(&q), Some(oracle[0]));
        let (id, d) = budgeted.nearest(&q).unwrap();
        assert_eq!(d, metric().distance_flat(&q, &states[id]));
        excess += d / oracle[0].1 - 1.0;
        exact += usize::from(id == oracle[0].0);
    }
    // Far queries: the answer is near the nearest (the planner's metric spreads little
    // there), and often it is the nearest.
    assert!(excess / 300.0 < 0.02, "mean excess {}", excess / 300.0);
    assert!(exact > 100, "{exact} of 300 exact");
}

#[test]
fn the_box_bound_is_below_every_distance_in_the_box() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let m = metric();
    let mut touching = 0;
    for _ in 0..2000 {
        // A box around a few random states (its yaw range sometimes wider than a turn).
        let corners: Vec<Vec<f64>> = (0..3).map(|_| uniform(&mut rng)).collect();
        let len = corners[0].len();
        let mut lo: Vec<f64> = (0..len)
            .map(|k| corners.iter().map(|c| c[k]).fold(f64::INFINITY, f64::min))
            .collect();
        let mut hi: Vec<f64> = (0..len)
            .map(|k| {
                corners
                    .iter()
                    .map(|c| c[k])
                    .fold(f64::NEG_INFINITY, f64::max)
            })
            .collect();
        for k in (DOF + 2..len).step_by(3) {
            let shrink = rng.random_range(0.0..1.0);
            if rng.random_bool(0.2) {
                hi[k] += 2.0 * PI * shrink; // raw angles past a half turn
            } else {
                let mid = 0.5 * (lo[k] + hi[k]);
                lo[k] = mid - (mid - lo[k]) * shrink;
                hi[k] = mid + (hi[k] - mid) * shrink;
            }
        }
        let q = uniform(&mut rng);
        let bound = m.lower_bound_flat(&q, &lo, &hi);
        let nearest_inside = (0..200)
            .map(|_| {
                let s: Vec<f64> = (0..len).map(|k| rng.random_range(lo[k]..=hi[k])).collect();
                m.distance_flat(&q, &s)
            })
            .fold(f64::INFINITY, f64::min);
        assert!(
            bound <= nearest_inside + 1e-12,
            "bound {bound} above {nearest_inside}"
        );
        // The bound is attained at the box's nearest point: a state there is that far.
        let nearest_point: Vec<f64> = (0..len).map(|k| q[k].clamp(lo[k], hi[k])).collect();
        touching += usize::from(m.distance_flat(&q, &nearest_point) - bound < 1e-9);
    }
    // Clamping is the nearest point unless a yaw is nearer across +-pi.
    assert!(touching > 1000, "{touching}");
}
