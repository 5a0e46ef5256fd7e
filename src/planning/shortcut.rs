//! Path shortcutting (Sec. IV, Fig. 3 of the whole-arm paper).
//!
//! Repeatedly pick two states of the path, connect only their robot configurations by a
//! new constrained action (the end effector moves in a straight line along the plane
//! between the two end-effector poses; the null-space sample pulls the joints towards
//! the second configuration), propagate it through the physics, re-propagate every
//! remaining control from the new state, and keep the result when every state is valid,
//! the goal is still reached and the manipulator path is shorter (joint space).
//!
//! The connecting control ends near the second configuration, not on it (the projection
//! is damped, the pull is projected into the null space), and a long path replayed from
//! a configuration a few milliradians off pushes its objects a little differently until a
//! later push tips one or a link closes in on one: most shortcuts of a long path used to
//! fail so, far from the shortcut. Up to [`CLOSING_CONTROLS`] short controls after it
//! close the gap to about 0.2 mrad, and the rest replays much as it was planned (a long
//! Panda plan's shortcuts across free stretches: 240 of 256 failed in their tail before,
//! 55 of 152 with them).
//!
//! Toward robustness ([`Criterion::MoreRobust`]) half the attempts are nudges instead: one
//! control held for a different number of steps. A push held a little longer or stopped
//! a little earlier moves where the objects end up (deeper into the goal disc, further
//! from a neighbour), which no shortcut between the path's own states can do.
//!
//! The budget is counted in propagation steps, not wall-clock time, so shortcutting is
//! deterministic under its seed; [`STEPS_PER_SECOND`] converts the user's seconds.

use crate::math::wrap_angle;
use crate::planning::passed;
use crate::planning::path::{simulate, PathControl, PathMetrics, SimulatedPath};
use crate::planning::robustness::{reaches, PerturbedWorld};
use crate::propagate::Propagator;
use crate::random::SplitMix64;
use crate::robot::EeAction;
use crate::scene::Goal;
use crate::state::State;
use nalgebra::DVector;
use std::time::Instant;

/// Propagation steps one second of shortcutting buys (about what this machine does:
/// see BENCHMARKS.md).
pub const STEPS_PER_SECOND: f64 = 200_000.0;

/// How shortcutting runs: its budget in steps of work (so that it is deterministic), its seed, and a deadline.
#[derive(Clone, Copy, Debug)]
pub struct ShortcutSettings {
    /// Work budget in propagation steps.
    pub budget_steps: u64,
    /// Seeds the choice of shortcuts.
    pub seed: u64,
    /// Wall-clock time at which shortcutting stops even if budget is left (the plan's
    /// time limit). Only then does the outcome depend on the machine's speed.
    pub deadline: Option<Instant>,
    /// Told how far shortcutting is before every attempt (a progress line); it cannot
    /// change the outcome.
    pub progress: Option<fn(&ShortcutProgress)>,
    /// Threads the perturbed worlds of [`Criterion::MoreRobust`] are re-simulated on (0
    /// counts as one). The outcome does not depend on it: the worlds are judged in order and
    /// the work counted as if re-simulated one after another.
    pub threads: usize,
}

impl ShortcutSettings {
    /// A budget of about `seconds` of work.
    pub fn from_seconds(seconds: f64, seed: u64) -> Self {
        Self {
            budget_steps: (seconds.max(0.0) * STEPS_PER_SECOND) as u64,
            seed,
            deadline: None,
            progress: None,
            threads: 1,
        }
    }
}

/// How far shortcutting is.
#[derive(Clone, Copy, Debug)]
pub struct ShortcutProgress {
    /// Work done and the budget (propagation steps).
    pub work: u64,
    /// The whole budget (propagation steps).
    pub budget: u64,
    /// Shortcuts tried.
    pub attempts: usize,
    /// Shortcuts kept.
    pub accepted: usize,
    /// The current path's manipulator path (joint space) and duration (s).
    pub joint_length: f64,
    /// The current path's duration (s).
    pub duration: f64,
}

