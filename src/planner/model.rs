//! The planning problem as OMPL sees it: a scene, its propagator and metric, reached
//! through flat arrays ([`State::to_flat`], [`EeAction::from_flat`]). Every method checks
//! the arrays' lengths and turns a panic into an error message, because its caller is
//! C++ (nothing may unwind across the bridge).

use super::heading::{PushHeading, PushTarget};
use super::particles::ParticleWorlds;
use super::recent_tools::RecentTools;
use super::{NearestTree, SearchCounter, SearchStats};
use crate::distance::DistanceMetric;
use crate::math::Pose2;
use crate::planning::darrt;
use crate::planning::path::PathControl;
use crate::planning::robustness::Noise;
use crate::planning::static_clutter::StaticClutter;
use crate::planning::trajectory::Trajectory;
use crate::planning::{FinishSettings, FinishedPath, PlannerKind, Problem};
use crate::propagate::Propagator;
use crate::robot::EeAction;
use crate::scene::Scene;
use crate::state::{poses_from_flat_into, State};
use crate::validity::check_state;
use nalgebra::DVector;
use std::cell::RefCell;
use std::f64::consts::PI;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::{Duration, Instant};

/// A scene with its propagator and metric, in pushing mode or in Static RRT's mode.
pub struct Model {
    propagator: Propagator,
    /// The Static RRT baseline's view of the same problem, used while `static_mode`.
    static_view: StaticClutter,
    static_mode: bool,
    metric: DistanceMetric,
    /// Which way the tool should go to push an object toward a target.
    push_heading: PushHeading,
    /// Robust planning's perturbed worlds, carried along every state (none by default).
    particles: ParticleWorlds,
    /// The last state `propagate` produced and whether it was valid: OMPL asks
    /// `isValid` of exactly that state next, and the propagation already knows.
    last_result: Option<(Vec<f64>, bool)>,
    /// The tool point at the last valid propagation results: the projection's first
    /// coordinates without forward kinematics.
    recent_tools: RecentTools,
    /// The projection's buffer for a state's object poses.
    projected_objects: RefCell<Vec<Pose2>>,
    steps_taken: u64,
    /// The smallest goal distance asked for so far (progress reports: how close the
    /// search has come).
    closest_goal_distance: std::cell::Cell<f64>,
    /// The largest (with the smallest: whether any state has moved the goal object).
    farthest_goal_distance: std::cell::Cell<f64>,
    /// Wall time spent in `propagate` (progress reports: the rest is the planner's).
    propagating: Duration,
    search: SearchCounter,
    /// After this instant propagation refuses to start (the search's time limit): a
    /// search whose every extension holds k controls of many steps stops on time.
    deadline: Option<Instant>,
}

/// Runs `f`, turning a panic into an error message.
fn guarded<T>(what: &str, f: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(result) => result,
        Err(panic) => {
            let detail = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Err(format!("internal error in {what}: {detail}"))
        }
    }
}

impl Model {
    /// The model of `scene`, in the pushing problem (see [`Model::set_static_clutter`]).
    pub fn new(scene: Scene) -> Model {
        // One motion's states: OMPL propagates a control step by step, then projects each.
        let motion_states = (scene.planner.max_duration / scene.planner.step)
            .ceil()
            .clamp(1.0, 1000.0) as usize
            + 1;
        let state_len = State::flat_len(scene.robot.dof(), scene.objects.len());
        Model {
            recent_tools: RecentTools::new(motion_states, state_len),
            projected_objects: RefCell::new(Vec::new()),
            metric: DistanceMetric::from_scene(&scene),
            push_heading: PushHeading::new(&scene),
            search: SearchCounter::new(&scene),
            static_view: StaticClutter::new(&scene),
            static_mode: false,
            propagator: Propagator::new(scene),
            particles: ParticleWorlds::default(),
            last_result: None,
            steps_taken: 0,
            closest_goal_distance: std::cell::Cell::new(f64::INFINITY),
            farthest_goal_distance: std::cell::Cell::new(f64::NEG_INFINITY),
            propagating: Duration::ZERO,
            deadline: None,
        }
    }

