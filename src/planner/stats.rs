//! What a search's propagations did: how many there were, why they stopped early, and
//! whether they moved the goal object or the clutter. Diagnostics for the planner's user
//! and for benchmarks (`benches/stops.sh`), not part of the plan.

use crate::scene::Scene;
use crate::state::State;
use crate::validity::Invalid;
use std::collections::BTreeMap;

/// Counts over a search. OMPL propagates a control one step at a time and stops at the
/// first invalid step; a *propagation* is one such run of steps from a tree state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SearchStats {
    /// Propagations made.
    pub propagations: u64,
    /// Propagation steps taken.
    pub steps: u64,
    /// Propagations in which some step moved the goal object / any other object.
    pub moved_goal_object: u64,
    /// Propagations in which some step moved an object other than the goal object.
    pub moved_clutter: u64,
    /// Propagations stopped by an invalid step, by [`Invalid::kind`].
    pub stopped: BTreeMap<String, u64>,
    /// Of those stopped by self-collision, by the pair of links (names in order): a
    /// robot whose searches stop on one pair usually needs it in `allowed_collisions`.
    pub self_collisions: BTreeMap<(String, String), u64>,
}

/// Link pairs named in the report's self-collision share, at most.
const NAMED_PAIRS: usize = 3;

impl SearchStats {
    /// Adds another search's counts (parallel searches report their sum).
    pub fn add(&mut self, other: &SearchStats) {
        self.propagations += other.propagations;
        self.steps += other.steps;
        self.moved_goal_object += other.moved_goal_object;
        self.moved_clutter += other.moved_clutter;
        for (reason, n) in &other.stopped {
            *self.stopped.entry(reason.clone()).or_insert(0) += n;
        }
        for (pair, n) in &other.self_collisions {
            *self.self_collisions.entry(pair.clone()).or_insert(0) += n;
        }
    }

    /// One line: "N propagations of S steps on average, P % stopped early (reason P %,
    /// ...); the goal object moved in G %, other objects in C %" (reasons most frequent
    /// first, shares of all propagations; self-collision names its most frequent link
    /// pairs).
    pub fn report(&self) -> String {
        let share = |n: u64| 100.0 * n as f64 / self.propagations.max(1) as f64;
        let mut reasons: Vec<(&String, &u64)> = self.stopped.iter().collect();
        reasons.sort_by(|a, b| b.1.cmp(a.1).then(a.0.cmp(b.0)));
        let reasons: Vec<String> = reasons
            .iter()
            .map(|(reason, n)| match reason.as_str() {
                "self-collision" if !self.self_collisions.is_empty() => {
                    format!(
                        "{reason} {:.1} % [{}]",
                        share(**n),
                        self.named_pairs(&share)
                    )
                }
                _ => format!("{reason} {:.1} %", share(**n)),
            })
            .collect();
        format!(
            "{} propagations of {:.1} steps on average, {:.1} % stopped early{}; the goal object moved in {:.1} %, other objects in {:.1} %",
            self.propagations,
            self.steps as f64 / self.propagations.max(1) as f64,
            share(self.stopped.values().sum()),
            match reasons.is_empty() {
                true => String::new(),
                false => format!(" ({})", reasons.join(", ")),
            },
            share(self.moved_goal_object),
            share(self.moved_clutter)
        )
    }
}

impl SearchStats {
    /// The most frequent self-colliding link pairs with their shares: "'a' and 'b' 20.1 %;
    /// ...".
    fn named_pairs(&self, share: &dyn Fn(u64) -> f64) -> String {
        let mut pairs: Vec<(&(String, String), &u64)> = self.self_collisions.iter().collect();
        pairs.sort_by(|a, b| b.1.cmp(a.1).then(a.0.cmp(b.0)));
        let mut named: Vec<String> = pairs
            .iter()
            .take(NAMED_PAIRS)
            .map(|((a, b), n)| format!("'{a}' and '{b}' {:.1} %", share(**n)))
            .collect();
        if pairs.len() > NAMED_PAIRS {
            named.push(format!("{} more pairs", pairs.len() - NAMED_PAIRS));
        }
        named.join("; ")
    }
}

