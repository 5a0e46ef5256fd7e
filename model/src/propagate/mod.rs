//! `ConstrainedProp` (Alg. 2): hold an action for a duration, step by step.
//!
//! Per step of `dt` seconds:
//! 1. project the end-effector action to a joint step on the pushing plane;
//! 2. read each contact's pusher velocity from the links' motion and solve each touched
//!    object's twist (one complementarity problem per object), then move the objects;
//! 3. check the new state; the first invalid state ends the propagation.
//!
//! The contacts found while checking a state are the contacts its next step pushes with,
//! so each step runs one contact query per nearby link-object pair; the propagator also
//! remembers the last state it reached, so propagating on from it (as OMPL does, one step
//! per call) skips preparing it again. Results depend only on the start state and the
//! action: propagation is deterministic bit for bit.

mod cluster;

use crate::collision::section::slab_section;
use crate::contact::{
    by_object, object_bounds, planar_contacts, ArmBounds, ArmContact, ObjectContacts,
};
use crate::math::Pose2;
use crate::physics::tipping::{
    largest_tipping_moment, pusher_forces, sliding_push_tips, support_balance, ContactElevation,
};
use crate::physics::{object_motion, PlanarContact, PusherForce, SupportBalance};
use crate::robot::EeAction;
use crate::scene::file::PhysicsModel;
use crate::scene::Scene;
use crate::semi_dynamic::{Body, Rest, RestSettings, Sweep, Sweeps, Transition, Unsettled};
use crate::state::State;
use crate::validity::{check_arm_objects, check_objects, check_robot, Invalid};
use nalgebra::{DVector, Isometry3, Vector2};
use parry3d_f64::bounding_volume::Aabb;
use std::sync::Arc;

/// A link pushing an object during one step, with the force it applies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// Index of the link in the robot's chain.
    pub link: usize,
    /// Index of the object in the scene.
    pub object: usize,
    /// Total normal force of the link's contacts on the object (N).
    pub force: f64,
}

/// The outcome of holding one action.
#[derive(Clone, Debug, PartialEq)]
pub struct Propagation {
    /// The last valid state reached.
    pub state: State,
    /// Valid steps taken; the valid duration is `steps * dt`.
    pub steps: usize,
    /// Valid duration (s).
    pub duration: f64,
    /// For each valid step, the links that pushed objects.
    pub contacts: Vec<Vec<Contact>>,
    /// Why the propagation stopped early (`None` when the full duration was valid).
    pub stopped_by: Option<Invalid>,
}

/// Propagates actions through the scene's physics. Holds scratch buffers; one per thread.
pub struct Propagator {
    scene: Arc<Scene>,
    /// The valid state the buffers below describe (link poses, bounds, contacts).
    prepared: Option<State>,
    dt: f64,
    poses: Vec<Isometry3<f64>>,
    poses_new: Vec<Isometry3<f64>>,
    bounds: ArmBounds,
    object_boxes: Vec<Aabb>,
    object_boxes_new: Vec<Aabb>,
    contacts: Vec<ArmContact>,
    contacts_new: Vec<ArmContact>,
    object_contacts: ObjectContacts,
    forces: Vec<PusherForce>,
    q_new: DVector<f64>,
    objects_new: Vec<Pose2>,
    moved: Vec<bool>,
    /// The semi-dynamic model (`physics.model: semi_dynamic`), if it is the scene's.
    semi_dynamic: Option<SemiDynamic>,
}

impl Propagator {
    /// A propagator stepping with the scene's `planner.step`.
    pub fn new(scene: impl Into<Arc<Scene>>) -> Self {
        let scene = scene.into();
        let dt = scene.planner.step;
        Self::with_step(scene, dt)
    }