/// What shortcutting made of a path.
#[derive(Clone, Debug, PartialEq)]
pub struct ShortcutOutcome {
    /// The shortened path.
    pub controls: Vec<PathControl>,
    /// The metrics before.
    pub before: PathMetrics,
    /// The metrics after.
    pub after: PathMetrics,
    /// Shortcuts tried.
    pub attempts: usize,
    /// Shortcuts kept.
    pub accepted: usize,
    /// Shortcutting stopped at the deadline, with budget left.
    pub stopped_at_deadline: bool,
}

impl ShortcutOutcome {
    /// Nothing shortcut yet: `controls` with their metrics.
    pub fn unchanged(controls: &[PathControl], metrics: PathMetrics) -> Self {
        Self {
            controls: controls.to_vec(),
            before: metrics,
            after: metrics,
            attempts: 0,
            accepted: 0,
            stopped_at_deadline: false,
        }
    }

    /// This outcome followed by `next`, which shortcut this one's path further.
    pub fn then(self, next: ShortcutOutcome) -> Self {
        Self {
            before: self.before,
            attempts: self.attempts + next.attempts,
            accepted: self.accepted + next.accepted,
            stopped_at_deadline: self.stopped_at_deadline || next.stopped_at_deadline,
            ..next
        }
    }
}

/// What a shortcut must improve to be kept.
pub enum Criterion {
    /// The manipulator path in joint space (the paper's Sec. IV).
    Shorter,
    /// Reaching the goal in more of these perturbed worlds; in as many, a shorter path.
    /// Robust planning shortcuts toward the most robust path with it, and nudges.
    MoreRobust(Vec<PerturbedWorld>),
}

/// Shortcuts a valid path from `start` that reaches the scene's goal, keeping shortcuts
/// that make the manipulator path shorter.
pub fn shortcut(
    propagator: &mut Propagator,
    start: &State,
    controls: &[PathControl],
    settings: &ShortcutSettings,
) -> ShortcutOutcome {
    shortcut_by(
        propagator,
        start,
        controls,
        settings,
        &mut Criterion::Shorter,
    )
}

/// Shortcuts a valid path from `start` that reaches the scene's goal, keeping shortcuts
/// that improve it by `criterion`. Every kept path is valid and reaches the goal.
pub fn shortcut_by(
    propagator: &mut Propagator,
    start: &State,
    controls: &[PathControl],
    settings: &ShortcutSettings,
    criterion: &mut Criterion,
) -> ShortcutOutcome {
    let scene = propagator.shared_scene();
    let mut current = controls.to_vec();
    let mut path = simulate(propagator, start, &current, false);
    let before = path.metrics;
    let mut outcome = ShortcutOutcome::unchanged(&[], before);
    if !path.valid() || !scene.goal.is_satisfied(path.final_state()) {
        outcome.controls = current;
        return outcome;
    }
    let mut rng = SplitMix64::new(settings.seed ^ 0x5EED_5407_C0DE);
    let mut work = path.steps() as u64;
    let mut worlds = match criterion {
        Criterion::Shorter => None,
        Criterion::MoreRobust(worlds) => {
            Some(WorldRuns::new(worlds, settings.deadline, settings.threads))
        }
    };
    if let Some(worlds) = &mut worlds {
        let Some(spent) = worlds.run(&scene.goal, &current) else {
            outcome.stopped_at_deadline = true;
            outcome.controls = current;
            return outcome;
        };
        work += spent;
    }
    // Shortcuts need two controls to replace; nudges one.
    let least = if worlds.is_some() { 1 } else { 2 };
    while work < settings.budget_steps && current.len() >= least {
        if passed(settings.deadline) {
            outcome.stopped_at_deadline = true;
            break;
        }
        if let Some(progress) = settings.progress {
            progress(&ShortcutProgress {
                work,
                budget: settings.budget_steps,
                attempts: outcome.attempts,
                accepted: outcome.accepted,
                joint_length: path.metrics.joint_length,
                duration: path.metrics.duration,
            });
        }
        outcome.attempts += 1;
        // The candidate differs from the current path from control i on.
        let (i, candidate) = if worlds.is_some() && (current.len() < 2 || rng.below(2) == 0) {
            nudge(&current, &mut rng)
        } else {
            // Two states i < j at least two controls apart; controls i..j are replaced.
            let n = current.len();
            let i = rng.below(n - 1);
            let j = i + 2 + rng.below(n - i - 1);
            let Some(connection) =
                connection(propagator, &path.states[i], &path.states[j], &mut work)
            else {
                continue;
            };
            let mut candidate = current[..i].to_vec();
            candidate.extend(connection);
            candidate.extend_from_slice(&current[j..]);
            (i, candidate)
        };
        let tail = simulate(propagator, &path.states[i], &candidate[i..], false);
        work += tail.steps() as u64 + 1;
        if !tail.valid() || !scene.goal.is_satisfied(tail.final_state()) {
            continue;
        }
        let shorter =
            path.joint_length_at[i] + tail.metrics.joint_length < path.metrics.joint_length - 1e-9;
        let better = match &mut worlds {
            None => shorter,
            Some(worlds) => {
                // As robust and shorter, or more robust.
                let needed = worlds.reached + usize::from(!shorter);
                let (reaches, spent) = worlds.candidate_reaches(&scene.goal, &candidate, i, needed);
                work += spent;
                reaches
            }
        };
        if better {
            current = candidate;
            path = splice(&path, i, tail, propagator.step_size());
            outcome.accepted += 1;
            if let Some(worlds) = &mut worlds {
                // Cut short by the deadline, the runs are incomplete: no candidate is
                // judged by them (the loop stops at the deadline).
                work += worlds.run(&scene.goal, &current).unwrap_or(0);
            }
        }
    }
    if outcome.accepted > 0 {
        // The spliced path's joint length is a sum in another order: the reported
        // metrics are the path's simulated from its start.
        path = simulate(propagator, start, &current, false);
    }
    outcome.after = path.metrics;
    outcome.controls = current;
    outcome
}

