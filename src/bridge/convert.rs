//! The bridge's shared types from and to the model's own, and the delegations that
//! convert.

use super::ffi as bridge;
use super::Propagator;
use crate::planner::SearchStats;
use crate::planning::darrt::PrimitivePath;
use crate::planning::path::{PathControl, PathMetrics};
use crate::planning::{FinishSettings, FinishedPath, MeasuredRate, RobustRequirement};
use crate::planning::{PlannerKind, RunSettings};
use crate::scene::{Goal, Scene};

pub(super) fn planner_name(kind: PlannerKind) -> &'static str {
    kind.name()
}

pub(super) fn plan_robust_trials() -> u32 {
    crate::planning::PLAN_ROBUST_TRIALS
}

pub(super) fn repair_share() -> f64 {
    crate::planning::rest::REPAIR_SHARE
}

pub(super) fn executor_defaults() -> bridge::ExecutorSettings {
    use crate::planner::closed_loop::defaults;
    bridge::ExecutorSettings {
        planner: PlannerKind::PushKpiece,
        seed: 1,
        replan_time: defaults::REPLAN_TIME,
        replan_threads: 1,
        replan_shortcut: defaults::REPLAN_SHORTCUT,
        replan_polish: defaults::REPLAN_POLISH,
        replan_mend: defaults::REPLAN_MEND,
        max_replans: defaults::MAX_REPLANS,
        replan_budget: defaults::REPLAN_BUDGET,
        replan_leg: defaults::REPLAN_LEG,
        repair_ahead: defaults::REPAIR_AHEAD,
        speed: 1.0,
    }
}

pub(super) fn run_settings_of_scene(
    kind: PlannerKind,
    params: &super::PlannerParams,
) -> RunSettings {
    RunSettings::of_scene(kind, &params.0)
}

pub(super) fn planner_shares_one_search(kind: PlannerKind) -> bool {
    kind.shares_one_search()
}

pub(super) fn planner_cut_at_time_limit(kind: PlannerKind) -> bool {
    kind.cut_at_time_limit()
}

pub(super) fn planner_yields_controls(kind: PlannerKind) -> bool {
    kind.yields_controls()
}

pub(super) fn check_run_settings(settings: &RunSettings) -> Result<(), String> {
    settings.check(crate::limits::Front::CppOptions)
}

pub(super) fn planner_kind(name: &str) -> Result<PlannerKind, String> {
    name.parse()
}

pub(super) fn search_stats(propagator: &Propagator) -> bridge::SearchStats {
    bridge::SearchStats::from(propagator.search_stats())
}

pub(super) fn add_search_stats(
    a: &bridge::SearchStats,
    b: &bridge::SearchStats,
) -> bridge::SearchStats {
    let mut sum = SearchStats::from(a);
    sum.add(&SearchStats::from(b));
    bridge::SearchStats::from(&sum)
}

impl From<&SearchStats> for bridge::SearchStats {
    fn from(stats: &SearchStats) -> Self {
        bridge::SearchStats {
            propagations: stats.propagations,
            steps: stats.steps,
            moved_goal_object: stats.moved_goal_object,
            moved_clutter: stats.moved_clutter,
            stop_reasons: stats.stopped.keys().cloned().collect(),
            stop_counts: stats.stopped.values().copied().collect(),
            self_collision_links: stats
                .self_collisions
                .keys()
                .flat_map(|(a, b)| [a.clone(), b.clone()])
                .collect(),
            self_collision_counts: stats.self_collisions.values().copied().collect(),
        }
    }
}

impl From<&bridge::SearchStats> for SearchStats {
    fn from(stats: &bridge::SearchStats) -> Self {
        SearchStats {
            propagations: stats.propagations,
            steps: stats.steps,
            moved_goal_object: stats.moved_goal_object,
            moved_clutter: stats.moved_clutter,
            stopped: stats
                .stop_reasons
                .iter()
                .cloned()
                .zip(stats.stop_counts.iter().copied())
                .collect(),
            self_collisions: stats
                .self_collision_links
                .chunks_exact(2)
                .map(|pair| (pair[0].clone(), pair[1].clone()))
                .zip(stats.self_collision_counts.iter().copied())
                .collect(),
        }
    }
}