    /// A propagator stepping with `dt` seconds.
    pub fn with_step(scene: impl Into<Arc<Scene>>, dt: f64) -> Self {
        let scene: Arc<Scene> = scene.into();
        let (dof, objects) = (scene.robot.dof(), scene.objects.len());
        Self {
            prepared: None,
            dt,
            poses: Vec::new(),
            poses_new: Vec::new(),
            bounds: ArmBounds::default(),
            object_boxes: Vec::new(),
            object_boxes_new: Vec::new(),
            contacts: Vec::new(),
            contacts_new: Vec::new(),
            object_contacts: ObjectContacts::default(),
            forces: Vec::new(),
            q_new: DVector::zeros(dof),
            objects_new: Vec::new(),
            moved: vec![false; objects],
            semi_dynamic: SemiDynamic::of(&scene),
            scene,
        }
    }

    /// The propagation step `dt` (s).
    pub fn step_size(&self) -> f64 {
        self.dt
    }

    /// The scene the propagator steps.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The scene, shared.
    pub fn shared_scene(&self) -> Arc<Scene> {
        Arc::clone(&self.scene)
    }

    /// The tool point's world xy (m) at the state the buffers describe: where the last
    /// propagation ended (its last valid state). None before any propagation.
    pub fn tool_xy(&self) -> Option<nalgebra::Vector2<f64>> {
        self.prepared.as_ref()?;
        Some(
            self.scene
                .robot
                .tool_pose(&self.poses)
                .translation
                .vector
                .xy(),
        )
    }

    /// The state the last failed step tried to reach (invalid; for callers that must
    /// report a result state anyway, like OMPL's propagator).
    pub fn attempted_state(&self) -> State {
        State {
            q: self.q_new.clone(),
            objects: self.objects_new.clone(),
        }
    }

    /// Holds `action` for `duration` seconds (rounded up to whole steps) from `start`,
    /// which must be valid.
    pub fn propagate(&mut self, start: &State, action: &EeAction, duration: f64) -> Propagation {
        let steps = (duration / self.dt - 1e-9).ceil().max(0.0) as usize;
        self.propagate_steps(start, action, steps)
    }

    /// Holds `action` for `steps` steps from `start`, which must be valid.
    pub fn propagate_steps(
        &mut self,
        start: &State,
        action: &EeAction,
        steps: usize,
    ) -> Propagation {
        let mut state = start.clone();
        let mut contacts = Vec::with_capacity(steps);
        let mut stopped_by = self.prepare(start).err();
        if stopped_by.is_none() {
            for _ in 0..steps {
                match self.step(&mut state, action) {
                    Ok(step_contacts) => contacts.push(step_contacts),
                    Err(e) => {
                        stopped_by = Some(e);
                        break;
                    }
                }
            }
            // Into the kept buffer: OMPL propagates one step per call.
            match &mut self.prepared {
                Some(prepared) => prepared.clone_from(&state),
                None => self.prepared = Some(state.clone()),
            }
        }
        let steps = contacts.len();
        Propagation {
            state,
            steps,
            duration: steps as f64 * self.dt,
            contacts,
            stopped_by,
        }
    }

    /// Fills the buffers for `state` (link poses, contacts), unless they hold it already.
    fn prepare(&mut self, state: &State) -> Result<(), Invalid> {
        if self.prepared.as_ref().is_some_and(|p| same_bits(p, state)) {
            return Ok(());
        }
        self.prepared = None;
        let scene = &*self.scene;
        scene
            .robot
            .chain
            .forward_kinematics(&state.q, &mut self.poses);
        ArmBounds::compute(scene, &self.poses, &mut self.bounds);
        object_bounds(scene, &state.objects, &mut self.object_boxes);
        check_arm_objects(
            scene,
            &self.poses,
            &self.bounds,
            &state.objects,
            &self.object_boxes,
            &mut self.contacts,
        )?;
        self.prepared = Some(state.clone());
        Ok(())
    }

