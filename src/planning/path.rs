//! Paths: a start state and a sequence of controls, simulated step by step, with the
//! metrics of Sec. V-B (manipulator path length, object displacement).

use crate::propagate::{Contact, Propagator};
use crate::robot::EeAction;
use crate::state::State;
use crate::validity::Invalid;

/// One control of a path: an action held for a number of propagation steps.
#[derive(Clone, Debug, PartialEq)]
pub struct PathControl {
    /// The action: tool velocity and null-space sample.
    pub action: EeAction,
    /// Propagation steps it is held for.
    pub steps: usize,
}

impl PathControl {
    /// Controls in the flat layout of [`EeAction::from_flat`], one after another, with
    /// their step counts.
    pub fn from_flat(
        controls: &[f64],
        steps: &[usize],
        dof: usize,
    ) -> Result<Vec<PathControl>, String> {
        let width = 3 + dof;
        if controls.len() != width * steps.len() {
            return Err(format!(
                "{} control values for {} controls of {width}",
                controls.len(),
                steps.len()
            ));
        }
        Ok(controls
            .chunks(width)
            .zip(steps)
            .map(|(c, &steps)| PathControl {
                action: EeAction::from_flat(c),
                steps,
            })
            .collect())
    }

    /// The control that moves the tool back the way this one moved it, for as many
    /// steps: its tool velocity and null-space sample negated.
    pub fn reversed(&self) -> PathControl {
        PathControl {
            action: EeAction {
                velocity: self.action.velocity.map(|v| -v),
                nullspace: -&self.action.nullspace,
            },
            steps: self.steps,
        }
    }

    /// The flat layout of [`PathControl::from_flat`]: the actions and the step counts.
    pub fn to_flat(controls: &[PathControl]) -> (Vec<f64>, Vec<usize>) {
        (
            controls.iter().flat_map(|c| c.action.flat()).collect(),
            controls.iter().map(|c| c.steps).collect(),
        )
    }
}

/// How long and how disruptive a path is. C++'s `pushplan::PathMetrics` is the same type
/// (same fields, same order): the bridge passes it as is.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
#[repr(C)]
pub struct PathMetrics {
    /// Joint-space path length: sum over steps of |q_{k+1} - q_k| (rad, or m for prismatic joints).
    pub joint_length: f64,
    /// Distance travelled by the tool point (m).
    pub ee_length: f64,
    /// Total distance travelled by all object centres (m).
    pub object_displacement: f64,
    /// Objects whose centre travelled more than 1 mm.
    pub objects_moved: usize,
    /// Links that pushed an object at some step.
    pub links_in_contact: usize,
    /// Duration of the path (s).
    pub duration: f64,
}

/// A path simulated from its start.
#[derive(Clone, Debug, PartialEq)]
pub struct SimulatedPath {
    /// The state at the start and after each control.
    pub states: Vec<State>,
    /// Joint-space path length up to each of `states`.
    pub joint_length_at: Vec<f64>,
    /// Every step's state, starting with the start state (when recorded).
    pub step_states: Vec<State>,
    /// Per control, per step, the links pushing objects.
    pub contacts: Vec<Vec<Vec<Contact>>>,
    /// Why a control stopped early, if one did (the path is then invalid).
    pub stopped_by: Option<(usize, Invalid)>,
    /// Its manipulator path, object displacement and duration.
    pub metrics: PathMetrics,
}

impl SimulatedPath {
    /// Was every step valid?
    pub fn valid(&self) -> bool {
        self.stopped_by.is_none()
    }

    /// Total number of steps taken.
    pub fn steps(&self) -> usize {
        self.contacts.iter().map(Vec::len).sum()
    }

    /// The state after the last step.
    pub fn final_state(&self) -> &State {
        self.states.last().expect("a path has a start state")
    }
}

/// Simulates `controls` from `start` one step at a time (bit-identical to holding each
/// control in one call), measuring the path. `record_steps` keeps every step's state.
pub fn simulate(
    propagator: &mut Propagator,
    start: &State,
    controls: &[PathControl],
    record_steps: bool,
) -> SimulatedPath {
    let scene = propagator.shared_scene();
    let robot = &scene.robot;
    let tool = |s: &State| robot.tool_pose(&robot.link_poses(&s.q)).translation.vector;
    let objects = start.objects.len();
    let mut state = start.clone();
    let mut tool_at = tool(&state);
    let mut travelled = vec![0.0; objects];
    let mut links = Vec::new();
    let mut path = SimulatedPath {
        states: vec![start.clone()],
        joint_length_at: vec![0.0],
        step_states: if record_steps {
            vec![start.clone()]
        } else {
            vec![]
        },
        contacts: Vec::with_capacity(controls.len()),
        stopped_by: None,
        metrics: PathMetrics::default(),
    };
    for (i, control) in controls.iter().enumerate() {
        let mut control_pushes = Vec::with_capacity(control.steps);
        for _ in 0..control.steps {
            let run = propagator.propagate_steps(&state, &control.action, 1);
            if let Some(reason) = run.stopped_by {
                path.stopped_by = Some((i, reason));
                break;
            }
            let m = &mut path.metrics;
            m.joint_length += (&run.state.q - &state.q).norm();
            let next_tool = tool(&run.state);
            m.ee_length += (next_tool - tool_at).norm();
            tool_at = next_tool;
            for (k, (a, b)) in state.objects.iter().zip(&run.state.objects).enumerate() {
                travelled[k] += (b.translation() - a.translation()).norm();
            }
            let pushes = run.contacts.into_iter().next().unwrap_or_default();
            for p in &pushes {
                if !links.contains(&p.link) {
                    links.push(p.link);
                }
            }
            control_pushes.push(pushes);
            state = run.state;
            m.duration += propagator.step_size();
            if record_steps {
                path.step_states.push(state.clone());
            }
        }
        path.contacts.push(control_pushes);
        path.states.push(state.clone());
        path.joint_length_at.push(path.metrics.joint_length);
        if path.stopped_by.is_some() {
            break;
        }
    }
    path.metrics.object_displacement = travelled.iter().sum();
    path.metrics.objects_moved = travelled.iter().filter(|&&d| d > 1e-3).count();
    path.metrics.links_in_contact = links.len();
    path
}
