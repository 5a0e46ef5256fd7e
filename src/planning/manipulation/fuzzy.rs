//! The low-level Fuzzy PRM of the lecture (Nielsen and Kavraki, IROS 2000): a roadmap
//! between two configurations whose edges are not checked when added but carry the
//! probability of being free, raised as they are checked at finer resolutions.
//!
//! CONSTRUCTION adds a sample and edges from it to every earlier sample, each with the
//! probability `P*(l)` of an edge checked at level `l` (0: only its ends). QUERY takes the
//! most probable path (Dijkstra over `-ln p`) and, until every edge on it is certain,
//! checks its least probable edge at the next level (the midpoints its previous level
//! left out); an edge found in collision is removed and the query fails.

use nalgebra::DVector;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A roadmap edge between samples `a` and `b`.
#[derive(Clone, Debug, PartialEq)]
pub struct FuzzyEdge {
    /// One end (sample index).
    pub a: usize,
    /// The other end (sample index).
    pub b: usize,
    /// Joint-space length (the largest joint's motion, rad or m).
    pub length: f64,
    /// Subdivision level checked: 2^level - 1 interior points, evenly spaced.
    pub level: u32,
    /// Probability that the edge is free.
    pub probability: f64,
}

/// `P*(l)`: the probability that an edge of `length` is free once checked at `level`,
/// `exp(-s / free_length)` with `s = length / 2^level` the unchecked spacing; 1 once the
/// spacing is within `resolution` (the edge is then checked as finely as any motion).
pub fn edge_probability(length: f64, level: u32, free_length: f64, resolution: f64) -> f64 {
    let spacing = length / 2f64.powi(level as i32);
    if spacing <= resolution {
        1.0
    } else {
        (-spacing / free_length).exp()
    }
}

/// What a query found.
#[derive(Clone, Debug, PartialEq)]
pub enum Query {
    /// Sample indices from the start (0) to the goal (1), every edge certain.
    Found(Vec<usize>),
    /// No path, or an edge of the most probable one was in collision (and is removed).
    Failed,
}

/// A low-level Fuzzy PRM between samples 0 (start) and 1 (goal).
#[derive(Clone, Debug)]
pub struct FuzzyRoadmap {
    /// Joint configurations: the start first, the goal second, then samples.
    pub samples: Vec<DVector<f64>>,
    /// The roadmap's edges.
    pub edges: Vec<FuzzyEdge>,
    /// Length of free motion a random edge typically has (rad): the scale of `P*`.
    free_length: f64,
    /// Spacing at which a checked edge is certain (rad).
    resolution: f64,
    /// Validity checks run so far (the roadmap's "time").
    pub checks: usize,
}

impl FuzzyRoadmap {
    /// The roadmap of `start` and `goal`, joined by one unchecked edge.
    pub fn new(start: DVector<f64>, goal: DVector<f64>, free_length: f64, resolution: f64) -> Self {
        let mut roadmap = FuzzyRoadmap {
            samples: vec![start],
            edges: Vec::new(),
            free_length,
            resolution,
            checks: 0,
        };
        roadmap.add_sample(goal);
        roadmap
    }

    /// CONSTRUCTION: adds `q` (already found valid) and an edge from it to every earlier
    /// sample, each at level 0.
    pub fn add_sample(&mut self, q: DVector<f64>) {
        let new = self.samples.len();
        for (i, other) in self.samples.iter().enumerate() {
            let length = (&q - other).amax();
            self.edges.push(FuzzyEdge {
                a: i,
                b: new,
                length,
                level: 0,
                probability: edge_probability(length, 0, self.free_length, self.resolution),
            });
        }
        self.samples.push(q);
    }

    /// The most probable path from sample 0 to sample 1, as edge indices in order.
    fn most_probable_path(&self) -> Option<Vec<usize>> {
        let edges: Vec<(usize, usize, f64)> = self
            .edges
            .iter()
            .map(|e| (e.a, e.b, e.probability))
            .collect();
        most_probable_path(self.samples.len(), &edges, 0, |n| n == 1)
            .map(|path| path.into_iter().map(|(e, _)| e).collect())
    }