    /// One step from `state` (whose link poses and contacts are cached). On success the
    /// state, poses and contacts advance; on failure nothing changes.
    fn step(&mut self, state: &mut State, action: &EeAction) -> Result<Vec<Contact>, Invalid> {
        if self.semi_dynamic.is_some() {
            return self.semi_dynamic_step(state, action);
        }
        self.project(state, action)?;
        self.objects_new.clone_from(&state.objects);
        self.object_boxes_new.clone_from(&self.object_boxes);
        self.moved.iter_mut().for_each(|m| *m = false);
        if self.scene.physics.object_pushing {
            if let Some(cluster) = self.find_cluster(state) {
                let pushes = self.push_cluster(state, &cluster)?;
                self.accept(state)?;
                return Ok(pushes);
            }
        }
        let scene = &*self.scene;
        let dt = self.dt;

        // Physics: every object with contacts, each alone.
        let mut pushes = Vec::new();
        for (object, run) in by_object(&self.contacts) {
            let pose = state.objects[object];
            planar_contacts(
                &self.contacts[run],
                &pose,
                scene.table.top,
                &self.poses,
                &self.poses_new,
                dt,
                &mut self.object_contacts,
            );
            let contacts = &self.object_contacts;
            let body = &scene.objects[object];
            let jammed = |_| Invalid::Jammed {
                object: body.name.clone(),
            };
            let mut motion = object_motion(&contacts.planar, &body.limit_surface, body.mu_c, dt)
                .map_err(jammed)?;
            if !motion.twist.is_zero() {
                let centroid = body.footprint.centroid();
                pusher_forces(
                    &contacts.planar,
                    &contacts.elevations,
                    &motion,
                    &mut self.forces,
                );
                let mut balance = support_balance(body.mass, centroid, &self.forces);
                if scene.physics.pressure_shift && balance.stays_flat(&body.footprint, 0.0) {
                    // The pushes move the centre of pressure by p_OP - p_OG; the centre of
                    // friction moves with it. One re-solve: the forces barely change with
                    // the centre.
                    let surface = body.loaded_surface(&balance);
                    motion =
                        object_motion(&contacts.planar, &surface, body.mu_c, dt).map_err(jammed)?;
                    pusher_forces(
                        &contacts.planar,
                        &contacts.elevations,
                        &motion,
                        &mut self.forces,
                    );
                    balance = support_balance(body.mass, centroid, &self.forces);
                }
                keeps_flat(scene, object, contacts, &balance, &self.forces)?;
                let moved = pose.integrate(&motion.twist, dt);
                self.objects_new[object] = moved;
                self.object_boxes_new[object] =
                    body.geometry.aabb(&moved.to_isometry(scene.table.top));
                self.moved[object] = true;
            }
            no_link_closes_in(scene, object, contacts, &motion.normal_forces)?;
            for (&link, &force) in contacts.links.iter().zip(&motion.normal_forces) {
                record_push(&mut pushes, link, object, force);
            }
        }

        self.accept(state)?;
        Ok(pushes)
    }

    /// The arm's step from `state` under `action` into `q_new` and `poses_new`.
    fn project(&mut self, state: &State, action: &EeAction) -> Result<(), Invalid> {
        self.scene
            .robot
            .project_step(
                &state.q,
                &self.poses,
                action,
                self.dt,
                &mut self.q_new,
                &mut self.poses_new,
            )
            .map_err(Invalid::Projection)
    }

    /// Checks the new state (`q_new`, `poses_new`, `objects_new` and their boxes, `moved`)
    /// and, if it is valid, makes it `state`; its contacts serve the next step.
    fn accept(&mut self, state: &mut State) -> Result<(), Invalid> {
        let scene = &*self.scene;
        ArmBounds::compute(scene, &self.poses_new, &mut self.bounds);
        check_robot(scene, &self.q_new, &self.poses_new, &self.bounds)?;
        check_arm_objects(
            scene,
            &self.poses_new,
            &self.bounds,
            &self.objects_new,
            &self.object_boxes_new,
            &mut self.contacts_new,
        )?;
        let moved = &self.moved;
        check_objects(scene, &self.objects_new, |i| moved[i])?;

        state.q.copy_from(&self.q_new);
        state.objects.clone_from(&self.objects_new);
        std::mem::swap(&mut self.poses, &mut self.poses_new);
        std::mem::swap(&mut self.contacts, &mut self.contacts_new);
        std::mem::swap(&mut self.object_boxes, &mut self.object_boxes_new);
        Ok(())
    }
}

