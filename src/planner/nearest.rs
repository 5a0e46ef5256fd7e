//! Nearest neighbours in the model's metric for the planners' trees: a k-d tree over
//! flat copies of the states, each leaf's one after another.
//!
//! The metric (`w_q ||dq|| + sum_i w_i ||do_i||`, yaws wrapped) is no norm of the flat
//! numbers, so the tree does not split space by it: it splits boxes of flat numbers, and a
//! query skips every box whose [`DistanceMetric::lower_bound_flat`] already exceeds the
//! best distance found. Boxes are the tight bounds of the states below them, so the
//! clutter that never moved in a tree costs one bound, not a branch.
//!
//! Exact answers grow nearly linear in the tree's size: a planner's queries are uniform
//! samples, far from the tree, where the distances of the nearest hundred states lie
//! within a few per cent of each other (12 objects: 500 us a query at 40 000 states).
//! So [`NearestTree::nearest`] may stop after a budget of states, taken from the most
//! promising boxes first (best bin first, as FLANN does): 128 states answer within 1.6 %
//! of the nearest distance on average at 40 000 states, in 33 us (BENCHMARKS.md).
//!
//! Why not OMPL's GNAT through the bridge: every distance it asked for read two OMPL
//! states through their component pointers and crossed the bridge; at 14 000 states
//! with 12 objects that was half the planning time (BENCHMARKS.md).

use crate::distance::DistanceMetric;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// States per leaf before it splits.
const LEAF_SIZE: usize = 32;

#[derive(Clone, Debug)]
enum Node {
    /// States by index, with their numbers one after another: a query reads a leaf front to
    /// back instead of 32 states scattered in insertion order (the distances were waiting
    /// on cache misses, BENCHMARKS.md).
    Leaf { ids: Vec<u32>, points: Vec<f64> },
    /// States with `state[axis] < value` go to `children[0]`, the rest to `children[1]`.
    Split {
        axis: usize,
        value: f64,
        children: [u32; 2],
    },
}

/// The states of a planner's tree, by insertion index, for exact nearest-neighbour queries.
#[derive(Clone, Debug)]
pub struct NearestTree {
    metric: DistanceMetric,
    /// States [`Self::nearest`] compares at most (0: exact).
    checks: usize,
    /// Flat state length: joints, then x, y, yaw per object.
    state_len: usize,
    /// How much a unit of each flat number counts (to choose split axes).
    weights: Vec<f64>,
    /// Whether state `i` was taken out (one entry per state added; the states themselves
    /// live in the leaves).
    removed: Vec<bool>,
    live: usize,
    nodes: Vec<Node>,
    /// Node `n`'s box: lows at `bounds[2 n len..]`, highs right after.
    bounds: Vec<f64>,
}

impl NearestTree {
    /// An empty tree for flat states of `dof` joints and the metric's objects, whose
    /// [`Self::nearest`] compares at most about `checks` states (0: exact).
    pub fn new(metric: DistanceMetric, dof: usize, checks: usize) -> Self {
        let weights = metric.flat_weights(dof);
        NearestTree {
            checks,
            state_len: weights.len(),
            metric,
            weights,
            removed: Vec::new(),
            live: 0,
            nodes: Vec::new(),
            bounds: Vec::new(),
        }
    }

    /// The flat state length this tree holds.
    pub fn state_len(&self) -> usize {
        self.state_len
    }

