//! The searches of a closed loop after an observation whose rest no longer reaches the
//! goal: a repair of the rest, a new plan from the observed state, and legs along the goal
//! object's track ([`ClosedLoop::search`]).

use super::{ClosedLoop, SearchFound};
use crate::planning::path::{PathControl, SimulatedPath};
use crate::planning::rest::REPAIR_SHARE;
use crate::planning::{FinishSettings, Problem, RunSettings};
use crate::scene::{Goal, Scene};
use crate::state::State;
use nalgebra::Vector2;
use std::path::Path;
use std::time::Instant;

/// What the searches after one observation brought ([`ClosedLoop::search`]).
pub(super) enum Searched {
    /// A plan to the goal: the rest repaired (an ending added), or searched anew.
    Plan {
        controls: Vec<PathControl>,
        repair: bool,
    },
    /// A leg to `goal`, searched after a search to the goal that failed (why), or first,
    /// far from the goal disc (None).
    Leg {
        controls: Vec<PathControl>,
        goal: Goal,
        failure: Option<String>,
    },
    /// Nothing: why the search to the goal found nothing.
    Nothing(String),
}

impl Searched {
    /// Its kind, on the record: `goal` is the execution's.
    pub(super) fn found(&self, goal: &Goal) -> SearchFound {
        match self {
            Searched::Plan { repair: true, .. } => SearchFound::Repair,
            Searched::Plan { .. } => SearchFound::Replan,
            Searched::Leg { failure: None, .. } => SearchFound::LegFirst,
            Searched::Leg { goal: leg, .. } if onto_the_disc(goal, leg) => {
                SearchFound::LegOntoTheDisc
            }
            Searched::Leg { .. } => SearchFound::Leg,
            Searched::Nothing(_) => SearchFound::Nothing,
        }
    }
}

impl ClosedLoop {
    /// The searches after an observation whose rest of the plan does not reach the goal
    /// (`from`'s start): a repair of the rest `kept` up to where it stops being valid
    /// (`kept.1`, its end), then, far from the goal disc, a leg along `track`, then a new
    /// plan to the goal, then (if no leg was searched) a leg. The repair gets
    /// [`REPAIR_SHARE`] of `time`, each search after it the whole `time`, no more than
    /// what is left of `budget_left` (counted from the call): a leg and a search to the
    /// goal may take twice `time` together. The `index`-th search of the execution.
    pub(super) fn search(
        &self,
        from: &Scene,
        kept: (&[PathControl], &State),
        track: &Track,
        (time, budget_left): (f64, f64),
        index: usize,
    ) -> Searched {
        let began = Instant::now();
        let time_left = || time.min(budget_left - began.elapsed().as_secs_f64());
        // The rest is kept as far as it is valid (to its end if it ends short) and
        // an ending is searched from there (a warm start: the search begins where
        // the rest stops, most often close to the goal, and finds a short ending
        // fast); failing that, a new plan from the observed state.
        if !kept.0.is_empty() {
            if let Ok(controls) = self.repair(from, kept.0, kept.1, time, index) {
                return Searched::Plan {
                    controls,
                    repair: true,
                };
            }
        }
        // Far from the goal disc (a leg's aim off it) a leg is searched first and the
        // goal only where none is found: from there a search to the goal rarely finds
        // one in its seconds, and a leg takes a fraction of that (dense 16 and 19,
        // BENCHMARKS.md "Dense scenes, closed loop").
        let leg_goal = self.leg_goal(from, track);
        let far = leg_first(&from.goal, leg_goal.as_ref());
        if let (true, Some(goal)) = (far, &leg_goal) {
            if let Some(controls) = self.leg(from, goal, time_left(), index) {
                return Searched::Leg {
                    controls,
                    goal: goal.clone(),
                    failure: None,
                };
            }
        }
        let failure = match time_left() {
            left if left > 0.0 => {
                let problem = Problem::new(from.clone(), self.settings.planner);
                match self.replan(&problem, left, index) {
                    Ok(controls) => {
                        return Searched::Plan {
                            controls,
                            repair: false,
                        }
                    }
                    Err(failure) => failure,
                }
            }
            _ => "the search budget is spent".into(),
        };
        // None found: a leg along the track, with the time left (not twice).
        let leg = leg_goal.filter(|_| !far).and_then(|goal| {
            let controls = self.leg(from, &goal, time_left(), index)?;
            Some((controls, goal))
        });
        match leg {
            Some((controls, goal)) => Searched::Leg {
                controls,
                goal,
                failure: Some(failure),
            },
            None => Searched::Nothing(failure),
        }
    }

