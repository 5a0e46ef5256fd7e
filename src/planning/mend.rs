//! Mending the rest of a plan that a world off the model broke, before searching anew.
//!
//! Closing the loop re-simulates the rest of a plan from each observed state
//! ([`crate::planning::rest`]). Often it stops being valid at one control far from its end
//! (a link of the arm comes a millimetre inside its clearance of a glass that sits 5 mm
//! from where the plan had it) and the rest of it is still good. A search from the
//! observed state, or from where the rest stops, must then find the whole way to the goal
//! again: in a hard scene it finds nothing in its seconds, and the trial is lost with a
//! good plan in hand.
//!
//! A mend edits the rest where it fails, as shortcutting edits a path
//! ([`crate::planning::shortcut`]), and keeps the first edit that is valid from the
//! observed state and does the plan's work:
//! - a **detour** where a control stops being valid: the arm is taken from a state up to
//!   [`REACH`] controls before that control (straight, or every other time by way of a
//!   waypoint with its revolute joints turned) to the configuration the rest has up
//!   to [`REACH`] controls after it (the configuration the arm alone reaches: objects never
//!   move it), and the rest goes on from there;
//! - a **nudge** where the rest ends short of the goal, or as every other attempt at a
//!   stop: one control near the end (or the stop) held for a different number of steps
//!   (a push held longer carries its object further; one stopped earlier does not tip it).
//!
//! The budget is counted in propagation steps, as shortcutting's, so a mend is
//! deterministic under its seed, unless its deadline stops it first.
//!
//! The executor mends only when asked (`--replan-mend`): side by side on hard dense
//! scenes in MuJoCo mends reached the goal as often as searches alone, and they do not
//! free dense 17's trials, where the arm passes a glass 9 mm off along a long stretch of
//! the plan (docs/notes/plans-in-the-world.md, "Mending the rest before searching").

use crate::planning::passed;
use crate::planning::path::{simulate, PathControl, SimulatedPath};
#[cfg(doc)]
use crate::planning::shortcut::STEPS_PER_SECOND;
use crate::planning::shortcut::{connecting_control, connection, nudge_at};
use crate::propagate::Propagator;
use crate::random::SplitMix64;
use crate::robot::chain::JointKind;
use crate::robot::Robot;
use crate::state::State;
use nalgebra::{DVector, Isometry3};
use std::time::Instant;

/// A detour leaves the rest at most this many controls before the control that stops
/// being valid, and joins it again at most this many after; a nudge changes a control at
/// most this many before the stop or the rest's end. Far enough to go round an object
/// (a control lasts 0.1-0.5 s), near enough that the rest after the detour is the plan's.
pub const REACH: usize = 8;

/// How far a detour's waypoint turns each revolute joint off the rest's configuration
/// (rad; prismatic joints stay).
pub const WAYPOINT_TURN: f64 = 0.3;

/// How a mend runs: its budget in propagation steps and its seed.
#[derive(Clone, Copy, Debug)]
pub struct MendSettings {
    /// Work budget in propagation steps.
    pub budget_steps: u64,
    /// Seeds the choice of edits.
    pub seed: u64,
    /// Wall-clock time at which the mend stops even if budget is left: a step among many
    /// objects in contact costs several times what [`STEPS_PER_SECOND`] counts on, and
    /// the arm waits on a mend. Only then does the outcome depend on the machine's speed.
    pub deadline: Option<Instant>,
}

/// A rest mended: valid from its start and doing the plan's work.
#[derive(Clone, Debug, PartialEq)]
pub struct Mended {
    /// The mended rest.
    pub controls: Vec<PathControl>,
    /// Edits tried (the last one kept).
    pub attempts: usize,
    /// Propagation steps spent.
    pub work: u64,
}