/// The current path re-simulated in each perturbed world ([`Criterion::MoreRobust`]).
struct WorldRuns<'a> {
    worlds: &'a mut [PerturbedWorld],
    runs: Vec<SimulatedPath>,
    /// How many of the runs reach the goal.
    reached: usize,
    /// When re-simulating stops (the shortcutting's deadline).
    deadline: Option<Instant>,
    /// Worlds re-simulated at once, each on a thread of its own.
    threads: usize,
}

impl<'a> WorldRuns<'a> {
    fn new(worlds: &'a mut [PerturbedWorld], deadline: Option<Instant>, threads: usize) -> Self {
        Self {
            worlds,
            runs: vec![],
            reached: 0,
            deadline,
            threads: threads.max(1),
        }
    }

    /// Re-simulates `controls`, the new current path, in every world; returns the
    /// propagation steps spent, or `None` if the deadline came first.
    fn run(&mut self, goal: &Goal, controls: &[PathControl]) -> Option<u64> {
        self.runs.clear();
        for round in self.worlds.chunks_mut(self.threads) {
            if passed(self.deadline) {
                return None;
            }
            self.runs
                .extend(at_once(round, |world, _| world.run(controls)));
        }
        self.reached = self.runs.iter().filter(|r| reaches(goal, r)).count();
        Some(self.runs.iter().map(|r| r.steps() as u64).sum())
    }

    /// Whether `candidate`, which differs from the current path from control `i` on,
    /// reaches the goal in at least `needed` worlds, and the propagation steps spent
    /// finding out. Only the differing part is re-simulated, and only until the answer
    /// is known: the worlds are judged in order, `threads` re-simulated at once, and the
    /// steps of those judged counted (those re-simulated past the answer are not), so
    /// the answer and the count are those of one world after another.
    fn candidate_reaches(
        &mut self,
        goal: &Goal,
        candidate: &[PathControl],
        i: usize,
        needed: usize,
    ) -> (bool, u64) {
        let n = self.worlds.len();
        if needed > n {
            return (false, 0);
        }
        let (mut reached, mut failed, mut work) = (0, 0, 0);
        let runs = &self.runs;
        let starts = (0..).step_by(self.threads);
        for (first, round) in starts.zip(self.worlds.chunks_mut(self.threads)) {
            // Past the deadline the candidate is not judged (and not kept).
            if passed(self.deadline) {
                return (false, work);
            }
            // A world whose run stopped before control i fails the same way.
            let tails = at_once(round, |world, j| {
                let run = &runs[first + j];
                run.stopped_by
                    .as_ref()
                    .is_none_or(|(k, _)| *k >= i)
                    .then(|| world.simulate(&run.states[i], &candidate[i..]))
            });
            for tail in tails {
                work += tail.as_ref().map_or(0, |t| t.steps() as u64);
                if tail.is_some_and(|t| reaches(goal, &t)) {
                    reached += 1;
                } else {
                    failed += 1;
                }
                if reached >= needed || n - failed < needed {
                    return (reached >= needed, work);
                }
            }
        }
        (reached >= needed, work)
    }
}