    /// Loads a scene file into a model (boxed for C++).
    pub fn load(path: &str) -> Result<Box<Model>, String> {
        guarded("loading a scene", || {
            let scene = Scene::load(path).map_err(|e| e.to_string())?;
            Ok(Box::new(Model::new(scene)))
        })
    }

    /// A model from a scene's YAML text; `source` names it in messages and anchors its
    /// relative paths.
    pub fn from_yaml(yaml: &str, source: &str) -> Result<Box<Model>, String> {
        guarded("reading a scene", || {
            let scene =
                Scene::from_yaml(yaml, std::path::Path::new(source)).map_err(|e| e.to_string())?;
            Ok(Box::new(Model::new(scene)))
        })
    }

    /// The scene whose states OMPL holds.
    pub fn scene(&self) -> &Scene {
        self.propagator.scene()
    }

    /// The problem of the current mode (for finishing, robustness, trajectories).
    fn problem(&self) -> Problem {
        let kind = if self.static_mode {
            PlannerKind::StaticRrt
        } else {
            PlannerKind::PcRrt
        };
        Problem::new(self.scene().clone(), kind)
    }

    fn state_len(&self) -> usize {
        State::flat_len(self.scene().robot.dof(), self.scene().objects.len())
    }

    /// The state of a flat array, its length checked.
    fn state(&self, flat: &[f64]) -> Result<State, String> {
        self.check_state_len(flat)?;
        Ok(State::from_flat(flat, self.scene().robot.dof()))
    }

    fn check_state_len(&self, flat: &[f64]) -> Result<(), String> {
        if flat.len() != self.state_len() {
            return Err(format!(
                "a state has {} values, this scene needs {}",
                flat.len(),
                self.state_len()
            ));
        }
        Ok(())
    }

    /// States one after another in a flat array.
    fn states(&self, flat: &[f64]) -> Result<Vec<State>, String> {
        let scene = self.scene();
        State::many_from_flat(flat, scene.robot.dof(), scene.objects.len())
    }

    fn action(&self, control: &[f64]) -> Result<EeAction, String> {
        let dof = self.scene().robot.dof();
        if control.len() != 3 + dof {
            return Err(format!(
                "a control has {} values, this scene needs {}",
                control.len(),
                3 + dof
            ));
        }
        Ok(EeAction::from_flat(control))
    }

    fn path_controls(&self, controls: &[f64], steps: &[usize]) -> Result<Vec<PathControl>, String> {
        PathControl::from_flat(controls, steps, self.scene().robot.dof())
    }

