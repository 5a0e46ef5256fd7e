//! Open-loop execution of a plan in an independent 3D rigid-body engine (rapier): the
//! arm follows the plan's joint trajectory exactly, the objects are free 3D bodies that
//! can slide, turn and tip. This checks the planar quasistatic model from outside: the
//! engine knows nothing of limit surfaces, complementarity or tipping rules.
//!
//! Each trial perturbs the scene as [`Noise::world`] says, plays the
//! trajectory at `speed` times its planned pace, lets the objects settle, and compares
//! with the plan's predicted object poses.

pub mod engine;
mod fresh_contacts;
pub mod mujoco;
pub mod rapier;

use crate::math::Pose2;
use crate::planning::plan_file::PlanFile;
use crate::planning::robustness::Noise;
use crate::planning::trajectory::Playback;
use crate::random::SplitMix64;
use crate::scene::Scene;
pub use engine::{Engine, EngineKind, STEP};
use nalgebra::DVector;
use rapier::SolverSettings;
use serde::Serialize;

/// How to execute.
#[derive(Clone, Debug, PartialEq)]
pub struct ExecuteSettings {
    /// Trials; the first is unperturbed (the nominal run), the others perturbed.
    pub trials: usize,
    /// Execution pace relative to the plan's trajectory (0.25: four times slower).
    pub speed: f64,
    /// Seed of the perturbations.
    pub seed: u64,
    /// The perturbations of the trials after the first (nominal) one.
    pub noise: Noise,
    /// Keep each trial's object poses at the trajectory's rate (for pictures).
    pub record: bool,
    /// The engine the trials run in.
    pub engine: EngineKind,
    /// rapier's solver effort.
    pub solver: SolverSettings,
}

impl Default for ExecuteSettings {
    fn default() -> Self {
        ExecuteSettings {
            trials: 10,
            speed: 1.0,
            seed: 1,
            noise: Noise::world(),
            record: false,
            engine: EngineKind::Rapier,
            solver: SolverSettings::default(),
        }
    }
}

/// Tilt beyond which an object counts as tipped (rad; about 8.6 degrees).
pub const TIPPED_TILT: f64 = 0.15;
/// Distance from the predicted position that counts as drift (m).
pub const DRIFT: f64 = 0.02;
/// How far below the table top an object's base must end to have fallen off it (m).
pub const FALLEN_DROP: f64 = 0.05;

/// Time the objects get to come to rest after the trajectory ends (s).
pub const SETTLE: f64 = 1.0;

/// The first way a trial parted from the plan.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Divergence {
    /// An object tilted beyond [`TIPPED_TILT`].
    Tipped {
        /// The object.
        object: String,
        /// When (s into the trajectory).
        time: f64,
    },
    /// Two objects touched (the planar model keeps them apart).
    ObjectContact {
        /// One object.
        object_a: String,
        /// The other.
        object_b: String,
        /// When (s into the trajectory).
        time: f64,
    },
    /// An object's centre left its predicted position by more than [`DRIFT`].
    Drift {
        /// The object.
        object: String,
        /// When (s into the trajectory).
        time: f64,
        /// How far off its predicted position (m).
        error: f64,
    },
}

/// One execution.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ExecutionTrial {
    /// The goal object ended upright (it may have rocked on the way) with its centre
    /// inside the goal disc.
    pub reached: bool,
    /// Distance of the goal object's final centre from the disc's edge (m; negative inside).
    pub goal_distance: f64,
    /// Objects that tilted beyond [`TIPPED_TILT`] at some time (tipped over, or rocked
    /// on an edge and fell back) and ended on the table.
    pub tipped: Vec<String>,
    /// Objects pushed off the table: their base ended more than [`FALLEN_DROP`] below
    /// its top (their tilt on the way down is the fall, not counted in `tipped`).
    pub fell_off: Vec<String>,
    /// Two objects touched at some time.
    pub objects_touched: bool,
    /// Each object's final position error against the plan's prediction (m), scene order.
    pub final_errors: Vec<f64>,
    /// Each object's final planar pose `[x, y, yaw]` (m, m, rad; world frame), scene order.
    pub final_poses: Vec<[f64; 3]>,
    /// Each object's final tilt from upright (rad), scene order.
    pub final_tilts: Vec<f64>,
    /// The first way the trial parted from the plan, if it did.
    pub first_divergence: Option<Divergence>,
    /// Object poses `[x, y, yaw]` at the trajectory's sample times (when recorded).
    #[serde(skip)]
    pub frames: Vec<Vec<[f64; 3]>>,
}