/// Counts a search's steps into [`SearchStats`], step by step as OMPL propagates.
#[derive(Clone, Debug)]
pub struct SearchCounter {
    stats: SearchStats,
    /// The object the goal names, if any.
    goal_object: Option<usize>,
    /// Whether the current propagation has already been counted as moving them.
    goal_move_counted: bool,
    clutter_move_counted: bool,
}

impl SearchCounter {
    /// A counter for searches of `scene` (its goal object).
    pub fn new(scene: &Scene) -> Self {
        let goal_object = scene.goal.object();
        Self {
            stats: SearchStats::default(),
            goal_object,
            goal_move_counted: false,
            clutter_move_counted: false,
        }
    }

    /// The counts so far.
    pub fn stats(&self) -> &SearchStats {
        &self.stats
    }

    /// Counts one step from `start` whose valid part ended at `end`, stopped by
    /// `stopped_by` if so; `continues` says it extends the previous step's propagation.
    pub fn record(
        &mut self,
        start: &State,
        end: &State,
        stopped_by: Option<&Invalid>,
        continues: bool,
    ) {
        let stats = &mut self.stats;
        stats.steps += 1;
        if !continues {
            stats.propagations += 1;
            self.goal_move_counted = false;
            self.clutter_move_counted = false;
        }
        let moved = |i: usize| start.objects[i] != end.objects[i];
        if !self.goal_move_counted && self.goal_object.is_some_and(moved) {
            self.goal_move_counted = true;
            stats.moved_goal_object += 1;
        }
        let objects = start.objects.len();
        if !self.clutter_move_counted
            && (0..objects).any(|i| Some(i) != self.goal_object && moved(i))
        {
            self.clutter_move_counted = true;
            stats.moved_clutter += 1;
        }
        if let Some(reason) = stopped_by {
            self.count_stop(reason.kind());
            if let Invalid::SelfCollision { link_a, link_b } = reason {
                let (a, b) = match link_a <= link_b {
                    true => (link_a, link_b),
                    false => (link_b, link_a),
                };
                // Found without building a key: no allocation once a pair has been seen
                // (a robot has few pairs).
                let pairs = &mut self.stats.self_collisions;
                match pairs.iter_mut().find(|((x, y), _)| x == a && y == b) {
                    Some((_, n)) => *n += 1,
                    None => {
                        pairs.insert((a.clone(), b.clone()), 1);
                    }
                }
            }
        }
    }

    /// Counts the last step as stopped in a perturbed world (robust planning), which
    /// the nominal state survived.
    pub fn record_perturbed_world_stop(&mut self, kind: &str) {
        self.count_stop(&format!("{kind} (in a perturbed world)"));
    }

    fn count_stop(&mut self, kind: &str) {
        // No allocation once a reason has been seen.
        match self.stats.stopped.get_mut(kind) {
            Some(n) => *n += 1,
            None => {
                self.stats.stopped.insert(kind.to_string(), 1);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stop(counter: &mut SearchCounter, state: &State, reason: Invalid) {
        counter.record(state, state, Some(&reason), false);
    }

    #[test]
    fn self_collision_stops_name_their_link_pairs_most_frequent_first() {
        let scene = Scene::load("scenes/herb_single_object.yaml").unwrap();
        let state = scene.start.clone();
        let mut counter = SearchCounter::new(&scene);
        let pair = |a: &str, b: &str| Invalid::SelfCollision {
            link_a: a.into(),
            link_b: b.into(),
        };
        for _ in 0..3 {
            stop(&mut counter, &state, pair("forearm", "upper_arm"));
        }
        // The same pair named the other way round is the same pair.
        stop(&mut counter, &state, pair("upper_arm", "forearm"));
        stop(&mut counter, &state, pair("hand", "shoulder"));
        for _ in 0..5 {
            counter.record(&state, &state, None, false);
        }
        let mut other = SearchCounter::new(&scene);
        stop(&mut other, &state, pair("hand", "shoulder"));
        let mut stats = counter.stats().clone();
        stats.add(other.stats());
        assert_eq!(
            stats.self_collisions[&("forearm".into(), "upper_arm".into())],
            4
        );
        assert_eq!(
            stats.self_collisions[&("hand".into(), "shoulder".into())],
            2
        );
        let report = stats.report();
        assert!(
            report.contains(
                "self-collision 54.5 % ['forearm' and 'upper_arm' 36.4 %; 'hand' and 'shoulder' 18.2 %]"
            ),
            "{report}"
        );
    }
}