impl From<&Scene> for bridge::SceneInfo {
    fn from(scene: &Scene) -> Self {
        let chain = &scene.robot.chain;
        let limits = chain.limits();
        let (goal_object, center, radius, configuration) = match &scene.goal {
            Goal::ObjectInDisc {
                object,
                center,
                radius,
                margin,
            } => (
                *object as i64,
                [center.x, center.y],
                radius - margin,
                vec![],
            ),
            Goal::Configuration { q, tolerance } => {
                (-1, [0.0; 2], *tolerance, q.as_slice().to_vec())
            }
            Goal::Grasp { .. } => (-1, [0.0; 2], 0.0, vec![]),
        };
        let grasp_object = match &scene.goal {
            Goal::Grasp { object, .. } => *object as i64,
            _ => -1,
        };
        bridge::SceneInfo {
            name: scene.name.clone(),
            dof: scene.robot.dof(),
            objects: scene.objects.len(),
            joint_names: (0..chain.dof())
                .map(|i| chain.dof_joint(i).name.clone())
                .collect(),
            joint_lower: limits.iter().map(|l| l.0).collect(),
            joint_upper: limits.iter().map(|l| l.1).collect(),
            object_names: scene.objects.iter().map(|o| o.name.clone()).collect(),
            link_names: chain.links.iter().map(|l| l.name.clone()).collect(),
            table: [
                scene.table.x.0,
                scene.table.x.1,
                scene.table.y.0,
                scene.table.y.1,
            ],
            planner: super::PlannerParams(scene.planner),
            goal_object,
            goal_center: center,
            goal_radius: radius,
            goal_configuration: configuration,
            grasp_object,
            start: scene.start.to_flat(),
        }
    }
}

impl TryFrom<&bridge::FinishSettings> for FinishSettings {
    type Error = String;

    fn try_from(s: &bridge::FinishSettings) -> Result<Self, String> {
        if !(0.0..=1.0).contains(&s.robust_rate) {
            return Err(format!(
                "the robust rate must be in [0, 1], got {}",
                s.robust_rate
            ));
        }
        if s.found_rate > 1.0 || (s.found_rate >= 0.0 && s.found_trials == 0) {
            return Err(format!(
                "the found path's rate must be at most 1 and over at least one trial, got {} over {}",
                s.found_rate, s.found_trials
            ));
        }
        Ok(FinishSettings {
            shortcut: s.shortcut,
            seed: s.seed,
            robust: (s.robust_trials > 0).then_some(RobustRequirement {
                trials: s.robust_trials,
                rate: s.robust_rate,
            }),
            only_toward_robustness: s.only_toward_robustness,
            unseen_trials: s.unseen_trials,
            found_rate: (s.found_rate >= 0.0).then_some(MeasuredRate {
                rate: s.found_rate,
                trials: s.found_trials,
            }),
            deadline: crate::planning::deadline(std::time::Instant::now(), s.time_left),
            progress: None,
            threads: s.threads,
        })
    }
}

impl From<FinishedPath> for bridge::FinishedPath {
    fn from(path: FinishedPath) -> Self {
        let (controls, steps) = PathControl::to_flat(&path.controls);
        let sim = &path.simulation;
        let contacts = sim
            .contacts
            .iter()
            .enumerate()
            .flat_map(|(control, steps)| {
                steps.iter().enumerate().flat_map(move |(step, pushes)| {
                    pushes.iter().map(move |p| bridge::Contact {
                        control,
                        step,
                        link: p.link,
                        object: p.object,
                        force: p.force,
                    })
                })
            });
        bridge::FinishedPath {
            controls,
            steps,
            states: sim.states.iter().flat_map(|s| s.to_flat()).collect(),
            contacts: contacts.collect(),
            before: path.before,
            after: sim.metrics,
            shortcut_attempts: path.shortcut.attempts,
            shortcut_accepted: path.shortcut.accepted,
            shortcut_dropped_as_less_robust: path.shortcut.dropped_as_less_robust,
            robustness: path.robustness.map_or(-1.0, |r| r.rate),
            robustness_trials: path.robustness.map_or(0, |r| r.trials),
            unseen_rate: path.unseen.map_or(-1.0, |r| r.rate),
            unseen_trials: path.unseen.map_or(0, |r| r.trials),
        }
    }
}

impl From<crate::planning::trajectory::Trajectory> for bridge::Trajectory {
    fn from(t: crate::planning::trajectory::Trajectory) -> Self {
        bridge::Trajectory {
            rate: t.rate,
            times: t.times,
            q: t.q.into_iter().flatten().collect(),
            objects: t.objects.into_iter().flatten().flatten().collect(),
        }
    }
}

impl From<Result<PrimitivePath, String>> for bridge::PrimitiveCheck {
    fn from(checked: Result<PrimitivePath, String>) -> Self {
        match checked {
            Ok(path) => bridge::PrimitiveCheck {
                valid: true,
                goal_reached: path.goal_reached,
                message: String::new(),
                metrics: path.metrics,
                durations: path.durations,
                pick_places: path.pick_places,
            },
            Err(message) => bridge::PrimitiveCheck {
                valid: false,
                goal_reached: false,
                message,
                metrics: PathMetrics::default(),
                durations: vec![],
                pick_places: 0,
            },
        }
    }
}
