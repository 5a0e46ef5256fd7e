//! [`Problem`]: a scene loaded for OMPL, and the search it is set up for (pushing or
//! Static RRT's pinned clutter; perturbed worlds). Its parts ([`super::Propagator`],
//! [`super::ValidityChecker`], ...) are made from it and share its [`Core`].

use super::core::{guarded, SharedCore};
use super::ffi::SceneInfo;
use crate::planner::{ParticleWorlds, PushHeading};
use crate::planning::static_clutter::StaticClutter;
use crate::scene::Scene;
use crate::state::State;
use std::sync::{Arc, OnceLock};

/// A scene loaded for OMPL (OMPL's problem definition and space information, as far as
/// the model is concerned).
pub struct Problem {
    pub(crate) scene: Arc<Scene>,
    pub(crate) core: SharedCore,
    /// The push headings of the scene, made on first use (where the hand cannot get
    /// behind the goal object they measure its reach: inverse kinematics, once), and
    /// shared with its duplicates: they depend on the scene alone.
    push_heading: Arc<OnceLock<Arc<PushHeading>>>,
}

// The entry points' bridge (`super::entry`) takes a problem by reference: the C++ type
// is the one `super::ffi` declares (an opaque Rust type), named here so that a second
// bridge may use it.
unsafe impl cxx::ExternType for Problem {
    type Id = cxx::type_id!("pushplan::bridge::Problem");
    type Kind = cxx::kind::Opaque;
}

impl Problem {
    /// The problem of `scene`, in the pushing problem without perturbed worlds.
    pub fn new(scene: Scene) -> Problem {
        Problem {
            core: SharedCore::new(&scene),
            scene: Arc::new(scene),
            push_heading: Arc::default(),
        }
    }

    /// The problem of the same scene and start as `load` would give it anew (the pushing
    /// problem, no perturbed worlds), without reading or preparing the scene again: a
    /// search's models (one per search and lane) are duplicates of one loaded problem.
    /// The scene and push headings are shared; the core (what one model's parts share
    /// while it searches) is its own.
    pub fn duplicate(&self) -> Box<Problem> {
        Box::new(Problem {
            core: SharedCore::new(&self.scene),
            scene: self.scene.clone(),
            push_heading: self.push_heading.clone(),
        })
    }

    /// The push headings of the scene ([`PushHeading`]), shared by every projection and
    /// control sampler made from this problem.
    pub(crate) fn push_heading(&self) -> Arc<PushHeading> {
        self.push_heading
            .get_or_init(|| Arc::new(PushHeading::new(&self.scene)))
            .clone()
    }

    /// Loads a scene file (boxed for C++).
    pub fn load(path: &str) -> Result<Box<Problem>, String> {
        guarded("loading a scene", || {
            let scene = Scene::load(path).map_err(|e| e.to_string())?;
            Ok(Box::new(Problem::new(scene)))
        })
    }

    /// A problem from a scene's YAML text; `source` names it in messages and anchors its
    /// relative paths.
    pub fn from_yaml(yaml: &str, source: &str) -> Result<Box<Problem>, String> {
        guarded("reading a scene", || {
            let scene =
                Scene::from_yaml(yaml, std::path::Path::new(source)).map_err(|e| e.to_string())?;
            Ok(Box::new(Problem::new(scene)))
        })
    }

    /// Plans from `flat` (a state in the flat layout, such as one observed while a plan
    /// runs) instead of the scene's start, checked as a scene's start is
    /// ([`Scene::with_start`]). Call it before any part is made from this problem: they
    /// would keep the old start.
    pub fn set_start(&mut self, flat: &[f64]) -> Result<(), String> {
        guarded("set_start", || {
            let (dof, objects) = (self.scene.robot.dof(), self.scene.objects.len());
            if flat.len() != State::flat_len(dof, objects) {
                return Err(format!(
                    "a start of {} values for a state of {} ({dof} joints, {objects} objects)",
                    flat.len(),
                    State::flat_len(dof, objects)
                ));
            }
            let start = State::from_flat(flat, dof);
            let scene = self
                .scene
                .with_start(&start, std::path::Path::new("the observed start"))
                .map_err(|e| e.to_string())?;
            *self = Problem::new(scene);
            Ok(())
        })
    }

    /// What the OMPL side needs to know about the scene.
    pub fn info(&self) -> SceneInfo {
        SceneInfo::from(&*self.scene)
    }

    /// The scene check's warnings (`scene::check`), in words.
    pub fn scene_warnings(&self) -> Vec<String> {
        crate::scene::check::check(&self.scene)
            .iter()
            .map(ToString::to_string)
            .collect()
    }

    /// The scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Switches to (or from) the Static RRT baseline: clutter objects become static
    /// obstacles at their start poses.
    pub fn set_static_clutter(&mut self, on: bool) {
        let mut core = self.core.lock();
        core.static_clutter = on.then(|| StaticClutter::new(&self.scene));
        core.last_result = None;
    }

    /// Is the clutter pinned (Static RRT's mode)?
    pub fn static_clutter(&self) -> bool {
        self.core.lock().static_clutter.is_some()
    }

    /// Robust planning: from now on every state carries `count` perturbed worlds drawn
    /// from `seed` ([`ParticleWorlds`]); 0 turns them off. In the pushing problem only.
    pub fn set_particles(&mut self, count: usize, seed: u64) -> Result<(), String> {
        guarded("set_particles", || {
            let mut core = self.core.lock();
            if count > 0 && core.static_clutter.is_some() {
                return Err("perturbed worlds are carried in the pushing problem only".into());
            }
            core.particles = ParticleWorlds::draw(&self.scene, count, seed)
                .map_err(|e| format!("no valid perturbed start for a perturbed world: {e}"))?;
            core.last_result = None;
            Ok(())
        })
    }

    /// The perturbed worlds' start poses (empty without worlds): a state's block of
    /// perturbed poses has this many values.
    pub fn start_particles(&self) -> Vec<f64> {
        self.core.lock().particles.start_flat()
    }
}