    /// QUERY: checks the most probable path's edges, least probable first, level by
    /// level, with `valid`, until all are certain (the path) or one is in collision
    /// (removed; `Failed`).
    pub fn query(&mut self, mut valid: impl FnMut(&DVector<f64>) -> bool) -> Query {
        let Some(path) = self.most_probable_path() else {
            return Query::Failed;
        };
        loop {
            let Some(&weakest) = path
                .iter()
                .filter(|&&e| self.edges[e].probability < 1.0)
                .min_by(|&&x, &&y| {
                    self.edges[x]
                        .probability
                        .total_cmp(&self.edges[y].probability)
                })
            else {
                return Query::Found(self.path_samples(&path));
            };
            let edge = self.edges[weakest].clone();
            let (a, b) = (&self.samples[edge.a], &self.samples[edge.b]);
            // The midpoints level `level + 1` adds: odd multiples of 1 / 2^(level + 1).
            let parts = 2usize.pow(edge.level + 1);
            let free = (1..parts).step_by(2).all(|k| {
                self.checks += 1;
                valid(&a.lerp(b, k as f64 / parts as f64))
            });
            if !free {
                self.edges.remove(weakest);
                return Query::Failed;
            }
            let e = &mut self.edges[weakest];
            e.level += 1;
            e.probability = edge_probability(e.length, e.level, self.free_length, self.resolution);
        }
    }

    /// QUERY, then every edge of the path found walked at the points `line` gives (those
    /// the rest of the planner checks a line at, which dyadic levels need not include): an
    /// edge with an invalid point is removed and the query fails.
    pub fn query_walked(
        &mut self,
        mut valid: impl FnMut(&DVector<f64>) -> bool,
        line: impl Fn(&DVector<f64>, &DVector<f64>) -> Vec<DVector<f64>>,
    ) -> Query {
        let Query::Found(samples) = self.query(&mut valid) else {
            return Query::Failed;
        };
        for pair in samples.windows(2) {
            let (a, b) = (&self.samples[pair[0]], &self.samples[pair[1]]);
            let checks = &mut self.checks;
            let free = line(a, b).iter().all(|q| {
                *checks += 1;
                valid(q)
            });
            if !free {
                let (a, b) = (pair[0], pair[1]);
                self.edges
                    .retain(|e| !((e.a == a && e.b == b) || (e.a == b && e.b == a)));
                return Query::Failed;
            }
        }
        Query::Found(samples)
    }

    /// The samples along a path of edges from sample 0.
    fn path_samples(&self, path: &[usize]) -> Vec<usize> {
        let mut nodes = vec![0];
        for &e in path {
            let edge = &self.edges[e];
            let last = *nodes.last().unwrap();
            nodes.push(if edge.a == last { edge.b } else { edge.a });
        }
        nodes
    }

    /// The probability of the edge between samples `a` and `b` (`None` if there is none).
    pub fn probability(&self, a: usize, b: usize) -> Option<f64> {
        self.edges
            .iter()
            .find(|e| (e.a == a && e.b == b) || (e.a == b && e.b == a))
            .map(|e| e.probability)
    }
}

#[derive(PartialEq)]
struct Visit(f64, usize);

impl Eq for Visit {}

impl PartialOrd for Visit {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Visit {
    // The smallest cost first (BinaryHeap is a max-heap); ties by node, for determinism.
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

/// The most probable path from `start` to a node `is_goal` accepts, over `nodes` nodes
/// and `edges` `(a, b, probability)` (independent events: the path's probability is the
/// product, so Dijkstra over `-ln p`): the edges in order, each with the node it is
/// entered from.
pub fn most_probable_path(
    nodes: usize,
    edges: &[(usize, usize, f64)],
    start: usize,
    is_goal: impl Fn(usize) -> bool,
) -> Option<Vec<(usize, usize)>> {
    let mut adjacent = vec![Vec::new(); nodes];
    for (i, &(a, b, _)) in edges.iter().enumerate() {
        adjacent[a].push((i, b));
        adjacent[b].push((i, a));
    }
    let mut cost = vec![f64::INFINITY; nodes];
    let mut via: Vec<Option<(usize, usize)>> = vec![None; nodes];
    let mut heap = BinaryHeap::new();
    cost[start] = 0.0;
    heap.push(Visit(0.0, start));
    while let Some(Visit(c, node)) = heap.pop() {
        if c > cost[node] {
            continue;
        }
        if is_goal(node) {
            let mut path = Vec::new();
            let mut at = node;
            while let Some((edge, from)) = via[at] {
                path.push((edge, from));
                at = from;
            }
            path.reverse();
            return Some(path);
        }
        for &(edge, next) in &adjacent[node] {
            let through = c - edges[edge].2.ln();
            if through.is_finite() && through < cost[next] {
                cost[next] = through;
                via[next] = Some((edge, node));
                heap.push(Visit(through, next));
            }
        }
    }
    None
}