/// What the trials found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ExecutionReport {
    /// The engine the trials ran in.
    pub engine: EngineKind,
    /// The objects' names, in scene order: the order of every per-object list.
    pub objects: Vec<String>,
    /// The goal object's name.
    pub goal_object: Option<String>,
    /// Every trial, the nominal one first.
    pub trials: Vec<ExecutionTrial>,
    /// Execution pace relative to the plan's trajectory.
    pub speed: f64,
    /// Fraction of trials that reached the goal.
    pub success_rate: f64,
    /// Trials in which some object tipped.
    pub tipped_trials: usize,
    /// Trials in which some object was pushed off the table.
    pub fell_off_trials: usize,
    /// Trials in which two objects touched.
    pub object_contact_trials: usize,
}

/// Executes `plan` in its scene (`scene`: the full scene, every object movable).
pub fn execute(
    scene: &Scene,
    plan: &PlanFile,
    settings: &ExecuteSettings,
) -> Result<ExecutionReport, String> {
    let predicted = predicted_poses(scene, plan)?;
    let mut trials = Vec::with_capacity(settings.trials);
    for world in trial_worlds(scene, settings) {
        trials.push(run(&world?, scene, plan, &predicted, settings)?);
    }
    let n = trials.len().max(1) as f64;
    Ok(ExecutionReport {
        success_rate: trials.iter().filter(|t| t.reached).count() as f64 / n,
        tipped_trials: trials.iter().filter(|t| !t.tipped.is_empty()).count(),
        fell_off_trials: trials.iter().filter(|t| !t.fell_off.is_empty()).count(),
        object_contact_trials: trials.iter().filter(|t| t.objects_touched).count(),
        speed: settings.speed,
        engine: settings.engine,
        objects: scene.objects.iter().map(|o| o.name.clone()).collect(),
        goal_object: scene.goal.object().map(|i| scene.objects[i].name.clone()),
        trials,
    })
}

/// The worlds of `settings.trials` trials in `scene`: the scene as it is first, then
/// scenes perturbed by `settings.noise`, drawn from `settings.seed`.
pub fn trial_worlds<'a>(
    scene: &'a Scene,
    settings: &'a ExecuteSettings,
) -> impl Iterator<Item = Result<Scene, String>> + 'a {
    let mut rng = SplitMix64::new(settings.seed);
    (0..settings.trials).map(move |trial| match trial {
        0 => Ok(scene.clone()),
        _ => settings
            .noise
            .perturb(scene, &mut rng)
            .map_err(|e| format!("no valid perturbed start: {e}")),
    })
}

/// One open-loop execution of `plan` in a world built from `world_scene` (the same scene,
/// its objects and parameters changed), judged against `scene`'s goal and the plan.
pub fn execute_in_world(
    world_scene: &Scene,
    scene: &Scene,
    plan: &PlanFile,
    settings: &ExecuteSettings,
) -> Result<ExecutionTrial, String> {
    let predicted = predicted_poses(scene, plan)?;
    run(world_scene, scene, plan, &predicted, settings)
}

/// The plan's predicted object poses at each trajectory sample, in `scene`'s object
/// order (objects the plan does not move, such as Static RRT's clutter, stay at their
/// start).
pub fn predicted_poses(scene: &Scene, plan: &PlanFile) -> Result<Vec<Vec<Pose2>>, String> {
    let trajectory = &plan.trajectory;
    if trajectory.q.is_empty() || trajectory.q.len() != trajectory.objects.len() {
        return Err("the plan has no executable trajectory".into());
    }
    let dof = scene.robot.dof();
    if let Some(bad) = trajectory.q.iter().position(|q| q.len() != dof) {
        return Err(format!(
            "trajectory.q[{bad}] has {} values, the robot {dof} joints",
            trajectory.q[bad].len()
        ));
    }
    let index: Vec<Option<usize>> = scene
        .objects
        .iter()
        .map(|o| plan.objects.iter().position(|n| *n == o.name))
        .collect();
    Ok(trajectory
        .objects
        .iter()
        .map(|sample| {
            index
                .iter()
                .zip(&scene.start.objects)
                .map(|(k, start)| match k.and_then(|k| sample.get(k)) {
                    Some(p) => Pose2::new(p[0], p[1], p[2]),
                    None => *start,
                })
                .collect()
        })
        .collect())
}

