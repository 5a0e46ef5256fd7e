//! Pictures of a plan (Fig. 2 of the whole-arm paper): top-down snapshots, a contact
//! timeline, and a self-contained HTML animation (a 3D view and a top view).
//!
//! The renderer re-simulates the plan from its file, recording every step, so it draws
//! exactly what the model predicts. Times are plan time: step index x the propagation step;
//! under the semi-dynamic model, the plan at its pace with the objects coasting to rest
//! after every step, in frames one propagation step apart.

mod html;
pub mod outline;
mod svg;
mod webgl;

use crate::planning::plan_file::PlanFile;
use crate::planning::trajectory::paced;
use crate::planning::Problem;
use crate::scene::file::PhysicsModel;
use crate::scene::{Goal, Scene};
use crate::state::State;
use nalgebra::Vector2;
use outline::{footprint_outline, shape_outline};
use std::path::{Path, PathBuf};

/// A plan, simulated step by step, ready to draw.
pub struct Film {
    /// The scene.
    pub scene: Scene,
    /// Every step's state, from the start.
    pub states: Vec<State>,
    /// Per step (from state k to k+1), the (link, object) pairs pushing.
    pub contacts: Vec<Vec<(usize, usize)>>,
    /// Step indices where each control starts, and the last step.
    pub control_starts: Vec<usize>,
    /// The propagation step (s).
    pub dt: f64,
    /// Object poses an execution reached at each state (empty: none drawn).
    pub executed: Vec<Vec<crate::math::Pose2>>,
}

/// One drawn moment.
pub struct Frame {
    /// Seconds from the start.
    pub time: f64,
    /// Outline and "in contact" flag of each solid link.
    pub links: Vec<(Vec<Vector2<f64>>, bool)>,
    /// Outline of each object.
    pub objects: Vec<Vec<Vector2<f64>>>,
    /// Outline of each object where the execution had it (empty when none).
    pub executed: Vec<Vec<Vector2<f64>>>,
}

impl Film {
    /// Simulates the plan in the file (its scene resolved as `check` does).
    pub fn of(plan: &PlanFile, plan_path: &Path) -> Result<Film, String> {
        let mut film = Film::of_controls(plan, plan_path)?;
        film.append_reach(plan);
        Ok(film)
    }

    /// A reach of a grasp after the controls, one frame per Transit check (objects still).
    fn append_reach(&mut self, plan: &PlanFile) {
        let Some(end) = self.states.last().cloned() else {
            return;
        };
        let waypoints = plan.reach_waypoints();
        if waypoints.is_empty() {
            return;
        }
        let states = crate::planning::reach::reach_states(&end, &waypoints);
        self.contacts
            .extend(std::iter::repeat_n(Vec::new(), states.len() - 1));
        self.states.extend(states.into_iter().skip(1));
        self.control_starts.push(self.states.len() - 1);
    }

    /// The plan's controls simulated.
    fn of_controls(plan: &PlanFile, plan_path: &Path) -> Result<Film, String> {
        let scene = plan.load_scene(plan_path)?;
        let path = Problem::new(scene.clone(), plan.settings.planner)
            .simulate(&plan.path_controls(), true);
        if let Some((i, reason)) = path.stopped_by {
            return Err(format!(
                "{}: the plan does not simulate: control {i}: {reason}",
                plan_path.display()
            ));
        }
        // The file's trajectory is not drawn, but a picture of a plan whose trajectory is
        // not its controls' would show a plan that is not the file (as execute refuses it).
        plan.check_trajectory(&scene)
            .map_err(|e| format!("{}: {e}", plan_path.display()))?;
        let mut control_starts = vec![0];
        for c in &plan.controls {
            control_starts.push(control_starts.last().unwrap() + c.steps);
        }
        let dt = scene.planner.step;
        let contacts: Vec<Vec<(usize, usize)>> = path
            .contacts
            .iter()
            .flatten()
            .map(|s| s.iter().map(|p| (p.link, p.object)).collect())
            .collect();
        if scene.physics.model == PhysicsModel::SemiDynamic {
            // Objects coast after each step: frames every `dt` of the plan at its pace.
            let paced = paced(&scene, &path.step_states, 1.0 / dt)?;
            return Ok(Film {
                dt,
                contacts: paced.steps[1..]
                    .iter()
                    .map(|&s| contacts.get(s).cloned().unwrap_or_default())
                    .collect(),
                control_starts: control_starts
                    .iter()
                    .map(|&s| (paced.step_starts[s] / dt).round() as usize)
                    .map(|k| k.min(paced.states.len() - 1))
                    .collect(),
                states: paced.states,
                scene,
                executed: Vec::new(),
            });
        }
        Ok(Film {
            dt,
            contacts,
            states: path.step_states,
            control_starts,
            scene,
            executed: Vec::new(),
        })
    }

    /// The plan's executable trajectory (frames at its sample times; no contact
    /// highlights), with the object poses of one execution (`executed`, per sample, scene
    /// order) drawn over the predicted ones.
    pub fn of_execution(
        plan: &PlanFile,
        plan_path: &Path,
        executed: &[Vec<[f64; 3]>],
    ) -> Result<Film, String> {
        let scene = plan.load_scene(plan_path)?;
        let predicted = crate::planning::execute::predicted_poses(&scene, plan)?;
        let trajectory = &plan.trajectory;
        if executed.len() != predicted.len() {
            return Err(format!(
                "{} executed frames for {} trajectory samples",
                executed.len(),
                predicted.len()
            ));
        }
        let states: Vec<State> = trajectory
            .q
            .iter()
            .zip(predicted)
            .map(|(q, objects)| State {
                q: nalgebra::DVector::from_column_slice(q),
                objects,
            })
            .collect();
        let n = states.len();
        Ok(Film {
            dt: 1.0 / trajectory.rate,
            contacts: vec![Vec::new(); n.saturating_sub(1)],
            control_starts: vec![0, n - 1],
            executed: executed
                .iter()
                .map(|f| {
                    f.iter()
                        .map(|p| crate::math::Pose2::new(p[0], p[1], p[2]))
                        .collect()
                })
                .collect(),
            states,
            scene,
        })
    }

