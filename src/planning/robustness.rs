//! Robustness of a plan in the planner's own terms: its controls re-simulated by the model
//! from perturbed scenes (object start poses, masses, frictions, pressure distributions),
//! counting how often the goal object still ends inside the goal disc.
//!
//! The arm's motion does not depend on the objects (actions are projected onto the
//! pushing plane from the arm alone), so re-simulating the controls is executing the
//! plan open loop.

use crate::planning::passed;
use crate::planning::path::{simulate, PathControl, SimulatedPath};
use crate::propagate::{Propagation, Propagator};
use crate::random::SplitMix64;
use crate::robot::EeAction;
use crate::scene::Clearances;
use crate::scene::{Goal, Scene};
use crate::state::State;
use crate::validity::{check_state, Invalid};
use serde::Serialize;
use std::sync::Arc;
use std::time::Instant;

/// A factor a physical parameter is multiplied by, drawn uniformly from `[low, high]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Factor {
    /// Smallest factor.
    pub low: f64,
    /// Largest factor.
    pub high: f64,
}

impl Factor {
    /// The parameter as the scene gives it.
    pub const ONE: Factor = Factor {
        low: 1.0,
        high: 1.0,
    };

    /// `1 ± spread`.
    pub const fn spread(spread: f64) -> Factor {
        Factor {
            low: 1.0 - spread,
            high: 1.0 + spread,
        }
    }

    fn draw(&self, rng: &mut SplitMix64) -> f64 {
        rng.uniform(self.low, self.high)
    }
}

/// The parameter noise. Poses are shifted uniformly within ± the given amounts; the
/// physical parameters are scaled by [`Factor`]s.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Noise {
    /// Start position of every object, per axis (m).
    pub position: f64,
    /// Start yaw of every object (rad).
    pub yaw: f64,
    /// Mass of every object.
    pub mass: Factor,
    /// Object–table friction coefficient `mu_g`.
    pub mu_g: Factor,
    /// Arm–object friction coefficient `mu_c`.
    pub mu_c: Factor,
    /// The limit surface's characteristic length `c` (how far the support pressure lies
    /// from the centre of friction).
    pub c: Factor,
    /// Largest shift of each object's centre of friction from its footprint's centroid,
    /// per axis (m): the support pressure is not known to be uniform.
    pub friction_centre: f64,
}

impl Default for Noise {
    /// The model's own noise (`check --noise`, `plan --robust`): the world's
    /// ([`Noise::world`]) widened where the model is known to err, so that a plan robust
    /// to it keeps margins the size of the model's error (BENCHMARKS.md, "Robust by
    /// default"):
    /// - each object's centre of friction shifted by up to ±2 cm per axis. The model
    ///   assumes a uniform support pressure; a real object's is not known, and a push at
    ///   height h loads the leading edge, moving the centre of friction by about
    ///   `mu_g h` (2 cm for the hand at 5 cm). Near-central pushes whose turning direction
    ///   depends on it are what failed in the 3D engine.
    /// - `mu_c` down to half the scene's: the arm's surface is the least known, and
    ///   the arm's friction drags objects sideways only as far as Coulomb's law lets it
    ///   (MuJoCo's regularised friction drags a box about half as far as the model).
    ///   Plans that lean on sideways drag are fragile.
    fn default() -> Self {
        Noise {
            mu_c: Factor {
                low: 0.5,
                high: 1.2,
            },
            friction_centre: 0.02,
            ..Noise::world()
        }
    }
}

impl Noise {
    /// How a real world differs from the scene (the 3D execution's trials): ±5 mm,
    /// ±0.05 rad, and ×U(0.8, 1.2) for mass, frictions and `c`.
    pub fn world() -> Self {
        Noise {
            position: 0.005,
            yaw: 0.05,
            mass: Factor::spread(0.2),
            mu_g: Factor::spread(0.2),
            mu_c: Factor::spread(0.2),
            c: Factor::spread(0.2),
            friction_centre: 0.0,
        }
    }

    /// No noise: every perturbed world is the scene itself.
    pub fn none() -> Self {
        Noise {
            position: 0.0,
            yaw: 0.0,
            mass: Factor::ONE,
            mu_g: Factor::ONE,
            mu_c: Factor::ONE,
            c: Factor::ONE,
            friction_centre: 0.0,
        }
    }

