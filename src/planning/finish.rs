//! Finishing a found path, one way for the CLI, the C++ API and `bench`: re-simulate it
//! (it must reproduce the planner's states and, if solved, reach the goal), shortcut it
//! (Sec. IV) and, in robust planning, shortcut toward the most robust path.

use crate::planning::passed;
use crate::planning::path::{simulate, PathControl, PathMetrics, SimulatedPath};
use crate::planning::robustness::{robustness_until, Noise, PerturbedWorld};
use crate::planning::shortcut::{
    shortcut_by, Criterion, ShortcutOutcome, ShortcutProgress, ShortcutSettings,
};
use crate::propagate::Propagator;
use crate::random::SplitMix64;
use crate::scene::Scene;
use crate::state::State;
use std::time::Instant;

/// How a found path is finished.
#[derive(Clone, Copy, Debug)]
pub struct FinishSettings {
    /// Shortcutting budget in seconds of work (0: none).
    pub shortcut: f64,
    /// Seeds shortcutting and the robustness trials.
    pub seed: u64,
    /// The robustness a solution must keep, if any.
    pub robust: Option<RobustRequirement>,
    /// With `robust`: the whole budget toward robustness, for a solution not robust
    /// enough yet (robust planning's search loop); else shortening first, then toward
    /// robustness, half the budget each (the plan's final shortcutting, which keeps the
    /// rate found). Shortened first, a fragile solution came out less robust than as found
    /// in most finishings, and the half left toward robustness started from the shorter,
    /// more fragile path (BENCHMARKS.md, "Robust finishing").
    pub only_toward_robustness: bool,
    /// Perturbed worlds no solution was chosen in that the finished path is measured in
    /// (measured by `finish`; robust planning's final finishing), 0: none.
    pub unseen_trials: usize,
    /// The found path's success rate under `robust`, if the caller measured it already
    /// (with the same seed): not measured again.
    pub found_rate: Option<MeasuredRate>,
    /// When shortcutting and robustness checks must stop, budget left or not (the plan's
    /// time limit): a check cut short is over the trials it ran ([`MeasuredRate`]).
    pub deadline: Option<Instant>,
    /// Told how far shortcutting is (a progress line).
    pub progress: Option<fn(&ShortcutProgress)>,
    /// Threads the shortcutting toward robustness re-simulates its perturbed worlds on
    /// (0 counts as one; the finished path does not depend on it).
    pub threads: usize,
}

/// Keep a path only if at least `rate` of `trials` perturbed re-simulations
/// ([`crate::planning::robustness`], default noise) reach the goal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobustRequirement {
    /// Perturbed re-simulations.
    pub trials: usize,
    /// Fraction of them that must reach the goal.
    pub rate: f64,
}

/// A success rate under noise, and the perturbed re-simulations it is over: fewer than
/// asked where the time limit cut the check short (the first of those asked: the same
/// seed and that many trials measure it again).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeasuredRate {
    /// Fraction of the trials that reached the goal.
    pub rate: f64,
    /// Perturbed re-simulations run.
    pub trials: usize,
}

impl RobustRequirement {
    /// The fraction of perturbed re-simulations of `controls` that reach the goal, over
    /// the trials run by `deadline` (at least one).
    pub fn success_rate(
        &self,
        scene: &Scene,
        controls: &[PathControl],
        seed: u64,
        deadline: Option<Instant>,
    ) -> MeasuredRate {
        measured_rate(scene, controls, self.trials, seed, deadline)
    }

    /// Whether a shortcut path measured at `shortcut` replaces the path as found, measured
    /// at `found`: if robust enough, or at least as robust as the path as found, over as many
    /// trials. A check the deadline cut short does not replace a path measured in full (a
    /// shortcut right before the time limit, rated 100 % over one trial, took the place of
    /// a path measured robust over 20).
    pub fn keeps(&self, shortcut: MeasuredRate, found: MeasuredRate) -> bool {
        shortcut.rate >= found.rate.min(self.rate) && shortcut.trials >= found.trials
    }

    /// As many perturbed worlds as trials to shortcut toward robustness in, drawn apart
    /// from [`Self::success_rate`]'s: the requirement is checked in worlds the path was
    /// not fitted to.
    pub fn shortcut_worlds(&self, scene: &Scene, seed: u64) -> Vec<PerturbedWorld> {
        let mut rng = SplitMix64::new(seed ^ 0x0B57_AC1E_5EED);
        (0..self.trials)
            .filter_map(|_| PerturbedWorld::draw(&Noise::default(), scene, &mut rng).ok())
            .collect()
    }
}