    /// `rest` (valid from `from`'s start, ending in `end`: short of the goal, or where the
    /// rest after it stops being valid) with an ending searched from `end`, with
    /// [`REPAIR_SHARE`] of `time` ([`ClosedLoop::replan`]).
    fn repair(
        &self,
        from: &Scene,
        rest: &[PathControl],
        end: &State,
        time: f64,
        index: usize,
    ) -> Result<Vec<PathControl>, String> {
        let ending = self.ending(from, end, time, index)?;
        Ok([rest, &ending].concat())
    }

    /// A repair's ending: a plan from `end` (a state the model predicts from `from`'s
    /// start) to `from`'s goal, searched with [`REPAIR_SHARE`] of `time`.
    pub(super) fn ending(
        &self,
        from: &Scene,
        end: &State,
        time: f64,
        index: usize,
    ) -> Result<Vec<PathControl>, String> {
        let at_end = from
            .with_start(end, Path::new("the rest's end"))
            .map_err(|e| e.to_string())?;
        self.replan(
            &Problem::new(at_end, self.settings.planner),
            REPAIR_SHARE * time,
            index,
        )
    }

    /// The goal of a leg from `from`'s start (the observed state): the goal object to
    /// within half [`ClosedLoopSettings::leg`] of the point that far ahead on `track`.
    /// None for legs turned off, goals other than an object's disc, or a track that ends
    /// nearer than a leg (the goal itself is the next aim).
    pub(super) fn leg_goal(&self, from: &Scene, track: &Track) -> Option<Goal> {
        let ahead = self.settings.leg;
        let Goal::ObjectInDisc { object, .. } = from.goal else {
            return None;
        };
        if ahead <= 0.0 {
            return None;
        }
        let center = track.waypoint(&from.start.objects[object].translation(), ahead)?;
        Some(Goal::ObjectInDisc {
            object,
            center,
            radius: 0.5 * ahead,
            margin: 0.0,
        })
    }

    /// A leg to `goal` from `from`'s start, searched for `time` seconds at most
    /// ([`ClosedLoop::replan`]); none found in the time: None.
    fn leg(&self, from: &Scene, goal: &Goal, time: f64, index: usize) -> Option<Vec<PathControl>> {
        if time <= 0.0 {
            return None;
        }
        let mut toward = from.clone();
        toward.goal = goal.clone();
        self.replan(&Problem::new(toward, self.settings.planner), time, index)
            .ok()
    }

    /// A new plan from `problem`'s start (the observed state): searched for `time` seconds
    /// at most, then finished (checked by re-simulation, shortcut). The `index`-th re-plan
    /// of the execution.
    fn replan(
        &self,
        problem: &Problem,
        time: f64,
        index: usize,
    ) -> Result<Vec<PathControl>, String> {
        let settings = &self.settings;
        let from = problem.scene();
        let run = RunSettings {
            time_limit: time,
            threads: settings.replan_threads,
            seed: settings.seed.wrapping_add(index as u64),
            shortcut: 0.0,
            ..RunSettings::of_scene(settings.planner, &from.planner)
        };
        let found = self
            .search
            .solve(from, &run, None)
            .map_err(|e| format!("re-planning failed: {e}"))?;
        if !found.summary.exact {
            return Err(format!(
                "no plan from the observed state within {time:.1} s"
            ));
        }
        let finish = FinishSettings {
            shortcut: settings.replan_shortcut,
            seed: run.seed,
            robust: None,
            only_toward_robustness: false,
            unseen_trials: 0,
            found_rate: None,
            deadline: None,
            progress: None,
            threads: 1,
        };
        Ok(problem
            .finish(&found.controls, &found.states, true, &finish)?
            .controls)
    }
}

/// The goal object's positions (m, world frame) at the states of a path that reaches an
/// object goal in the model: the way a leg follows when no search finds the goal.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Track(Vec<Vector2<f64>>);

impl Track {
    /// The goal object's track along `path`; empty for a goal that is not an object's.
    pub(super) fn of(goal: &Goal, path: &SimulatedPath) -> Track {
        match goal.object() {
            Some(object) => Track(
                path.states
                    .iter()
                    .map(|s| s.objects[object].translation())
                    .collect(),
            ),
            None => Track::default(),
        }
    }

