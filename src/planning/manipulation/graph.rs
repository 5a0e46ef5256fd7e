//! The upper level of the two-level Fuzzy PRM (the lecture; Nielsen and Kavraki): the
//! manipulation graph.
//!
//! Nodes `(q_obj, g, q_rob)` are given by the problem's placements and grasps (inverse
//! kinematics gives `q_rob`), plus the arm's start (holding nothing, the object at its
//! start placement). Every pair sharing a grasp is a transfer edge and every pair sharing
//! a placement a transit edge, each with probability 0.9999. The query loop takes the
//! most probable path from the start to a node at the goal placement and runs the edge's
//! low-level Fuzzy PRM (`fuzzy.rs`) for a short while on each uncertain edge of it: a
//! found path makes the edge certain (probability 1); otherwise its probability becomes
//! `1 - time(e) / total_time`, the share of all the time spent so far that was not spent
//! on it (the lecture's update; time counted in validity checks, so runs repeat exactly).

use super::fuzzy::{most_probable_path, FuzzyRoadmap, Query};
use super::{Motion, PickAndPlace, Segment};
use crate::planning::passed;
use crate::planning::transit::{transit_points, TRANSIT_RESOLUTION};
use crate::random::SplitMix64;
use nalgebra::DVector;
use std::time::Instant;

/// The query loop's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Samples a low-level run adds to an edge's roadmap (querying after each).
    pub samples_per_round: usize,
    /// Validity checks the whole search may spend.
    pub budget: usize,
    /// `P*`'s scale: joint motion (rad) an unchecked edge is free for with probability 1/e.
    pub free_length: f64,
    /// Seeds the samples and grasps.
    pub seed: u64,
    /// When to give up whatever the budget left (a caller's time limit; `None`: never).
    /// The budget alone keeps a search repeatable; a deadline it meets first does not.
    pub deadline: Option<Instant>,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            samples_per_round: 10,
            budget: 200_000,
            free_length: 1.0,
            seed: 1,
            deadline: None,
        }
    }
}

/// Transfer (the grasp shared) or transit (the placement shared).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeKind {
    /// The object rests at a placement; the arm moves between grasps.
    Transit,
    /// The arm carries the object in a grasp.
    Transfer,
}

/// A node `(q_obj, g, q_rob)`: placement index, grasp index (`None` for the arm's start).
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// Index of the object's placement.
    pub placement: usize,
    /// Index of the grasp (`None`: the arm's start).
    pub grasp: Option<usize>,
    /// The arm's configuration.
    pub q: DVector<f64>,
}

/// An edge of the manipulation graph.
#[derive(Clone, Debug)]
pub struct Edge {
    /// One node (index).
    pub a: usize,
    /// The other node (index).
    pub b: usize,
    /// Transit or transfer.
    pub kind: EdgeKind,
    /// Probability that the edge is free (1 once a path is found).
    pub probability: f64,
    /// Validity checks its low-level runs have spent.
    pub time: usize,
    /// Its low-level roadmap (from node `a`'s configuration to node `b`'s).
    roadmap: Option<FuzzyRoadmap>,
    /// The waypoints from `a` to `b` once found.
    path: Option<Vec<DVector<f64>>>,
}

/// The manipulation graph of a pick-and-place problem, and its query loop.
pub struct ManipulationGraph {
    /// The problem.
    pub problem: PickAndPlace,
    /// The graph's nodes.
    pub nodes: Vec<Node>,
    /// The graph's edges.
    pub edges: Vec<Edge>,
    /// Validity checks spent on every edge so far.
    pub total_time: usize,
    /// Low-level runs so far.
    pub runs: usize,
    settings: Settings,
    rng: SplitMix64,
}

/// The probability every edge starts with.
pub const INITIAL_PROBABILITY: f64 = 0.9999;

impl ManipulationGraph {
    /// The graph of `problem`: its nodes (grasps that inverse kinematics reaches validly
    /// at each placement) and every transfer and transit edge between them.
    pub fn new(problem: PickAndPlace, settings: Settings) -> ManipulationGraph {
        let mut nodes = vec![Node {
            placement: 0,
            grasp: None,
            q: problem.start.q.clone(),
        }];
        for placement in 0..problem.placements.len() {
            for grasp in 0..problem.grasps.len() {
                if let Some(q) = problem.grasp_configuration(placement, grasp) {
                    nodes.push(Node {
                        placement,
                        grasp: Some(grasp),
                        q,
                    });
                }
            }
        }
        let mut edges = Vec::new();
        for a in 0..nodes.len() {
            for b in a + 1..nodes.len() {
                let (na, nb) = (&nodes[a], &nodes[b]);
                let kind = if na.grasp.is_some() && na.grasp == nb.grasp {
                    EdgeKind::Transfer
                } else if na.placement == nb.placement {
                    EdgeKind::Transit
                } else {
                    continue;
                };
                edges.push(Edge {
                    a,
                    b,
                    kind,
                    probability: INITIAL_PROBABILITY,
                    time: 0,
                    roadmap: None,
                    path: None,
                });
            }
        }
        ManipulationGraph {
            problem,
            nodes,
            edges,
            total_time: 0,
            runs: 0,
            rng: SplitMix64::new(settings.seed),
            settings,
        }
    }