    /// Holds `control` for `steps` steps from `state` (and its perturbed worlds' poses
    /// `particles`, see [`Model::set_particles`]); writes the state reached (or, if a step
    /// was invalid, the invalid state it tried to reach) and the worlds' poses, and says
    /// whether it is valid: in every world.
    pub fn propagate(
        &mut self,
        state: &[f64],
        particles: &[f64],
        control: &[f64],
        steps: usize,
        result: &mut [f64],
        result_particles: &mut [f64],
    ) -> Result<bool, String> {
        let started = Instant::now();
        let outcome = guarded("propagate", || {
            // OMPL propagates one step at a time: a step from the last valid result
            // continues the same propagation.
            let continues = self.last_result_validity(state) == Some(true);
            let start = self.state(state)?;
            let action = self.action(control)?;
            if result.len() != state.len() {
                return Err("the result state has the wrong length".into());
            }
            self.check_particles(particles)?;
            self.check_particles(result_particles)?;
            // Count the propagation, then write the state reached: the valid part's end,
            // or the invalid state the last step tried to reach. Past the deadline: the
            // start, invalid, nothing counted.
            // `reached`: the state the propagation ended in, valid or not.
            let (valid, taken, reached) = if self.deadline.is_some_and(|d| started >= d) {
                result.copy_from_slice(state);
                (false, None, None)
            } else if self.static_mode {
                let view = &mut self.static_view;
                let run = view
                    .propagator
                    .propagate_steps(&view.reduce(&start), &action, steps);
                let end = view.expand(&run.state);
                let stopped = run.stopped_by.as_ref();
                self.search.record(&start, &end, stopped, continues);
                match stopped {
                    None => end.write_flat(result),
                    Some(_) => view
                        .expand(&view.propagator.attempted_state())
                        .write_flat(result),
                }
                (stopped.is_none(), Some(run.steps), Some(end))
            } else {
                let run = self.propagator.propagate_steps(&start, &action, steps);
                let stopped = run.stopped_by.as_ref();
                self.search.record(&start, &run.state, stopped, continues);
                match stopped {
                    None => run.state.write_flat(result),
                    Some(_) => self.propagator.attempted_state().write_flat(result),
                }
                (stopped.is_none(), Some(run.steps), Some(run.state))
            };
            if let Some(taken) = taken {
                self.steps_taken += taken as u64 + u64::from(!valid);
            }
            // The perturbed worlds follow the same controls from the same joints.
            result_particles.copy_from_slice(particles);
            let valid = valid && {
                // Valid: `result` holds `reached`.
                let nominal = reached
                    .as_ref()
                    .expect("a propagation that ran ended somewhere");
                let stopped = self.particles.propagate(
                    &start.q,
                    particles,
                    &action,
                    steps,
                    nominal,
                    result_particles,
                );
                if let Err(why) = &stopped {
                    self.search.record_perturbed_world_stop(why.kind());
                }
                stopped.is_ok()
            };
            if valid {
                let propagator = if self.static_mode {
                    &self.static_view.propagator
                } else {
                    &self.propagator
                };
                if let Some(tool) = propagator.tool_xy() {
                    self.recent_tools.push(result, tool);
                }
            }
            // Kept in the same buffer: OMPL propagates one step at a time.
            match &mut self.last_result {
                Some((last, last_valid)) => {
                    last.clear();
                    last.extend_from_slice(result);
                    *last_valid = valid;
                }
                None => self.last_result = Some((result.to_vec(), valid)),
            }
            Ok(valid)
        });
        self.propagating += started.elapsed();
        outcome
    }

    /// Whether `state` is, bit for bit, the last propagation's result, and if so, its
    /// validity (OMPL asks right after propagating).
    fn last_result_validity(&self, state: &[f64]) -> Option<bool> {
        let (last, valid) = self.last_result.as_ref()?;
        let same = last.len() == state.len()
            && last
                .iter()
                .zip(state)
                .all(|(a, b)| a.to_bits() == b.to_bits());
        same.then_some(*valid)
    }

    /// Whether `state` is valid, in every perturbed world (their poses `particles`).
    pub fn is_valid(&mut self, state: &[f64], particles: &[f64]) -> Result<bool, String> {
        guarded("is_valid", || {
            if let Some(valid) = self.last_result_validity(state) {
                return Ok(valid);
            }
            self.check_particles(particles)?;
            let state = self.state(state)?;
            // OMPL's bounds, which its checker leaves to the model: the joint limits and the
            // table are rules below; a yaw outside [-pi, pi] is outside SO2's.
            if state.objects.iter().any(|p| !(-PI..=PI).contains(&p.theta)) {
                return Ok(false);
            }
            if !self.particles.all_valid(&state.q, particles) {
                return Ok(false);
            }
            if self.static_mode {
                let view = &self.static_view;
                return Ok(view.clutter_in_place(&state)
                    && check_state(view.propagator.scene(), &view.reduce(&state)).is_ok());
            }
            Ok(check_state(self.scene(), &state).is_ok())
        })
    }