    /// Where a leg from `at` aims: past the track's point nearest `at` (the latest of
    /// equals, as an object held still between pushes leaves many), the first point
    /// `ahead` or farther from `at`. None where the track ends nearer.
    fn waypoint(&self, at: &Vector2<f64>, ahead: f64) -> Option<Vector2<f64>> {
        let distance = |p: &Vector2<f64>| (p - at).norm();
        let nearest = (0..self.0.len()).fold(None, |best: Option<usize>, i| match best {
            Some(b) if distance(&self.0[b]) < distance(&self.0[i]) => Some(b),
            _ => Some(i),
        })?;
        self.0[nearest..]
            .iter()
            .find(|p| distance(p) >= ahead)
            .copied()
    }
}

/// Is `leg` (a leg's goal, if there is one) searched before `goal`: far from the goal
/// disc, where the leg's aim lies off it.
pub(super) fn leg_first(goal: &Goal, leg: Option<&Goal>) -> bool {
    leg.is_some_and(|leg| !onto_the_disc(goal, leg))
}

/// Does `leg` aim at a point on `goal`'s disc (both an object's disc)?
pub(super) fn onto_the_disc(goal: &Goal, leg: &Goal) -> bool {
    match (goal, leg) {
        (Goal::ObjectInDisc { center, radius, .. }, Goal::ObjectInDisc { center: aim, .. }) => {
            (aim - center).norm() < *radius
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::{onto_the_disc, Track};
    use crate::scene::Goal;
    use nalgebra::{DVector, Vector2};

    fn track(points: &[[f64; 2]]) -> Track {
        Track(points.iter().map(|&[x, y]| Vector2::new(x, y)).collect())
    }

    /// A leg aims past the track's point nearest the object, at the first point a leg's
    /// length from it: along an L-shaped track, round the corner when the object stands
    /// near it, and nowhere when the track ends nearer.
    #[test]
    fn a_leg_aims_a_legs_length_ahead_of_the_nearest_point_of_the_track() {
        let l = track(&[
            [0.0, 0.0],
            [0.05, 0.0],
            [0.1, 0.0],
            [0.15, 0.0],
            [0.2, 0.0],
            [0.2, 0.05],
            [0.2, 0.1],
            [0.2, 0.15],
        ]);
        let at = |x, y| Vector2::new(x, y);
        // (0.1, 0) is 0.092 from (0.01, 0.02), (0.15, 0) 0.141.
        assert_eq!(l.waypoint(&at(0.01, 0.02), 0.1), Some(at(0.15, 0.0)));
        // Off the track's side: the nearest point is (0.15, 0); 0.1 from (0.16, 0.03) is
        // first passed round the corner, at (0.2, 0.15) ((0.2, 0.1) is 0.081 away).
        assert_eq!(l.waypoint(&at(0.16, 0.03), 0.1), Some(at(0.2, 0.15)));
        assert_eq!(l.waypoint(&at(0.2, 0.08), 0.1), None);
        // Standing far off the track, the leg goes back to its nearest point.
        assert_eq!(l.waypoint(&at(0.1, -0.3), 0.1), Some(at(0.1, 0.0)));
        assert_eq!(track(&[]).waypoint(&at(0.0, 0.0), 0.1), None);
    }

    /// An object held still while the hand goes round it leaves the same point many
    /// times: the leg counts from the last of them, not from an earlier visit.
    #[test]
    fn a_leg_counts_from_the_last_visit_of_the_nearest_point() {
        let back = track(&[[0.0, 0.0], [0.1, 0.0], [0.0, 0.0], [0.0, 0.1], [0.0, 0.2]]);
        let at = Vector2::new(0.0, 0.0);
        // From the first visit the leg would aim back at (0.1, 0).
        assert_eq!(back.waypoint(&at, 0.1), Some(Vector2::new(0.0, 0.1)));
    }

    /// A leg onto the goal disc is one whose aim lies on the disc (its margin aside); any
    /// other goal has no disc to aim onto.
    #[test]
    fn a_leg_is_onto_the_disc_when_its_aim_lies_on_it() {
        let disc = |x: f64, y: f64, radius: f64| Goal::ObjectInDisc {
            object: 0,
            center: Vector2::new(x, y),
            radius,
            margin: 0.03,
        };
        let goal = disc(0.85, -0.3, 0.1);
        // 0.09 from the centre: on the disc, though not inside its margin.
        assert!(onto_the_disc(&goal, &disc(0.85, -0.39, 0.05)));
        // 0.11 from the centre: off it, though the leg's own disc overlaps it.
        assert!(!onto_the_disc(&goal, &disc(0.85, -0.41, 0.05)));
        let configuration = Goal::Configuration {
            q: DVector::zeros(7),
            tolerance: 0.1,
        };
        assert!(!onto_the_disc(&configuration, &disc(0.85, -0.3, 0.05)));
    }
}