/// The fraction of `trials` perturbed re-simulations of `controls` (default noise, worlds
/// drawn from `seed`) that reach the goal, over those run by `deadline` (at least one).
fn measured_rate(
    scene: &Scene,
    controls: &[PathControl],
    trials: usize,
    seed: u64,
    deadline: Option<Instant>,
) -> MeasuredRate {
    let report = robustness_until(scene, controls, &Noise::default(), trials, seed, deadline);
    MeasuredRate {
        rate: report.success_rate,
        trials: report.trials.len(),
    }
}

/// The fraction of `trials` perturbed re-simulations of `controls` that reach the goal in
/// worlds drawn apart from the check's and the shortcutting's ([`unseen_seed`]); `None` if
/// `deadline` has passed. Every solution of a robust run is judged in the check's worlds
/// and the plan is the first to pass there (or the best set aside), so the check's rate is
/// the luckiest of the run: plans stated at 95 % measured 82-98 % over 200 other worlds
/// (BENCHMARKS.md, "Robust finishing"). Worlds the choice did not see give a rate without
/// that bias.
fn unseen_rate(
    scene: &Scene,
    controls: &[PathControl],
    trials: usize,
    seed: u64,
    deadline: Option<Instant>,
) -> Option<MeasuredRate> {
    (trials > 0 && !passed(deadline))
        .then(|| measured_rate(scene, controls, trials, unseen_seed(seed), deadline))
}

/// The seed of the worlds a plan made with `seed` is measured in after its choice
/// (by `finish`): a stream of its own, apart from the check's (`seed`) and the
/// shortcutting's ([`RobustRequirement::shortcut_worlds`]).
pub fn unseen_seed(seed: u64) -> u64 {
    seed ^ 0x0005_EED0_F7E5_7ED5
}

/// What shortcutting did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ShortcutReport {
    /// Shortcuts tried.
    pub attempts: usize,
    /// Shortcuts kept.
    pub accepted: usize,
    /// The shortcut path was dropped because it was less robust than required.
    pub dropped_as_less_robust: bool,
    /// Shortcutting stopped at the deadline with budget left.
    pub stopped_at_deadline: bool,
}

/// A finished path.
#[derive(Clone, Debug, PartialEq)]
pub struct FinishedPath {
    /// The finished path's controls.
    pub controls: Vec<PathControl>,
    /// The finished path simulated from the start, every step's state recorded.
    pub simulation: SimulatedPath,
    /// The metrics of the path as found (the same as after if nothing was shortened).
    pub before: PathMetrics,
    /// What shortcutting did.
    pub shortcut: ShortcutReport,
    /// The finished path's success rate under noise, in robust planning.
    pub robustness: Option<MeasuredRate>,
    /// Its rate in worlds no solution was chosen in (`FinishSettings::unseen_trials`).
    pub unseen: Option<MeasuredRate>,
}