    /// The model's metric between two flat states ([`crate::DistanceMetric`]).
    pub fn distance(&self, a: &[f64], b: &[f64]) -> Result<f64, String> {
        guarded("distance", || {
            let n = self.state_len();
            if a.len() != n || b.len() != n {
                return Err(format!(
                    "states of {} and {} values, this scene needs {n}",
                    a.len(),
                    b.len()
                ));
            }
            Ok(self.metric.distance_flat(a, b))
        })
    }

    /// An empty nearest-neighbour tree in this model's metric.
    pub fn nearest_tree(&self) -> NearestTree {
        let scene = self.scene();
        let checks = scene.planner.nearest_checks as usize;
        NearestTree::new(self.metric.clone(), scene.robot.dof(), checks)
    }

    /// The largest distance between two states within the bounds.
    pub fn max_extent(&self) -> f64 {
        self.metric.max_extent(self.scene())
    }

    /// How far `state` is from the goal (m or rad; zero or negative inside): the nominal
    /// state with the planning margin, every perturbed world (poses `particles`) without.
    pub fn goal_distance(&self, state: &[f64], particles: &[f64]) -> Result<f64, String> {
        guarded("goal_distance", || {
            self.check_particles(particles)?;
            let state = self.state(state)?;
            let goal = &self.scene().goal;
            let worlds = self.particles.goal_distance(&state.q, particles);
            let distance = goal.distance(&state).max(worlds);
            let closest = &self.closest_goal_distance;
            closest.set(closest.get().min(distance));
            let farthest = &self.farthest_goal_distance;
            farthest.set(farthest.get().max(distance));
            Ok(distance)
        })
    }

    /// The smallest goal distance of a state so far (m or rad; infinite before any).
    pub fn closest_goal_distance(&self) -> f64 {
        self.closest_goal_distance.get()
    }

    /// The largest goal distance of a state so far (m or rad; minus infinity before any).
    pub fn farthest_goal_distance(&self) -> f64 {
        self.farthest_goal_distance.get()
    }

    /// Robust planning: from now on every state carries `count` perturbed worlds drawn
    /// from `seed` ([`ParticleWorlds`]); 0 turns them off. In the pushing problem only.
    pub fn set_particles(&mut self, count: usize, seed: u64) -> Result<(), String> {
        guarded("set_particles", || {
            if count > 0 && self.static_mode {
                return Err("perturbed worlds are carried in the pushing problem only".into());
            }
            self.particles = ParticleWorlds::draw(self.scene(), count, seed)
                .map_err(|e| format!("no valid perturbed start for a perturbed world: {e}"))?;
            self.last_result = None;
            Ok(())
        })
    }

    /// The number of values of a state's perturbed worlds' poses (0 without worlds).
    pub fn particle_len(&self) -> usize {
        self.particles.flat_len()
    }

    /// The perturbed worlds' start poses.
    pub fn start_particles(&self) -> Vec<f64> {
        self.particles.start_flat()
    }

    fn check_particles(&self, particles: &[f64]) -> Result<(), String> {
        if particles.len() != self.particles.flat_len() {
            return Err(format!(
                "a state's perturbed worlds have {} values, this search needs {}",
                particles.len(),
                self.particles.flat_len()
            ));
        }
        Ok(())
    }

    /// End-effector xy and goal-object xy (m), and how deep the objects in the goal
    /// object's way stand in it ([`PushHeading::blockage`], m): the projection of the
    /// projection-based planners (KPIECE1, Push KPIECE, EST, PDST). The goal object's xy
    /// is (0, 0) and the blockage 0 for a configuration goal. The blockage tells states
    /// whose way has been cleared from the rest: a planner that explores new cells of the
    /// projection goes on from them.
    pub fn projection(&self, state: &[f64]) -> Result<Vec<f64>, String> {
        guarded("projection", || {
            self.check_state_len(state)?;
            let robot = &self.scene().robot;
            let (q, object_poses) = state.split_at(robot.dof());
            let tool = self.recent_tools.get(state).unwrap_or_else(|| {
                let q = DVector::from_column_slice(q);
                robot
                    .tool_pose(&robot.link_poses(&q))
                    .translation
                    .vector
                    .xy()
            });
            // Called for every state of every motion: the poses go to a kept buffer.
            let mut objects = self.projected_objects.borrow_mut();
            poses_from_flat_into(object_poses, &mut objects);
            let goal = match self.scene().goal.object() {
                Some(object) => objects[object].translation(),
                None => nalgebra::Vector2::zeros(),
            };
            let blockage = self.push_heading.blockage(&objects);
            Ok(vec![tool.x, tool.y, goal.x, goal.y, blockage])
        })
    }