impl Propagator {
    /// One step of the semi-dynamic model: the links reaching the objects' heights sweep
    /// as the projected joint step moves them, the world (rebuilt from `state`) runs until
    /// its objects rest, and the new state must be valid (arm against table and
    /// obstacles, arm against objects in 3D, objects on the table and apart). A contact's
    /// force is the mean normal force over the step: the engine's impulse over `dt`.
    fn semi_dynamic_step(
        &mut self,
        state: &mut State,
        action: &EeAction,
    ) -> Result<Vec<Contact>, Invalid> {
        self.project(state, action)?;
        let scene = &*self.scene;
        let model = self
            .semi_dynamic
            .as_mut()
            .expect("called for semi-dynamic scenes only");
        let rest = model
            .transition(
                scene,
                &state.objects,
                &self.poses,
                &self.poses_new,
                self.dt,
                false,
            )
            .map_err(|u| Invalid::Unsettled {
                object: scene.objects[u.object].name.clone(),
                speed: u.speed,
            })?;
        // Tipping, as the quasistatic model decides it for a push that slides the object
        // (`physics::tipping::sliding_push_tips`): the push along the impulse's direction
        // at the link's lowest point on the object's side. Strikes add inertia the check
        // leaves out.
        for push in &rest.pushes {
            let body = &scene.objects[push.object];
            let sweep = &model.buffer[push.pusher];
            let turn = nalgebra::Rotation2::new(-state.objects[push.object].theta);
            let contact = PlanarContact {
                // With a level push only the force's height and direction matter.
                point: body.footprint.centroid(),
                normal: turn * push.direction,
                pusher_velocity: Vector2::zeros(),
                gap: 0.0,
            };
            let elevation = ContactElevation {
                height: (sweep.lowest - scene.table.top).max(0.0),
                slope: 0.0,
            };
            if push.direction != Vector2::zeros()
                && sliding_push_tips(
                    body.mass,
                    body.mu_g,
                    &body.footprint,
                    &contact,
                    &elevation,
                    scene.physics.tipping_margin,
                )
            {
                return Err(Invalid::Tips {
                    object: body.name.clone(),
                    link: scene.robot.chain.links[sweep.link].name.clone(),
                });
            }
        }
        let pushes = rest
            .pushes
            .iter()
            .map(|p| Contact {
                link: model.buffer[p.pusher].link,
                object: p.object,
                force: p.impulse / self.dt,
            })
            .collect();
        self.objects_new = rest.poses;
        object_bounds(scene, &self.objects_new, &mut self.object_boxes_new);
        for (moved, (a, b)) in self
            .moved
            .iter_mut()
            .zip(state.objects.iter().zip(&self.objects_new))
        {
            *moved = a.x.to_bits() != b.x.to_bits()
                || a.y.to_bits() != b.y.to_bits()
                || a.theta.to_bits() != b.theta.to_bits();
        }
        self.accept(state)?;
        Ok(pushes)
    }
}

/// The semi-dynamic model of a scene: its objects as bodies of a top-down world, the
/// robot's links cut at the objects' heights as its pushers.
#[derive(Clone)]
pub struct SemiDynamic {
    transition: Transition,
    sweeps: Sweeps,
    /// The last step's sweeps.
    buffer: Vec<Sweep>,
}

impl SemiDynamic {
    /// The model of a scene whose `physics.model` is `semi_dynamic`.
    pub fn of(scene: &Scene) -> Option<SemiDynamic> {
        if scene.physics.model != PhysicsModel::SemiDynamic {
            return None;
        }
        let bodies: Vec<Body> = scene
            .objects
            .iter()
            .map(|o| Body {
                footprint: o.footprint.clone(),
                mass: o.mass,
                mu_g: o.mu_g,
                mu_c: o.mu_c,
            })
            .collect();
        let top = scene.table.top;
        let heights: Vec<f64> = scene.objects.iter().map(|o| o.height).collect();
        let sweeps = Sweeps::new(&heights, top);
        // Obstacles where they reach into the objects' height range, seen from above.
        let mut points = Vec::new();
        let obstacles: Vec<Vec<Vector2<f64>>> = scene
            .obstacles
            .iter()
            .map(|o| {
                points.clear();
                slab_section(
                    &o.geometry,
                    &o.pose,
                    top,
                    top + sweeps.tallest(),
                    &mut points,
                );
                points.iter().map(|p| p.xy().coords).collect()
            })
            .collect();
        let rest = RestSettings {
            t_max: scene.physics.t_max,
            ..RestSettings::default()
        };
        let transition = Transition::new(&bodies, sweeps.object_classes(), &obstacles, rest)
            .expect("a scene's footprints have area");
        Some(SemiDynamic {
            transition,
            sweeps,
            buffer: Vec::new(),
        })
    }