    /// `state` if it has this tree's length and only finite numbers: what the bridge
    /// passes on to [`Self::add`] and the queries, which assume both.
    pub fn checked<'a>(&self, state: &'a [f64]) -> Result<&'a [f64], String> {
        if state.len() != self.state_len {
            Err(format!(
                "a state of {} values, this tree holds states of {}",
                state.len(),
                self.state_len
            ))
        } else if let Some(i) = state.iter().position(|x| !x.is_finite()) {
            Err(format!("state value {i} is {}", state[i]))
        } else {
            Ok(state)
        }
    }

    /// States held (removed ones not counted).
    pub fn len(&self) -> usize {
        self.live
    }

    /// Does the tree hold no state?
    pub fn is_empty(&self) -> bool {
        self.live == 0
    }

    /// Removes every state.
    pub fn clear(&mut self) {
        self.removed.clear();
        self.live = 0;
        self.nodes.clear();
        self.bounds.clear();
    }

    /// Adds a state of [`Self::state_len`] numbers; returns its index (0, 1, 2, ...).
    pub fn add(&mut self, state: &[f64]) -> usize {
        assert_eq!(state.len(), self.state_len, "state length");
        let id = self.removed.len();
        self.removed.push(false);
        self.live += 1;
        if self.nodes.is_empty() {
            let root = Node::Leaf {
                ids: Vec::new(),
                points: Vec::new(),
            };
            self.push_node(root, state, state);
        }
        let mut n = 0;
        loop {
            self.grow_box(n, state);
            match &mut self.nodes[n] {
                Node::Split {
                    axis,
                    value,
                    children,
                } => n = children[usize::from(state[*axis] >= *value)] as usize,
                Node::Leaf { ids, points } => {
                    ids.push(id as u32);
                    points.extend_from_slice(state);
                    if ids.len() > LEAF_SIZE {
                        self.split(n);
                    }
                    return id;
                }
            }
        }
    }

    /// Takes state `id` out of every later answer. False if it was not held.
    pub fn remove(&mut self, id: usize) -> bool {
        match self.removed.get_mut(id) {
            Some(removed) if !*removed => {
                *removed = true;
                self.live -= 1;
                true
            }
            _ => false,
        }
    }

    /// The nearest held state to `query` and its distance: exact if the tree's `checks`
    /// is 0, otherwise the nearest of at most about `checks` states (whole leaves), taken
    /// from the boxes nearest `query` first.
    pub fn nearest(&self, query: &[f64]) -> Option<(usize, f64)> {
        let mut best: Option<(usize, f64)> = None;
        let budget = if self.checks == 0 {
            usize::MAX
        } else {
            self.checks
        };
        self.search(query, budget, |id, d| {
            if best.is_none_or(|(_, b)| d < b) {
                best = Some((id, d));
            }
            best.map_or(f64::INFINITY, |(_, b)| b)
        });
        best
    }

    /// The `k` nearest held states to `query`, nearest first (ties by index); exact.
    pub fn nearest_k(&self, query: &[f64], k: usize) -> Vec<(usize, f64)> {
        let mut found: Vec<(usize, f64)> = Vec::with_capacity(k + 1);
        if k == 0 {
            return found;
        }
        self.search(query, usize::MAX, |id, d| {
            if found.len() < k || closer((id, d), found[k - 1]) {
                let at = found.partition_point(|&f| closer(f, (id, d)));
                found.insert(at, (id, d));
                found.truncate(k);
            }
            if found.len() < k {
                f64::INFINITY
            } else {
                found[k - 1].1
            }
        });
        found
    }

    /// Every held state within `radius` of `query`, nearest first (ties by index); exact.
    pub fn nearest_r(&self, query: &[f64], radius: f64) -> Vec<(usize, f64)> {
        let mut found = Vec::new();
        self.search(query, usize::MAX, |id, d| {
            if d <= radius {
                found.push((id, d));
            }
            radius
        });
        found.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        found
    }

    /// Best bin first: goes down to a leaf, nearer box first, keeping each farther box
    /// aside by its lower bound; then resumes from the box set aside with the smallest
    /// bound. Stops when that bound exceeds the pruning distance `visit` returned after
    /// its last state, or once `budget` states have been visited (after a whole leaf).
    fn search(&self, query: &[f64], budget: usize, mut visit: impl FnMut(usize, f64) -> f64) {
        assert_eq!(query.len(), self.state_len, "state length");
        if self.nodes.is_empty() {
            return;
        }
        let mut prune = f64::INFINITY;
        let mut visited = 0usize;
        let mut aside = BinaryHeap::new();
        aside.push(Aside {
            bound: self.lower_bound(query, 0),
            node: 0,
        });
        while let Some(Aside { bound, node }) = aside.pop() {
            if bound > prune || visited >= budget {
                break;
            }
            let mut n = node;
            loop {
                match &self.nodes[n] {
                    Node::Leaf { ids, points } => {
                        for (&id, point) in ids.iter().zip(points.chunks_exact(self.state_len)) {
                            let id = id as usize;
                            if !self.removed[id] {
                                let d = self.metric.distance_flat(query, point);
                                prune = visit(id, d);
                                visited += 1;
                            }
                        }
                        break;
                    }
                    Node::Split { children, .. } => {
                        let [a, b] = children.map(|c| Aside {
                            bound: self.lower_bound(query, c as usize),
                            node: c as usize,
                        });
                        let (near, far) = if b.bound < a.bound { (b, a) } else { (a, b) };
                        if far.bound <= prune {
                            aside.push(far);
                        }
                        if near.bound > prune {
                            break;
                        }
                        n = near.node;
                    }
                }
            }
        }
    }

    fn lower_bound(&self, query: &[f64], node: usize) -> f64 {
        let (lo, hi) = self.node_box(node);
        self.metric.lower_bound_flat(query, lo, hi)
    }

    fn node_box(&self, node: usize) -> (&[f64], &[f64]) {
        let at = 2 * node * self.state_len;
        (
            &self.bounds[at..at + self.state_len],
            &self.bounds[at + self.state_len..at + 2 * self.state_len],
        )
    }

    fn push_node(&mut self, node: Node, lo: &[f64], hi: &[f64]) -> u32 {
        self.nodes.push(node);
        self.bounds.extend_from_slice(lo);
        self.bounds.extend_from_slice(hi);
        (self.nodes.len() - 1) as u32
    }

    fn grow_box(&mut self, node: usize, state: &[f64]) {
        let at = 2 * node * self.state_len;
        let (lo, hi) = self.bounds[at..at + 2 * self.state_len].split_at_mut(self.state_len);
        for ((l, h), &x) in lo.iter_mut().zip(hi.iter_mut()).zip(state) {
            *l = l.min(x);
            *h = h.max(x);
        }
    }

    /// Splits a full leaf along the number whose spread counts most in the metric, at the
    /// median (at the middle of the spread if the median leaves one side empty).
    fn split(&mut self, node: usize) {
        let Node::Leaf { ids, points } = &self.nodes[node] else {
            return;
        };
        let len = self.state_len;
        let (lo, hi) = self.node_box(node);
        let (axis, spread) = (0..len)
            .map(|a| (a, (hi[a] - lo[a]) * self.weights[a]))
            .fold((0, 0.0), |best, c| if c.1 > best.1 { c } else { best });
        if spread <= 0.0 {
            return; // all its states are one: nothing to split
        }
        let middle = 0.5 * (lo[axis] + hi[axis]);
        let mut values: Vec<f64> = points.chunks_exact(len).map(|p| p[axis]).collect();
        let half = values.len() / 2;
        let median = *values.select_nth_unstable_by(half, f64::total_cmp).1;
        let value = if points.chunks_exact(len).any(|p| p[axis] < median) {
            median
        } else {
            middle
        };
        // Both sides keep the leaf's order of states.
        let mut sides = [(); 2].map(|_| (Vec::new(), Vec::new()));
        for (&id, point) in ids.iter().zip(points.chunks_exact(len)) {
            let (side_ids, side_points) = &mut sides[usize::from(point[axis] >= value)];
            side_ids.push(id);
            side_points.extend_from_slice(point);
        }
        let children = sides.map(|(ids, points)| {
            let (lo, hi) = self.tight_box(&points);
            self.push_node(Node::Leaf { ids, points }, &lo, &hi)
        });
        self.nodes[node] = Node::Split {
            axis,
            value,
            children,
        };
    }

    /// The tight box of states laid one after another.
    fn tight_box(&self, points: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let mut lo = vec![f64::INFINITY; self.state_len];
        let mut hi = vec![f64::NEG_INFINITY; self.state_len];
        for point in points.chunks_exact(self.state_len) {
            for ((l, h), &x) in lo.iter_mut().zip(hi.iter_mut()).zip(point) {
                *l = l.min(x);
                *h = h.max(x);
            }
        }
        (lo, hi)
    }
}

/// A box set aside during a search: popped smallest bound first (then lowest node).
#[derive(PartialEq)]
struct Aside {
    bound: f64,
    node: usize,
}

impl Eq for Aside {}

impl Ord for Aside {
    fn cmp(&self, other: &Self) -> Ordering {
        // BinaryHeap pops the greatest: the smallest bound is the greatest here.
        other
            .bound
            .total_cmp(&self.bound)
            .then(other.node.cmp(&self.node))
    }
}

impl PartialOrd for Aside {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Orders (index, distance) pairs by distance, then index.
fn closer(a: (usize, f64), b: (usize, f64)) -> bool {
    a.1 < b.1 || (a.1 == b.1 && a.0 < b.0)
}