/// `f(world, index in round)` for every world of `round`, each on a thread of its own (the
/// first on this one), in order.
fn at_once<R: Send>(
    round: &mut [PerturbedWorld],
    f: impl Fn(&mut PerturbedWorld, usize) -> R + Sync,
) -> Vec<R> {
    if round.len() == 1 {
        return vec![f(&mut round[0], 0)];
    }
    let f = &f;
    std::thread::scope(|scope| {
        let (first, rest) = round.split_first_mut().expect("a round has a world");
        let others: Vec<_> = rest
            .iter_mut()
            .enumerate()
            .map(|(j, world)| scope.spawn(move || f(world, j + 1)))
            .collect();
        let mut results = vec![f(first, 0)];
        results.extend(
            others
                .into_iter()
                .map(|h| h.join().expect("a world's re-simulation panicked")),
        );
        results
    })
}

/// `path` up to its state `i`, then `tail`, a valid path simulated from that state: the
/// joined path's states, contacts and joint lengths without simulating its first `i`
/// controls again (a propagation is a function of its state and control alone). On a
/// long first plan re-simulating the whole path after every kept shortcut took more than
/// half the budget. Of the metrics only the joint length and the duration (`dt` s a
/// step) are the joined path's, which is all the loop reads.
fn splice(path: &SimulatedPath, i: usize, tail: SimulatedPath, dt: f64) -> SimulatedPath {
    let before = path.joint_length_at[i];
    let prefix_steps: usize = path.contacts[..i].iter().map(Vec::len).sum();
    let mut states = path.states[..=i].to_vec();
    states.extend(tail.states.into_iter().skip(1));
    let mut joint_length_at = path.joint_length_at[..=i].to_vec();
    joint_length_at.extend(tail.joint_length_at[1..].iter().map(|l| before + l));
    let mut contacts = path.contacts[..i].to_vec();
    contacts.extend(tail.contacts);
    SimulatedPath {
        states,
        joint_length_at,
        step_states: vec![],
        contacts,
        stopped_by: None,
        metrics: PathMetrics {
            joint_length: before + tail.metrics.joint_length,
            duration: prefix_steps as f64 * dt + tail.metrics.duration,
            ..tail.metrics
        },
    }
}

/// `controls` with one of them, drawn at random, held for a different number of steps
/// ([`nudge_at`]).
fn nudge(controls: &[PathControl], rng: &mut SplitMix64) -> (usize, Vec<PathControl>) {
    nudge_at(controls, rng.below(controls.len()), rng)
}

/// `controls` with control `i` held for a different number of steps: up to half as many
/// more or fewer, at least one step.
pub(crate) fn nudge_at(
    controls: &[PathControl],
    i: usize,
    rng: &mut SplitMix64,
) -> (usize, Vec<PathControl>) {
    let steps = controls[i].steps;
    let change = 1 + rng.below(steps.div_ceil(2));
    let mut nudged = controls.to_vec();
    nudged[i].steps = if rng.below(2) == 0 || change >= steps {
        steps + change
    } else {
        steps - change
    };
    (i, nudged)
}

/// At most this many closing controls follow a connecting control (`connection`). The
/// first leaves a fifth to an eighth of the gap (joint space); three leave about 0.2 mrad of
/// gaps of 0.15-0.3 rad.
pub const CLOSING_CONTROLS: usize = 3;

/// A closing control lasts at least this many steps: it closes its gap at a fraction of
/// the speed bounds rather than in one step.
const CLOSING_STEPS: usize = 5;