    /// The push heading at a state for pushing `object` toward `target` (world xy, m):
    /// unit xy in the world frame (see [`PushHeading`]), or no values when the object is
    /// at the target.
    pub fn push_heading(
        &self,
        state: &[f64],
        object: usize,
        target: &[f64],
    ) -> Result<Vec<f64>, String> {
        guarded("push_heading", || {
            let state = self.state(state)?;
            if object >= state.objects.len() || target.len() != 2 {
                return Err(format!(
                    "push_heading: object {object} of {}, a target of {} values (needs 2)",
                    state.objects.len(),
                    target.len()
                ));
            }
            let robot = &self.scene().robot;
            let tool = robot.tool_pose(&robot.link_poses(&state.q)).translation;
            let target = nalgebra::Vector2::new(target[0], target[1]);
            Ok(self
                .push_heading
                .heading(
                    &state,
                    nalgebra::Vector2::new(tool.x, tool.y),
                    object,
                    target,
                )
                .map_or_else(Vec::new, |h| vec![h.x, h.y]))
        })
    }

    /// The objects in the goal object's way at a state, each with a place out of it
    /// ([`PushHeading::blockers`]).
    pub fn push_blockers(&self, state: &[f64]) -> Result<Vec<PushTarget>, String> {
        guarded("push_blockers", || {
            Ok(self.push_heading.blockers(&self.state(state)?))
        })
    }

    /// From `seconds` from now on, every propagation is refused (invalid, no step taken):
    /// the search's time limit. Infinite: no limit.
    pub fn set_time_limit(&mut self, seconds: f64) {
        self.deadline = crate::planning::deadline(Instant::now(), seconds);
    }

    /// Switches to (or from) the Static RRT baseline: clutter objects become static
    /// obstacles at their start poses.
    pub fn set_static_clutter(&mut self, on: bool) {
        self.static_mode = on;
        self.last_result = None;
    }

    /// Is the clutter pinned (Static RRT's mode)?
    pub fn static_clutter(&self) -> bool {
        self.static_mode
    }

    /// Propagation steps taken so far.
    pub fn propagation_steps(&self) -> u64 {
        self.steps_taken
    }

    /// What the propagations so far did.
    pub fn search_stats(&self) -> &SearchStats {
        self.search.stats()
    }

    /// Wall time (s) spent propagating so far.
    pub fn propagation_seconds(&self) -> f64 {
        self.propagating.as_secs_f64()
    }

    /// Fraction of `trials` perturbed re-simulations of a plan that reach the goal
    /// ([`crate::planning::robustness`], default noise, drawn from `seed`).
    pub fn robustness(
        &self,
        controls: &[f64],
        steps: &[usize],
        trials: usize,
        seed: u64,
    ) -> Result<f64, String> {
        guarded("robustness", || {
            let controls = self.path_controls(controls, steps)?;
            let report = self
                .problem()
                .robustness(&controls, &Noise::default(), trials, seed);
            Ok(report.success_rate)
        })
    }

    /// Finishes a found path ([`crate::planning::finish`]): `controls` and `steps` as found,
    /// `states` the planner's states at the control boundaries.
    pub fn finish(
        &mut self,
        controls: &[f64],
        steps: &[usize],
        states: &[f64],
        solved: bool,
        settings: &FinishSettings,
    ) -> Result<FinishedPath, String> {
        guarded("finish", || {
            let controls = self.path_controls(controls, steps)?;
            let states = self.states(states)?;
            self.problem().finish(&controls, &states, solved, settings)
        })
    }