    /// A copy of `scene` with every object's start pose and parameters perturbed, drawn
    /// from `rng`: a possible real world. The planner's reserves (tipping margin, object,
    /// edge and arm clearance) are off in it, since the perturbation stands for what they reserve
    /// against, and objects push one another (`physics.object_pushing`): a real object a
    /// neighbour drifts into is pushed along, which may or may not spoil the plan.
    /// Perturbed start poses that would be invalid (overlapping objects) are drawn again,
    /// up to 100 times, before the error is returned.
    pub fn perturb(&self, scene: &Scene, rng: &mut SplitMix64) -> Result<Scene, Invalid> {
        let mut last = None;
        for _ in 0..100 {
            let mut s = scene.clone();
            s.physics.tipping_margin = 0.0;
            s.physics.object_clearance = 0.0;
            s.physics.edge_clearance = 0.0;
            s.physics.arm_clearance = 0.0;
            s.physics.object_pushing = true;
            for object in &mut s.objects {
                let mass = self.mass.draw(rng);
                let (mu_g, mu_c, c) = (self.mu_g.draw(rng), self.mu_c.draw(rng), self.c.draw(rng));
                object.mass *= mass;
                object.mu_g *= mu_g;
                object.mu_c *= mu_c;
                object.limit_surface.c *= c;
                object.limit_surface.f_max *= mass * mu_g;
                if self.friction_centre > 0.0 {
                    let r = self.friction_centre;
                    object.limit_surface.centre.x += rng.uniform(-r, r);
                    object.limit_surface.centre.y += rng.uniform(-r, r);
                }
            }
            for pose in &mut s.start.objects {
                pose.x += rng.uniform(-self.position, self.position);
                pose.y += rng.uniform(-self.position, self.position);
                pose.theta = crate::math::wrap_angle(pose.theta + rng.uniform(-self.yaw, self.yaw));
            }
            s.clearances = Clearances::at_start(&s);
            match check_state(&s, &s.start) {
                Ok(()) => return Ok(s),
                Err(e) => last = Some(e),
            }
        }
        Err(last.expect("tried at least once"))
    }
}

/// One perturbed re-simulation.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Trial {
    /// The goal object's centre ended inside the goal disc (margin not required) and
    /// every state was valid.
    pub reached: bool,
    /// The first invalid state's reason, if any (the model cannot follow the plan there).
    pub failure: Option<String>,
    /// The goal object's final pose `[x, y, yaw]` (where the re-simulation stopped).
    pub goal_object: Option<[f64; 3]>,
    /// Distance of the goal object's final centre from the disc's edge (m; negative inside).
    pub goal_distance: f64,
}

/// What N perturbed re-simulations found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RobustnessReport {
    /// Every trial.
    pub trials: Vec<Trial>,
    /// Fraction of trials that reached the goal.
    pub success_rate: f64,
    /// The goal object's final pose in the unperturbed plan.
    pub planned_goal_object: Option<[f64; 3]>,
    /// Spread of the goal object's final pose over the trials: the largest and mean
    /// distance (m) of its centre from the planned one, and the standard deviations of
    /// x, y (m) and yaw (rad).
    pub max_deviation: f64,
    /// Mean distance of the goal object's final centre from the planned one (m).
    pub mean_deviation: f64,
    /// Standard deviations of its x, y (m) and yaw (rad).
    pub std_xy_yaw: [f64; 3],
}

/// One possible real world: a perturbed copy of the scene ([`Noise::perturb`]) with its
/// own propagator, ready to re-simulate controls in.
pub struct PerturbedWorld {
    propagator: Propagator,
    start: State,
}

impl PerturbedWorld {
    /// Draws a world from `rng`.
    pub fn draw(noise: &Noise, scene: &Scene, rng: &mut SplitMix64) -> Result<Self, Invalid> {
        let perturbed = noise.perturb(scene, rng)?;
        Ok(Self {
            start: perturbed.start.clone(),
            propagator: Propagator::new(perturbed),
        })
    }

    /// `controls` simulated in this world from its perturbed start.
    pub fn run(&mut self, controls: &[PathControl]) -> SimulatedPath {
        simulate(&mut self.propagator, &self.start, controls, false)
    }

    /// The world's (perturbed) start state.
    pub fn start(&self) -> &State {
        &self.start
    }