/// Finishes `found` in `scene` (the scene the planner searched). `found_states` are the
/// planner's states at the control boundaries, start first; re-simulation must reproduce
/// them bit for bit. Only solved paths are shortened and measured for robustness.
pub fn finish(
    scene: &Scene,
    found: &[PathControl],
    found_states: &[State],
    solved: bool,
    settings: &FinishSettings,
) -> Result<FinishedPath, String> {
    if !(settings.shortcut.is_finite() && settings.shortcut >= 0.0) {
        return Err(format!(
            "the shortcut budget must be zero or positive, got {}",
            settings.shortcut
        ));
    }
    let mut propagator = Propagator::new(scene.clone());
    // Every step recorded: the plan file is written from this simulation
    // (`PlanFile::from_simulation`), not from another one.
    let simulating = Instant::now();
    let path = simulate(&mut propagator, &scene.start, found, true);
    // The rate in unseen worlds is measured last, on the finished path, within the
    // deadline: shortcutting stops early by what it takes, as long as this simulation
    // (which records every step, slower than a world's run) for each world, with half
    // again to spare.
    let unseen_reserve = simulating
        .elapsed()
        .mul_f64(1.5 * settings.unseen_trials as f64);
    let shortcut_deadline = settings
        .deadline
        .map(|d| d.checked_sub(unseen_reserve).unwrap_or(d));
    // A search stopped before it had a path (a limit of a millisecond) found none: the
    // start alone, which needs no reproducing.
    let nothing_found = found.is_empty() && found_states.is_empty();
    let reproduced = path.valid() && (nothing_found || path.states.as_slice() == found_states);
    if !reproduced || (solved && !scene.goal.is_satisfied(path.final_state())) {
        return Err(format!(
            "internal error: re-simulating the plan does not reproduce it{}",
            path.stopped_by
                .as_ref()
                .map(|(i, why)| format!(" (control {i}: {why})"))
                .unwrap_or_default()
        ));
    }
    let mut finished = FinishedPath {
        controls: found.to_vec(),
        before: path.metrics,
        simulation: path,
        shortcut: ShortcutReport::default(),
        robustness: None,
        unseen: None,
    };
    if !solved {
        return Ok(finished);
    }
    if settings.shortcut > 0.0 {
        let budget = ShortcutSettings {
            deadline: shortcut_deadline,
            progress: settings.progress,
            threads: settings.threads,
            ..ShortcutSettings::from_seconds(settings.shortcut, settings.seed)
        };
        // Robust planning's final shortcutting shortens first (fewer pushes: less to go
        // wrong), then shortcuts toward the most robust path, half the budget each; a
        // solution not robust enough yet spends it all toward robustness (which also keeps
        // shorter paths that reach the goal in as many worlds).
        let mut stages = vec![];
        if settings.robust.is_none() || !settings.only_toward_robustness {
            stages.push(Criterion::Shorter);
        }
        if let Some(r) = settings.robust {
            stages.push(Criterion::MoreRobust(
                r.shortcut_worlds(scene, settings.seed),
            ));
        }
        let stage_budget = ShortcutSettings {
            budget_steps: budget.budget_steps / stages.len() as u64,
            ..budget
        };
        let mut outcome = ShortcutOutcome::unchanged(found, finished.before);
        for mut criterion in stages {
            // A propagator of its own: the outcome does not depend on what ran before.
            let stage = shortcut_by(
                &mut Propagator::new(scene.clone()),
                &scene.start,
                &outcome.controls,
                &stage_budget,
                &mut criterion,
            );
            outcome = outcome.then(stage);
        }
        finished.shortcut.attempts = outcome.attempts;
        finished.shortcut.accepted = outcome.accepted;
        finished.shortcut.stopped_at_deadline = outcome.stopped_at_deadline;
        if outcome.accepted > 0 {
            let rates = settings.robust.map(|r| {
                let rate =
                    |controls| r.success_rate(scene, controls, settings.seed, shortcut_deadline);
                let found_rate = settings.found_rate.unwrap_or_else(|| rate(found));
                (r, rate(&outcome.controls), found_rate)
            });
            if rates.is_none_or(|(r, shortcut, found)| r.keeps(shortcut, found)) {
                finished.simulation =
                    simulate(&mut propagator, &scene.start, &outcome.controls, true);
                finished.controls = outcome.controls;
                finished.robustness = rates.map(|(_, shortcut, _)| shortcut);
            } else {
                finished.shortcut.dropped_as_less_robust = true;
            }
        }
    }
    // The rate of the finished controls, unless the shortcut's check or the caller
    // already measured it (unmeasured here, the finished controls are the found ones).
    if finished.robustness.is_none() {
        finished.robustness = settings.robust.map(|r| {
            settings.found_rate.unwrap_or_else(|| {
                r.success_rate(scene, &finished.controls, settings.seed, settings.deadline)
            })
        });
    }
    finished.unseen = unseen_rate(
        scene,
        &finished.controls,
        settings.unseen_trials,
        settings.seed,
        settings.deadline,
    );
    Ok(finished)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shortcut_replaces_the_found_path_only_if_as_robust_over_as_many_trials() {
        let required = RobustRequirement {
            trials: 20,
            rate: 0.95,
        };
        let rate = |rate, trials| MeasuredRate { rate, trials };
        // Robust enough, though less than as found.
        assert!(required.keeps(rate(0.95, 20), rate(1.0, 20)));
        // Not robust enough, but more robust than as found.
        assert!(required.keeps(rate(0.6, 20), rate(0.55, 20)));
        assert!(!required.keeps(rate(0.5, 20), rate(0.55, 20)));
        // Cut short by the deadline: one lucky trial does not replace 20 measured.
        assert!(!required.keeps(rate(1.0, 1), rate(0.95, 20)));
        assert!(!required.keeps(rate(1.0, 19), rate(0.5, 20)));
        // Both cut short: the shortcut's check ran at least as far.
        assert!(required.keeps(rate(1.0, 3), rate(1.0, 3)));
    }
}