/// The rest `controls` from `start` mended ([module docs](self)): the first edit that is
/// valid to its end and whose final state `reaches` accepts, within the budget; `None` if
/// none is found, or the rest needs no mend (it is valid and reaches), or it is empty.
pub fn mend(
    propagator: &mut Propagator,
    start: &State,
    controls: &[PathControl],
    reaches: impl Fn(&State) -> bool,
    settings: &MendSettings,
) -> Option<Mended> {
    let n = controls.len();
    if n == 0 {
        return None;
    }
    let path = simulate(propagator, start, controls, false);
    let mut work = path.steps() as u64 + 1;
    // The control that stops being valid, or none where the rest ends short.
    let stop = match &path.stopped_by {
        Some((k, _)) => Some(*k),
        None if reaches(path.final_state()) => return None,
        None => None,
    };
    // The configurations a detour may join: up to REACH controls after the stop (none
    // where the rest ends short: only nudges are tried).
    let joinable = stop.map_or(0, |k| (k + 1 + REACH).min(n));
    let arm = arm_configurations(
        &propagator.scene().robot,
        &start.q,
        &controls[..joinable],
        propagator.step_size(),
    );
    let mut rng = SplitMix64::new(settings.seed ^ 0x3E4D_0F7E);
    let mut attempts = 0;
    while work < settings.budget_steps && !passed(settings.deadline) {
        attempts += 1;
        // An attempt that simulates nothing (no configuration to join) still counts.
        work += 1;
        let (i, candidate) = match stop {
            // A detour round the stop, or every other attempt a nudge before it.
            Some(k) if rng.below(2) == 0 || k == 0 => {
                let Some((i, candidate)) =
                    detour(propagator, &path, controls, &arm, k, &mut rng, &mut work)
                else {
                    continue;
                };
                (i, candidate)
            }
            Some(k) => nudge_at(controls, k - rng.below(k.min(REACH)) - 1, &mut rng),
            None => nudge_at(controls, n - 1 - rng.below(n.min(REACH + 1)), &mut rng),
        };
        let tail = simulate(propagator, &path.states[i], &candidate[i..], false);
        work += tail.steps() as u64 + 1;
        if tail.valid() && reaches(tail.final_state()) {
            return Some(Mended {
                controls: candidate,
                attempts,
                work,
            });
        }
    }
    None
}

/// A detour round control `k`, which stops being valid: from the path's state `i` (up to
/// [`REACH`] before `k`) a connection to the arm's configuration after control `j` (up to
/// [`REACH`] after `k`), every other time by way of a waypoint, then the rest's controls
/// from `j`. Returns `i`, where the candidate starts to differ, and the candidate; `None`
/// where a connection is not valid or the arm's configuration after `j` is unknown.
fn detour(
    propagator: &mut Propagator,
    path: &SimulatedPath,
    controls: &[PathControl],
    arm: &[DVector<f64>],
    k: usize,
    rng: &mut SplitMix64,
    work: &mut u64,
) -> Option<(usize, Vec<PathControl>)> {
    let n = controls.len();
    let i = k - rng.below(k.min(REACH) + 1);
    let j = k + 1 + rng.below((n - k - 1).min(REACH) + 1);
    let from = &path.states[i];
    let to = State {
        q: arm.get(j)?.clone(),
        objects: from.objects.clone(),
    };
    let mut candidate = controls[..i].to_vec();
    // Every other detour goes by way of a configuration off the rest's: one between `i`
    // and `j` with every revolute joint turned by up to [`WAYPOINT_TURN`], which swings
    // the links the null space moves (a WAM's elbow) another way round the object.
    let mut at = from.clone();
    if rng.below(2) == 0 {
        let m = i + rng.below(j - i + 1);
        let chain = &propagator.scene().robot.chain;
        let mut q = arm[m].clone();
        for (d, q) in q.iter_mut().enumerate() {
            if chain.dof_joint(d).kind == JointKind::Revolute {
                *q += rng.uniform(-WAYPOINT_TURN, WAYPOINT_TURN);
            }
        }
        let way = State {
            q,
            objects: from.objects.clone(),
        };
        let to_way = connecting_control(propagator, from, &way)?;
        let run = simulate(propagator, from, std::slice::from_ref(&to_way), false);
        *work += run.steps() as u64 + 1;
        if !run.valid() {
            return None;
        }
        at = run.final_state().clone();
        candidate.push(to_way);
    }
    candidate.extend(connection(propagator, &at, &to, work)?);
    candidate.extend_from_slice(&controls[j..]);
    Some((i, candidate))
}