    /// The plan's duration (s).
    pub fn duration(&self) -> f64 {
        (self.states.len() - 1) as f64 * self.dt
    }

    /// The step nearest to time `t` (s).
    pub fn step_at(&self, t: f64) -> usize {
        ((t / self.dt).round().max(0.0) as usize).min(self.states.len() - 1)
    }

    /// The scene drawn at step `k`; links pushing during the step into `k` are highlighted.
    pub fn frame(&self, k: usize) -> Frame {
        let state = &self.states[k];
        let robot = &self.scene.robot;
        let poses = robot.link_poses(&state.q);
        let touching = |link: usize| self.link_touching(k, link);
        Frame {
            time: k as f64 * self.dt,
            links: robot
                .solid_links()
                .flat_map(|l| {
                    let hot = touching(l);
                    let pose = &poses[l];
                    robot.chain.links[l]
                        .geometry
                        .iter()
                        .map(|g| (shape_outline(g, pose), hot))
                        .collect::<Vec<_>>()
                })
                .collect(),
            objects: self
                .scene
                .objects
                .iter()
                .zip(&state.objects)
                .map(|(o, p)| footprint_outline(&o.footprint, p))
                .collect(),
            executed: self.executed.get(k).map_or(Vec::new(), |poses| {
                self.scene
                    .objects
                    .iter()
                    .zip(poses)
                    .map(|(o, p)| footprint_outline(&o.footprint, p))
                    .collect()
            }),
        }
    }

    /// Whether `link` pushes an object in the step into or out of state `k`.
    pub fn link_touching(&self, k: usize, link: usize) -> bool {
        let around = [k.checked_sub(1), Some(k)];
        around.iter().flatten().any(|&s| {
            self.contacts
                .get(s)
                .is_some_and(|p| p.iter().any(|&(l, _)| l == link))
        })
    }

    /// The goal disc, if the goal is an object goal.
    pub fn goal_disc(&self) -> Option<(Vector2<f64>, f64)> {
        match &self.scene.goal {
            Goal::ObjectInDisc { center, radius, .. } => Some((*center, *radius)),
            Goal::Configuration { .. } | Goal::Grasp { .. } => None,
        }
    }

    /// Default snapshot times: four control boundaries spread over the plan, first and last included.
    pub fn default_times(&self) -> Vec<f64> {
        let n = self.control_starts.len() - 1;
        let picks: Vec<usize> = if n < 3 {
            (0..=n).collect()
        } else {
            (0..4).map(|i| (i * n + 1) / 3).map(|i| i.min(n)).collect()
        };
        let mut times: Vec<f64> = picks
            .iter()
            .map(|&i| self.control_starts[i] as f64 * self.dt)
            .collect();
        times.dedup();
        times
    }
}

/// Writes `execution.html` into `dir`: the plan's trajectory animated with the object
/// poses of one execution (`executed`, per trajectory sample) drawn over it, dashed.
pub fn render_execution(
    plan: &PlanFile,
    plan_path: &Path,
    executed: &[Vec<[f64; 3]>],
    dir: &Path,
) -> Result<PathBuf, String> {
    let film = Film::of_execution(plan, plan_path, executed)?;
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let path = dir.join("execution.html");
    crate::output::write_whole(&path, html::animation(&film))?;
    Ok(path)
}

/// Files written by [`render`].
pub struct Rendered {
    /// `snapshots.svg`.
    pub snapshots: PathBuf,
    /// `timeline.svg`.
    pub timeline: PathBuf,
    /// `animation.html`.
    pub animation: PathBuf,
}

/// Writes `snapshots.svg`, `timeline.svg` and `animation.html` for the plan into `dir`.
/// `times` are the snapshot times (s); empty for the default.
pub fn render(
    plan: &PlanFile,
    plan_path: &Path,
    dir: &Path,
    times: &[f64],
) -> Result<Rendered, String> {
    write_pictures(&Film::of(plan, plan_path)?, dir, times)
}

/// Writes `snapshots.svg`, `timeline.svg` and `animation.html` of `film` into `dir`.
/// `times` are the snapshot times (s); empty for the default.
pub fn write_pictures(film: &Film, dir: &Path, times: &[f64]) -> Result<Rendered, String> {
    let times = if times.is_empty() {
        film.default_times()
    } else {
        times.to_vec()
    };
    if let Some(t) = times
        .iter()
        .find(|t| !(t.is_finite() && **t >= 0.0 && **t <= film.duration() + 1e-9))
    {
        return Err(format!(
            "snapshot time {t} is outside the plan (0 to {:.2} s)",
            film.duration()
        ));
    }
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let write = |name: &str, text: String| {
        let path = dir.join(name);
        crate::output::write_whole(&path, text)?;
        Ok::<PathBuf, String>(path)
    };
    Ok(Rendered {
        snapshots: write("snapshots.svg", svg::snapshots(film, &times))?,
        timeline: write("timeline.svg", svg::timeline(film))?,
        animation: write("animation.html", html::animation(film))?,
    })
}