/// The controls that take the arm from state `from` to state `to`'s configuration: the
/// connecting control, then up to [`CLOSING_CONTROLS`] closing controls (each the
/// connecting control from where the last ended, at least [`CLOSING_STEPS`] long) while a
/// joint is off by more than 1 nrad. `None` if the connecting control is not valid; the
/// closing controls stop before the first that is not. The steps simulated are added to
/// `work`.
pub(crate) fn connection(
    propagator: &mut Propagator,
    from: &State,
    to: &State,
    work: &mut u64,
) -> Option<Vec<PathControl>> {
    let connect = connecting_control(propagator, from, to)?;
    let mut at = valid_end(propagator, from, &connect, work)?;
    let mut controls = vec![connect];
    while controls.len() <= CLOSING_CONTROLS && (&to.q - &at.q).amax() >= 1e-9 {
        let Some(closing) = connecting_control(propagator, &at, to) else {
            break;
        };
        let closing = stretched(closing, CLOSING_STEPS);
        let Some(end) = valid_end(propagator, &at, &closing, work) else {
            break;
        };
        at = end;
        controls.push(closing);
    }
    Some(controls)
}

/// The state `control` ends in from `from`, if every step is valid; its steps are added
/// to `work`.
fn valid_end(
    propagator: &mut Propagator,
    from: &State,
    control: &PathControl,
    work: &mut u64,
) -> Option<State> {
    let run = simulate(propagator, from, std::slice::from_ref(control), false);
    *work += run.steps() as u64 + 1;
    run.valid().then(|| run.final_state().clone())
}

/// `control` slowed down to last at least `steps`, going as far.
fn stretched(mut control: PathControl, steps: usize) -> PathControl {
    if control.steps < steps {
        let slower = control.steps as f64 / steps as f64;
        control
            .action
            .velocity
            .iter_mut()
            .for_each(|v| *v *= slower);
        control.action.nullspace *= slower;
        control.steps = steps;
    }
    control
}