    /// The executable trajectory of a plan, as plan files hold it.
    pub fn trajectory(&mut self, controls: &[f64], steps: &[usize]) -> Result<Trajectory, String> {
        guarded("trajectory", || {
            let controls = self.path_controls(controls, steps)?;
            self.problem().trajectory(&controls)
        })
    }

    /// DARRT's Transit: is the straight joint-space line from `from` to `to` (same object
    /// poses) valid?
    pub fn darrt_transit(&self, from: &[f64], to: &[f64]) -> Result<bool, String> {
        guarded("darrt_transit", || {
            let (from, to) = (self.state(from)?, self.state(to)?);
            if from.objects != to.objects {
                return Err("a transit moves no object: the object poses differ".into());
            }
            Ok(crate::planning::transit::check_transit(self.scene(), &from, &to.q).is_ok())
        })
    }

    /// DARRT's Push, first part: writes the state with the hand caging `object` (ready
    /// to carry it to `target`, `[x, y, yaw]`) and returns true, or false if none is found.
    pub fn darrt_approach(
        &self,
        state: &[f64],
        object: usize,
        target: &[f64],
        result: &mut [f64],
    ) -> Result<bool, String> {
        guarded("darrt_approach", || {
            let state = self.state(state)?;
            let (object, target) = self.object_target(object, target)?;
            if result.len() != self.state_len() {
                return Err("the result state has the wrong length".into());
            }
            match darrt::approach(self.scene(), &state, object, &target) {
                Ok(caged) => {
                    caged.write_flat(result);
                    Ok(true)
                }
                Err(_) => Ok(false),
            }
        })
    }

    /// DARRT's Push, second part: carries the object caged in `state` to `target`
    /// (`[x, y, yaw]`). Returns the states of the carry (flat, one after another), or none
    /// if the line is blocked.
    pub fn darrt_carry(
        &self,
        state: &[f64],
        object: usize,
        target: &[f64],
    ) -> Result<Vec<f64>, String> {
        guarded("darrt_carry", || {
            let state = self.state(state)?;
            let (object, target) = self.object_target(object, target)?;
            let cage = darrt::Cage::of_state(self.scene(), &state, object);
            Ok(darrt::carry(self.scene(), &state, &cage, &target)
                .map(|states| states.iter().flat_map(State::to_flat).collect())
                .unwrap_or_default())
        })
    }

    /// DARRT's PickPlace: grasps `object` where it rests in `state`, carries it and sets it
    /// down at `target` (`[x, y, yaw]`), drawn from `seed`. Returns the states after
    /// `state` (flat, one after another) and what the hand holds in each (an object
    /// index, or -1), both empty if no way is found.
    pub fn darrt_pick_place(
        &self,
        state: &[f64],
        object: usize,
        target: &[f64],
        seed: u64,
    ) -> Result<(Vec<f64>, Vec<i64>), String> {
        guarded("darrt_pick_place", || {
            let state = self.state(state)?;
            let (object, target) = self.object_target(object, target)?;
            let settings = darrt::PickPlaceSettings::default();
            let path = darrt::pick_place(
                self.scene(),
                &state,
                object,
                &target,
                &settings,
                seed,
                self.deadline,
            )
            .unwrap_or_default();
            Ok((
                path.iter().flat_map(|p| p.state.to_flat()).collect(),
                path.iter().map(|p| held_to_flat(p.held)).collect(),
            ))
        })
    }