    /// The motion along edge `e` from node `a` to node `b`.
    fn motion(&self, e: usize) -> Motion {
        let edge = &self.edges[e];
        let (a, b) = (&self.nodes[edge.a], &self.nodes[edge.b]);
        match edge.kind {
            EdgeKind::Transit => Motion::Transit {
                placement: a.placement,
            },
            EdgeKind::Transfer => Motion::Transfer {
                grasp: a.grasp.expect("a transfer edge joins grasps"),
                from: a.placement,
                to: b.placement,
            },
        }
    }

    /// The most probable path from the start node to a node at the goal placement: its
    /// edges in order, with the node each is entered from.
    pub fn most_probable_path(&self) -> Option<Vec<(usize, usize)>> {
        let edges: Vec<(usize, usize, f64)> = self
            .edges
            .iter()
            .map(|e| (e.a, e.b, e.probability))
            .collect();
        let is_goal = |n: usize| self.nodes[n].placement == 1 && self.nodes[n].grasp.is_some();
        most_probable_path(self.nodes.len(), &edges, 0, is_goal)
    }

    /// The query loop: a path for the problem, or `None` when no path remains, the
    /// budget of validity checks is spent or the deadline has passed.
    pub fn solve(&mut self) -> Option<Vec<Segment>> {
        while self.total_time < self.settings.budget && !self.past_deadline() {
            let path = self.most_probable_path()?;
            if path.iter().all(|&(e, _)| self.edges[e].probability == 1.0) {
                return Some(self.segments(&path));
            }
            for &(e, _) in &path {
                if self.edges[e].probability != 1.0 {
                    self.run_low_level(e);
                }
            }
        }
        None
    }

    /// One low-level Fuzzy PRM run on edge `e` (a few samples, a query after each), and
    /// the edge's new probability.
    pub fn run_low_level(&mut self, e: usize) {
        self.runs += 1;
        let motion = self.motion(e);
        let (qa, qb) = (
            self.nodes[self.edges[e].a].q.clone(),
            self.nodes[self.edges[e].b].q.clone(),
        );
        let settings = self.settings;
        let mut roadmap = self.edges[e]
            .roadmap
            .take()
            .unwrap_or_else(|| FuzzyRoadmap::new(qa, qb, settings.free_length, TRANSIT_RESOLUTION));
        let problem = &self.problem;
        let chain = &problem.scene.robot.chain;
        let checks_before = roadmap.checks;
        let mut found = None;
        for _ in 0..settings.samples_per_round {
            if self.past_deadline() {
                break;
            }
            let q = chain.random_configuration(&mut self.rng);
            roadmap.checks += 1;
            if problem.valid(motion, &q) {
                roadmap.add_sample(q);
            }
            // Query until a path holds, or none is left of those not yet refuted.
            for _ in 0..roadmap.edges.len() + 1 {
                let line = |a: &DVector<f64>, b: &DVector<f64>| transit_points(a, b).collect();
                match roadmap.query_walked(|q| problem.valid(motion, q), line) {
                    Query::Found(samples) => {
                        found = Some(
                            samples
                                .iter()
                                .map(|&s| roadmap.samples[s].clone())
                                .collect(),
                        );
                        break;
                    }
                    Query::Failed => {}
                }
            }
            if found.is_some() {
                break;
            }
        }
        let spent = roadmap.checks - checks_before;
        self.total_time += spent;
        let edge = &mut self.edges[e];
        edge.time += spent;
        edge.roadmap = Some(roadmap);
        match found {
            Some(path) => {
                edge.probability = 1.0;
                edge.path = Some(path);
            }
            None => {
                edge.probability =
                    (1.0 - edge.time as f64 / self.total_time as f64).max(f64::MIN_POSITIVE);
            }
        }
    }

    fn past_deadline(&self) -> bool {
        passed(self.settings.deadline)
    }

    /// The segments of a path of certain edges.
    fn segments(&self, path: &[(usize, usize)]) -> Vec<Segment> {
        path.iter()
            .map(|&(e, from)| {
                let edge = &self.edges[e];
                let mut waypoints = edge.path.clone().expect("a certain edge has its path");
                let mut motion = self.motion(e);
                if from != edge.a {
                    waypoints.reverse();
                    if let Motion::Transfer { from, to, .. } = &mut motion {
                        std::mem::swap(from, to);
                    }
                }
                Segment { motion, waypoints }
            })
            .collect()
    }
}