    /// The objects' rest after the links move from poses `from` to `to` in `dt` seconds
    /// (with every engine step's poses if `record`).
    pub fn transition(
        &mut self,
        scene: &Scene,
        objects: &[Pose2],
        from: &[Isometry3<f64>],
        to: &[Isometry3<f64>],
        dt: f64,
        record: bool,
    ) -> Result<Rest, Unsettled> {
        self.sweeps
            .sweeps(&scene.robot.chain.links, from, to, &mut self.buffer);
        self.transition.step(objects, &self.buffer, dt, record)
    }
}

/// The table keeps pushed `object` flat under the links' `forces` (`balance`, theirs),
/// with the tipping margin; otherwise the link with the largest tipping moment tips it.
fn keeps_flat(
    scene: &Scene,
    object: usize,
    contacts: &ObjectContacts,
    balance: &SupportBalance,
    forces: &[PusherForce],
) -> Result<(), Invalid> {
    let body = &scene.objects[object];
    if balance.stays_flat(&body.footprint, scene.physics.tipping_margin) {
        return Ok(());
    }
    let pusher = largest_tipping_moment(forces).unwrap_or(0);
    Err(Invalid::Tips {
        object: body.name.clone(),
        link: scene.robot.chain.links[contacts.links[pusher]].name.clone(),
    })
}

/// No link closes in on `object` without pushing it (`normal_forces`, per contact) where a
/// push that slid it would tip it: the plan would hang on the touch never happening, or
/// on its turning the object rather than sliding it, and a few millimetres elsewhere in
/// the world it happens.
fn no_link_closes_in(
    scene: &Scene,
    object: usize,
    contacts: &ObjectContacts,
    normal_forces: &[f64],
) -> Result<(), Invalid> {
    let body = &scene.objects[object];
    match contacts.closing_in_at_tipping_height(
        body,
        normal_forces,
        scene.clearances.arm(object, scene.physics.arm_clearance),
        scene.physics.tipping_margin,
    ) {
        Some((link, distance)) => Err(Invalid::ClosesInAtTippingHeight {
            link: scene.robot.chain.links[link].name.clone(),
            object: body.name.clone(),
            distance,
        }),
        None => Ok(()),
    }
}

/// Adds a link's normal force on an object to the step's pushes (if it pushes).
fn record_push(pushes: &mut Vec<Contact>, link: usize, object: usize, force: f64) {
    if force <= 0.0 {
        return;
    }
    match pushes
        .iter_mut()
        .find(|p| p.link == link && p.object == object)
    {
        Some(p) => p.force += force,
        None => pushes.push(Contact {
            link,
            object,
            force,
        }),
    }
}

/// Bitwise equality of two states (NaN-safe, distinguishes -0.0).
fn same_bits(a: &State, b: &State) -> bool {
    a.q.len() == b.q.len()
        && a.objects.len() == b.objects.len()
        && a.q
            .iter()
            .zip(b.q.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits())
        && a.objects.iter().zip(&b.objects).all(|(p, o)| {
            p.x.to_bits() == o.x.to_bits()
                && p.y.to_bits() == o.y.to_bits()
                && p.theta.to_bits() == o.theta.to_bits()
        })
}

impl From<&Scene> for Arc<Scene> {
    fn from(scene: &Scene) -> Self {
        Arc::new(scene.clone())
    }
}