/// The arm's configuration at the start and after each of `controls` from `q` (steps of
/// `dt` s), as the arm alone moves (in the planar pushing model objects never move it), up
/// to the first step its projection refuses.
fn arm_configurations(
    robot: &Robot,
    q: &DVector<f64>,
    controls: &[PathControl],
    dt: f64,
) -> Vec<DVector<f64>> {
    let mut q = q.clone();
    let mut poses: Vec<Isometry3<f64>> = robot.link_poses(&q);
    let (mut q_new, mut poses_new) = (q.clone(), Vec::with_capacity(poses.len()));
    let mut along = vec![q.clone()];
    for control in controls {
        for _ in 0..control.steps {
            if robot
                .project_step(&q, &poses, &control.action, dt, &mut q_new, &mut poses_new)
                .is_err()
            {
                return along;
            }
            std::mem::swap(&mut q, &mut q_new);
            std::mem::swap(&mut poses, &mut poses_new);
        }
        along.push(q.clone());
    }
    along
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planning::shortcut::CLOSING_CONTROLS;
    use crate::robot::EeAction;
    use crate::{Pose2, Scene};

    /// The planar hand of `tests/data/hand_round_a_stick.yaml` (a box 0.04 m deep, its
    /// centre at x = 0.35 m) swings out to y = 0.08 m and back in four controls, where the
    /// plan had nothing, then pushes the box (centre 0.7 m, 0.1 m wide) straight ahead in
    /// seven: 0.04 m a control, the hand's centre ends at x = 0.79 m.
    fn round_and_push() -> Vec<PathControl> {
        let control = |vx: f64, vy: f64| PathControl {
            action: EeAction::planar(vx, vy, 0.0),
            steps: 20,
        };
        let mut controls = vec![control(0.2, 0.2), control(0.2, 0.2)];
        controls.extend([control(0.2, -0.2), control(0.2, -0.2)]);
        controls.extend((0..7).map(|_| control(0.2, 0.0)));
        controls
    }

    fn settings(budget_steps: u64) -> MendSettings {
        MendSettings {
            budget_steps,
            seed: 7,
            deadline: None,
        }
    }

    #[test]
    fn a_rest_that_meets_a_stick_where_the_plan_had_none_goes_round_it_to_the_goal() {
        let scene = Scene::load("tests/data/hand_round_a_stick.yaml").unwrap();
        let controls = round_and_push();
        let mut propagator = Propagator::new(scene.clone());
        let planned = simulate(&mut propagator, &scene.start, &controls, false);
        assert!(planned.valid(), "{:?}", planned.stopped_by);
        let box_at = |s: &State| s.objects[0];
        // A straight push through the box's centre: it ends touching the hand's face,
        // 0.02 + 0.05 m ahead of the hand's centre, unturned.
        let pushed = box_at(planned.final_state());
        assert!((pushed.x - (0.79 + 0.07)).abs() < 1e-6 && pushed.theta.abs() < 1e-9);
        let reaches = |s: &State| scene.goal.is_satisfied(s);
        assert!(reaches(planned.final_state()));

        // The world has the stick where the hand swings out (the hand spans y 0.02 to
        // 0.14 m there): pushed there it would tip, so the rest stops being valid.
        let mut observed = scene.start.clone();
        observed.objects[1] = Pose2::new(0.45, 0.11, 0.0);
        let mut propagator = Propagator::new(scene.clone());
        let broken = simulate(&mut propagator, &observed, &controls, false);
        let (k, rule) = broken.stopped_by.clone().expect("the stick is in the way");
        assert!(k < 4 && rule.to_string().contains("stick"), "{k}: {rule}");

        let mended = mend(
            &mut propagator,
            &observed,
            &controls,
            reaches,
            &settings(50_000),
        )
        .expect("a detour round the stick");
        let path = simulate(&mut propagator, &observed, &mended.controls, false);
        assert!(path.valid(), "{:?}", path.stopped_by);
        assert!(reaches(path.final_state()));
        // The stick is never touched, and after the detour the rest goes on as planned:
        // the plan's controls before it and after it, the detour itself a connection and
        // its closing controls (with a waypoint's one more).
        assert!(path
            .states
            .iter()
            .all(|s| s.objects[1] == observed.objects[1]));
        let m = &mended.controls;
        let before = (0..=k).take_while(|&c| m[c] == controls[c]).count();
        let after = (1..=m.len().min(controls.len()))
            .take_while(|&c| m[m.len() - c] == controls[controls.len() - c])
            .count();
        let joined = controls.len() - after;
        assert!(
            before <= k && joined > k && joined <= k + 1 + REACH,
            "{before} {joined}"
        );
        assert!(m.len() - before - after <= 2 + CLOSING_CONTROLS, "{m:?}");
        // A detour that joins before the pushes leaves them as planned, the box where the
        // plan put it; one that joins later pushes the box itself, straight at the rest's
        // configuration, and the box ends in the disc within a centimetre of it.
        let off = box_at(path.final_state());
        let tolerance = if joined <= 4 { 1e-6 } else { 0.01 };
        assert!(
            (off.x - pushed.x).abs() < tolerance && (off.y - pushed.y).abs() < tolerance,
            "{off:?} against {pushed:?}, joined at {joined}"
        );
        assert!(mended.work <= 50_000 + 10_000, "{}", mended.work);
    }

    #[test]
    fn a_rest_that_ends_short_is_mended_by_holding_a_push_longer() {
        let scene = Scene::load("tests/data/hand_round_a_stick.yaml").unwrap();
        let controls = round_and_push();
        let mut propagator = Propagator::new(scene.clone());
        // Asked to carry the box past x = 0.875 m, 0.015 m beyond where the plan ends it.
        let further = |s: &State| s.objects[0].x > 0.875;
        let short = simulate(&mut propagator, &scene.start, &controls, false);
        assert!(short.valid() && !further(short.final_state()));
        let mended = mend(
            &mut propagator,
            &scene.start,
            &controls,
            further,
            &settings(50_000),
        )
        .expect("a push held longer");
        // One push, one of the last, is held longer; nothing else changes.
        assert_eq!(mended.controls.len(), controls.len());
        let changed: Vec<usize> = (0..controls.len())
            .filter(|&i| mended.controls[i] != controls[i])
            .collect();
        assert_eq!(changed.len(), 1, "{changed:?}");
        let i = changed[0];
        assert!(i >= 4 && mended.controls[i].action == controls[i].action);
        let extra = mended.controls[i].steps - controls[i].steps;
        // The box ends ahead of the hand's face by as much as the hand went further:
        // 0.2 m/s for each extra step of 0.01 s.
        let path = simulate(&mut propagator, &scene.start, &mended.controls, false);
        let x = path.final_state().objects[0].x;
        assert!(
            (x - (0.86 + 0.002 * extra as f64)).abs() < 1e-6,
            "{x} after {extra} steps more"
        );
    }

    #[test]
    fn a_rest_that_reaches_or_a_mend_without_budget_gives_nothing() {
        let scene = Scene::load("tests/data/hand_round_a_stick.yaml").unwrap();
        let controls = round_and_push();
        let mut propagator = Propagator::new(scene.clone());
        let reaches = |s: &State| scene.goal.is_satisfied(s);
        assert_eq!(
            mend(
                &mut propagator,
                &scene.start,
                &controls,
                reaches,
                &settings(1 << 20)
            ),
            None
        );
        let mut observed = scene.start.clone();
        observed.objects[1] = Pose2::new(0.45, 0.11, 0.0);
        assert_eq!(
            mend(&mut propagator, &observed, &controls, reaches, &settings(0)),
            None
        );
        assert_eq!(
            mend(&mut propagator, &observed, &[], reaches, &settings(1 << 20)),
            None
        );
    }
}