    /// Holds `action` for `steps` steps from `from` (a valid state of this world).
    pub fn propagate_steps(
        &mut self,
        from: &State,
        action: &EeAction,
        steps: usize,
    ) -> Propagation {
        self.propagator.propagate_steps(from, action, steps)
    }

    /// Whether `state` is valid in this world (its reserves are off).
    pub fn is_valid(&self, state: &State) -> bool {
        check_state(self.propagator.scene(), state).is_ok()
    }

    /// `controls` simulated in this world from `from` (a state of this world).
    pub fn simulate(&mut self, from: &State, controls: &[PathControl]) -> SimulatedPath {
        simulate(&mut self.propagator, from, controls, false)
    }
}

/// Whether a re-simulation reached `goal`: every state valid and the goal object's centre
/// inside the disc at the end (the planner's margin not required: it is the reserve the
/// perturbation spends).
pub fn reaches(goal: &Goal, path: &SimulatedPath) -> bool {
    path.valid() && goal.task_distance(path.final_state()) <= 0.0
}

/// Re-simulates `controls` from `trials` perturbations of `scene` (drawn from `seed`).
pub fn robustness(
    scene: &Scene,
    controls: &[PathControl],
    noise: &Noise,
    trials: usize,
    seed: u64,
) -> RobustnessReport {
    robustness_until(scene, controls, noise, trials, seed, None)
}

/// [`robustness`], stopped at `deadline` after at least one trial: the report holds the
/// trials run, the first of the `trials` asked (the worlds are drawn in order, so a check
/// cut short is the full check of as many trials), and its rate is theirs.
pub fn robustness_until(
    scene: &Scene,
    controls: &[PathControl],
    noise: &Noise,
    trials: usize,
    seed: u64,
    deadline: Option<Instant>,
) -> RobustnessReport {
    let goal_object = scene.goal.object();
    let planned = {
        let mut propagator = Propagator::new(Arc::new(scene.clone()));
        let path = simulate(&mut propagator, &scene.start, controls, false);
        goal_object.map(|g| pose_array(&path.final_state().objects[g]))
    };
    let mut rng = SplitMix64::new(seed);
    let runs: Vec<Trial> = (0..trials)
        .take_while(|&i| i == 0 || !passed(deadline))
        .map(|_| match PerturbedWorld::draw(noise, scene, &mut rng) {
            Err(e) => Trial {
                reached: false,
                failure: Some(format!("no valid perturbed start: {e}")),
                goal_object: None,
                goal_distance: f64::INFINITY,
            },
            Ok(mut world) => {
                let path = world.run(controls);
                let end = path.final_state();
                Trial {
                    reached: reaches(&scene.goal, &path),
                    failure: path
                        .stopped_by
                        .as_ref()
                        .map(|(i, why)| format!("control {i}: {why}")),
                    goal_object: goal_object.map(|g| pose_array(&end.objects[g])),
                    goal_distance: scene.goal.task_distance(end),
                }
            }
        })
        .collect();
    let success_rate = runs.iter().filter(|t| t.reached).count() as f64 / runs.len().max(1) as f64;
    let ends: Vec<[f64; 3]> = runs.iter().filter_map(|t| t.goal_object).collect();
    let (mut max_deviation, mut mean_deviation, mut std_xy_yaw) = (0.0, 0.0, [0.0; 3]);
    if let (Some(p), false) = (planned, ends.is_empty()) {
        let n = ends.len() as f64;
        let deviations: Vec<f64> = ends
            .iter()
            .map(|e| (e[0] - p[0]).hypot(e[1] - p[1]))
            .collect();
        max_deviation = deviations.iter().copied().fold(0.0, f64::max);
        mean_deviation = deviations.iter().sum::<f64>() / n;
        for (k, spread) in std_xy_yaw.iter_mut().enumerate() {
            let delta = |e: &[f64; 3]| {
                if k == 2 {
                    crate::math::wrap_angle(e[2] - p[2])
                } else {
                    e[k] - p[k]
                }
            };
            let mean = ends.iter().map(delta).sum::<f64>() / n;
            *spread = (ends.iter().map(|e| (delta(e) - mean).powi(2)).sum::<f64>() / n).sqrt();
        }
    }
    RobustnessReport {
        trials: runs,
        success_rate,
        planned_goal_object: planned,
        max_deviation,
        mean_deviation,
        std_xy_yaw,
    }
}

fn pose_array(p: &crate::math::Pose2) -> [f64; 3] {
    [p.x, p.y, p.theta]
}