/// One trial in `world_scene` (perturbed), judged against `scene`'s goal and the plan.
fn run(
    world_scene: &Scene,
    scene: &Scene,
    plan: &PlanFile,
    predicted: &[Vec<Pose2>],
    settings: &ExecuteSettings,
) -> Result<ExecutionTrial, String> {
    let robot = &world_scene.robot;
    let trajectory = &plan.trajectory;
    let mut playback = Playback::new(trajectory);
    let mut poses = Vec::new();
    robot
        .chain
        .forward_kinematics(&playback.at(0.0), &mut poses);
    let mut world = settings.engine.world(
        world_scene,
        &world_scene.start.objects,
        &poses,
        &settings.solver,
    )?;
    let objects = scene.objects.len();
    let names = |i: usize| scene.objects[i].name.clone();

    let samples = trajectory.times.len();
    let plan_end = *trajectory.times.last().expect("non-empty trajectory");
    let end = plan_end / settings.speed;
    let total_steps = ((end + SETTLE) / STEP).ceil() as usize;
    let mut tipped = vec![false; objects];
    let mut objects_touched = false;
    let mut first_divergence = None;
    let mut frames = Vec::new();
    let mut next_sample = 0;
    for n in 1..=total_steps {
        let t = n as f64 * STEP;
        // Plan time of the arm at the end of this step: the trajectory, linearly
        // interpolated, then held at its end.
        let tau = (t * settings.speed).min(plan_end);
        let q = playback.at(tau);
        robot.chain.forward_kinematics(&q, &mut poses);
        world.move_arm(&poses);
        world.step();

        for (i, flag) in tipped.iter_mut().enumerate() {
            if !*flag && world.object_tilt(i) > TIPPED_TILT {
                *flag = true;
                first_divergence.get_or_insert(Divergence::Tipped {
                    object: names(i),
                    time: t,
                });
            }
        }
        if let Some((a, b)) = world.touching_objects() {
            objects_touched = true;
            first_divergence.get_or_insert(Divergence::ObjectContact {
                object_a: names(a),
                object_b: names(b),
                time: t,
            });
        }
        // At the trajectory's sample times: drift against the prediction.
        while next_sample < samples
            && trajectory.times[next_sample] <= tau + 1e-12
            && t <= end + STEP
        {
            let expected = &predicted[next_sample];
            if settings.record {
                frames.push(
                    (0..objects)
                        .map(|i| {
                            let p = world.object_pose2(i);
                            [p.x, p.y, p.theta]
                        })
                        .collect(),
                );
            }
            if first_divergence.is_none() {
                for (i, e) in expected.iter().enumerate() {
                    let error = (world.object_pose2(i).translation() - e.translation()).norm();
                    if error > DRIFT {
                        first_divergence = Some(Divergence::Drift {
                            object: names(i),
                            time: t,
                            error,
                        });
                        break;
                    }
                }
            }
            next_sample += 1;
        }
    }

    let last = predicted.last().expect("non-empty trajectory");
    let final_poses: Vec<Pose2> = (0..objects).map(|i| world.object_pose2(i)).collect();
    let final_errors = final_poses
        .iter()
        .zip(last)
        .map(|(a, b)| (a.translation() - b.translation()).norm())
        .collect();
    let mut end_state = scene.start.clone();
    end_state.q = DVector::from_column_slice(&trajectory.q[samples - 1]);
    end_state.objects.clone_from(&final_poses);
    let goal_distance = scene.goal.task_distance(&end_state);
    let upright = scene
        .goal
        .object()
        .is_none_or(|object| world.object_tilt(object) < TIPPED_TILT);
    let fell_off: Vec<bool> = (0..objects).map(|i| world.object_fell_off(i)).collect();
    Ok(ExecutionTrial {
        reached: goal_distance <= 0.0 && upright,
        goal_distance,
        tipped: (0..objects)
            .filter(|&i| tipped[i] && !fell_off[i])
            .map(names)
            .collect(),
        fell_off: (0..objects).filter(|&i| fell_off[i]).map(names).collect(),
        objects_touched,
        final_errors,
        final_poses: final_poses.iter().map(|p| [p.x, p.y, p.theta]).collect(),
        final_tilts: (0..objects).map(|i| world.object_tilt(i)).collect(),
        first_divergence,
        frames,
    })
}