    /// Checks a DARRT path (flat states one after another, and what the hand holds in
    /// each: an object index or -1) and measures it: the outer error is a malformed call,
    /// the inner one why the path is invalid.
    pub fn darrt_check(
        &self,
        states: &[f64],
        held: &[i64],
    ) -> Result<Result<darrt::PrimitivePath, String>, String> {
        guarded("darrt_check", || {
            let states = self.states(states)?;
            if held.len() != states.len() {
                return Err(format!(
                    "{} states but {} entries of what the hand holds",
                    states.len(),
                    held.len()
                ));
            }
            let objects = self.scene().objects.len();
            let path = states
                .into_iter()
                .zip(held)
                .map(|(state, &h)| match h {
                    -1 => Ok(darrt::PathState::resting(state)),
                    h if (0..objects as i64).contains(&h) => Ok(darrt::PathState {
                        state,
                        held: Some(h as usize),
                    }),
                    h => Err(format!(
                        "the hand holds object {h}, not -1 or an object index"
                    )),
                })
                .collect::<Result<Vec<_>, String>>()?;
            Ok(darrt::check_path(self.scene(), &path))
        })
    }

    /// Reaching a grasp: the index of the object named `name`, which must have grasps.
    pub fn graspable_object(&self, name: &str) -> Result<usize, String> {
        crate::planning::reach::graspable_object(self.scene(), name)
    }

    /// One try at a configuration in a grasp region of `object` at its pose in `state`,
    /// drawn from `seed`: valid among the objects (IK-BiRRT's ADDIKSOLUTIONS) or, with
    /// `arm_only`, valid for the arm alone (a grasp goal's sample, a target the pushing
    /// planner may clear the way to). Empty if this try's inverse kinematics found none.
    pub fn grasp_sample(
        &self,
        state: &[f64],
        object: usize,
        seed: u64,
        arm_only: bool,
    ) -> Result<Vec<f64>, String> {
        guarded("grasp_sample", || {
            let state = self.state(state)?;
            let sampling = if arm_only {
                crate::planning::reach::GraspSampling::ArmOnly
            } else {
                crate::planning::reach::GraspSampling::AmongObjects
            };
            Ok(
                crate::planning::reach::sample_grasp(self.scene(), &state, object, seed, sampling)?
                    .map_or_else(Vec::new, |q| q.as_slice().to_vec()),
            )
        })
    }

    /// The distance from `state`'s configuration to the nearest grasp region of `object`.
    pub fn grasp_distance(&self, state: &[f64], object: usize) -> Result<f64, String> {
        guarded("grasp_distance", || {
            crate::planning::reach::grasp_distance(self.scene(), &self.state(state)?, object)
        })
    }

    /// Checks a reach of `object` from `from` (waypoints flat, one configuration after
    /// another): an empty string if it is valid, else why not ([`crate::planning::reach::check_reach`]).
    pub fn check_reach(
        &self,
        from: &[f64],
        object: usize,
        waypoints: &[f64],
    ) -> Result<String, String> {
        guarded("check_reach", || {
            let from = self.state(from)?;
            let dof = self.scene().robot.dof();
            if waypoints.len() % dof != 0 {
                return Err(format!(
                    "{} waypoint values for {dof} joints",
                    waypoints.len()
                ));
            }
            let waypoints: Vec<DVector<f64>> = waypoints
                .chunks(dof)
                .map(DVector::from_column_slice)
                .collect();
            Ok(
                crate::planning::reach::check_reach(self.scene(), &from, object, &waypoints)
                    .err()
                    .unwrap_or_default(),
            )
        })
    }

    /// An object index and a target pose `[x, y, yaw]`, checked.
    fn object_target(&self, object: usize, target: &[f64]) -> Result<(usize, Pose2), String> {
        if object >= self.scene().objects.len() {
            return Err(format!(
                "object {object} does not exist ({} objects)",
                self.scene().objects.len()
            ));
        }
        match target {
            [x, y, yaw] if target.iter().all(|v| v.is_finite()) => {
                Ok((object, Pose2::new(*x, *y, *yaw)))
            }
            _ => Err(format!(
                "a target pose is [x, y, yaw], finite; got {target:?}"
            )),
        }
    }
}

/// What the hand holds, as the bridge passes it: the object's index, or -1.
fn held_to_flat(held: Option<usize>) -> i64 {
    held.map_or(-1, |i| i as i64)
}