/// The action that moves the end effector in a straight line (and turns it) from its pose
/// in state `a` to its pose in state `b` at the scene's speed bounds, pulling the joints
/// towards `b`'s configuration through the null space.
pub(crate) fn connecting_control(
    propagator: &Propagator,
    a: &State,
    b: &State,
) -> Option<PathControl> {
    let scene = propagator.scene();
    let robot = &scene.robot;
    let (ta, tb) = (
        robot.tool_pose(&robot.link_poses(&a.q)),
        robot.tool_pose(&robot.link_poses(&b.q)),
    );
    let yaw = |t: &nalgebra::Isometry3<f64>| {
        (t.rotation * robot.plane.orientation.inverse())
            .euler_angles()
            .2
    };
    let (dx, dy) = (
        tb.translation.x - ta.translation.x,
        tb.translation.y - ta.translation.y,
    );
    let dyaw = wrap_angle(yaw(&tb) - yaw(&ta));
    let p = &scene.planner;
    let time = (dx.abs().max(dy.abs()) / p.max_ee_speed).max(dyaw.abs() / p.max_ee_turn_rate);
    let steps = ((time / p.step).ceil() as usize).max(1);
    let duration = steps as f64 * p.step;
    let pull: DVector<f64> = (&b.q - &a.q) / duration;
    pull.iter().all(|v| v.is_finite()).then(|| PathControl {
        action: EeAction {
            velocity: [dx / duration, dy / duration, dyaw / duration],
            nullspace: pull,
        },
        steps,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scene;

    /// The planar hand pushes the box of `tests/data/hand_push_straight.yaml` (0.13 m
    /// ahead of it) in eight controls, turning on the way.
    fn pushes() -> Vec<PathControl> {
        (0..8)
            .map(|k| PathControl {
                action: EeAction::planar(0.2, if k % 2 == 0 { 0.02 } else { -0.02 }, 0.1),
                steps: 15,
            })
            .collect()
    }

    /// The WAM of the default scene moves its hand about in free space (back from the
    /// objects, then sideways and turning) while the null-space pulls swing its elbow.
    fn wandering_arm() -> (Scene, Vec<PathControl>) {
        let scene = Scene::load("scenes/herb_fig1_clutter.yaml").unwrap();
        let dof = scene.robot.dof();
        let controls = (0..8)
            .map(|k| PathControl {
                action: EeAction {
                    velocity: [-0.1, if k < 4 { 0.1 } else { -0.1 }, 0.2],
                    nullspace: DVector::from_fn(dof, |d, _| if d % 2 == 0 { 1.0 } else { -1.0 }),
                },
                steps: 20,
            })
            .collect();
        (scene, controls)
    }

    #[test]
    fn a_connection_ends_on_the_configuration_the_rest_of_the_path_goes_on_from() {
        let (scene, controls) = wandering_arm();
        let mut propagator = Propagator::new(scene.clone());
        let path = simulate(&mut propagator, &scene.start, &controls, false);
        assert!(path.valid(), "{:?}", path.stopped_by);
        assert_eq!(
            path.final_state().objects,
            scene.start.objects,
            "the arm must move free"
        );
        let (i, j) = (1, 6);
        // Without the closing controls, 240 of 256 shortcuts across the free stretches of
        // a long Panda plan failed in their tail, most far down it; with them 55 of 152
        // (notes: any-arm.md, "Shortcuts that arrive where the path went on").
        let (from, to) = (&path.states[i], &path.states[j]);
        let miss = |s: &State| (&to.q - &s.q).amax();

        let straight = connecting_control(&propagator, from, to).unwrap();
        let alone = simulate(
            &mut propagator,
            from,
            std::slice::from_ref(&straight),
            false,
        );
        let mut work = 0;
        let connection = connection(&mut propagator, from, to, &mut work).unwrap();
        let closed = simulate(&mut propagator, from, &connection, false);
        assert!(alone.valid() && closed.valid());
        // The connecting control alone ends off state j's configuration (1.6 mrad); the
        // closing controls after it bring the arm onto it (0.01 mrad).
        assert_eq!(connection[0], straight);
        assert!(connection.len() > 1 && connection.len() <= 1 + CLOSING_CONTROLS);
        let (open, shut) = (miss(alone.final_state()), miss(closed.final_state()));
        assert!(open > 5e-4 && shut < open / 50.0, "{open} then {shut}");
        // What it simulated is counted.
        assert!(work as usize >= closed.steps());

        // The rest of the path, replayed from there, goes where it went.
        let rest = &controls[j..];
        let replay = |s: &State, propagator: &mut Propagator| {
            simulate(propagator, s, rest, false).final_state().clone()
        };
        let after_straight = replay(alone.final_state(), &mut propagator);
        let after_closed = replay(closed.final_state(), &mut propagator);
        let off = |s: &State| (&path.final_state().q - &s.q).amax();
        let (open, shut) = (off(&after_straight), off(&after_closed));
        assert!(shut < open / 50.0, "{open} then {shut}");
    }

    #[test]
    fn a_path_spliced_after_a_state_is_the_path_simulated_from_its_start() {
        let scene = Scene::load("tests/data/hand_push_straight.yaml").unwrap();
        let mut propagator = Propagator::new(scene.clone());
        let controls = pushes();
        let whole = simulate(&mut propagator, &scene.start, &controls, false);
        assert!(whole.valid());
        let pushed_from = whole
            .contacts
            .iter()
            .position(|c| c.iter().any(|s| !s.is_empty()));
        assert!(
            pushed_from.is_some_and(|k| k > 0 && k < 7),
            "{pushed_from:?}"
        );
        for i in [0, 3, 7] {
            let tail = simulate(&mut propagator, &whole.states[i], &controls[i..], false);
            let spliced = splice(&whole, i, tail, propagator.step_size());
            // Bit for bit where it matters (the states and pushes the loop builds on);
            // the lengths, sums in another order, to rounding.
            assert_eq!(spliced.states, whole.states);
            assert_eq!(spliced.contacts, whole.contacts);
            for (a, b) in spliced.joint_length_at.iter().zip(&whole.joint_length_at) {
                assert!((a - b).abs() < 1e-12, "{a} vs {b}");
            }
            let (s, w) = (spliced.metrics, whole.metrics);
            assert!((s.joint_length - w.joint_length).abs() < 1e-12);
            assert!((s.duration - w.duration).abs() < 1e-12);
        }
    }
}
