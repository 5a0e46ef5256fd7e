//! The workshop paper's semi-dynamic transition function (issue 14, first part): the
//! table seen from above as a 2D rigid-body world (rapier2d), objects as dynamic bodies
//! that may be struck, slide, push one another and coast, a pusher as a kinematic body.
//! An action moves the pusher for its duration; then the world runs on with the pusher
//! still until every object rests, or the state is invalid after `t_max`. States stay
//! configurations only (no velocities), as in the paper.
//!
//! Support friction against the table is Coulomb friction, not damping: rapier has no
//! ground in a top-down world, so each step removes the velocity the friction wrench of
//! the ellipsoidal limit surface (`shared/docs/physics.md`) takes away: force `mu_g m g`
//! against sliding, torque `mu_g m g c` against turning (c the footprint's characteristic
//! length), coupled as the limit surface couples them; a body it would reverse stops.
//! Half the step's friction acts before the engine's step and half after, so positions
//! integrate the mid-step velocity (exact for a constant deceleration).
//!
//! Frames: world x, y on the table (m); yaw about world z (rad).

use crate::math::Pose2;
use crate::physics::limit_surface::GRAVITY;
use crate::physics::Footprint;
use nalgebra::{Isometry2, Point2, Vector2};
use rapier2d_f64::prelude::*;

/// Engine step (s).
pub const STEP: f64 = 1.0 / 240.0;

/// When objects count as resting, and how long they may take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RestSettings {
    /// Every object slower than this (m/s, and rad/s times its characteristic length).
    pub speed: f64,
    /// Longest time after an action for every object to come to rest (s).
    pub t_max: f64,
}

impl Default for RestSettings {
    fn default() -> Self {
        Self {
            speed: 1e-3,
            t_max: 8.0,
        }
    }
}

/// A movable object of the world: its footprint (object frame), mass and frictions.
#[derive(Clone, Debug)]
pub struct Body {
    pub footprint: Footprint,
    /// kg
    pub mass: f64,
    /// Support friction against the table, and contact friction against others.
    pub mu_g: f64,
    pub mu_c: f64,
}

/// Objects still moving `t_max` after the action: the state is invalid.
#[derive(Clone, Debug, PartialEq)]
pub struct Unsettled {
    /// The fastest object and its speed (m/s) when time ran out.
    pub object: usize,
    pub speed: f64,
}

/// A pusher's motion: planar velocity in the world frame (m/s, m/s, rad/s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PusherVelocity {
    pub vx: f64,
    pub vy: f64,
    pub omega: f64,
}

/// The friction a body's support removes, per step.
#[derive(Clone, Copy, Debug)]
struct Support {
    /// Largest friction force (N): mu_g m g.
    force: f64,
    /// Characteristic length c (m): the torque for pure turning is force * c.
    c: f64,
    mass: f64,
    inertia: f64,
}

/// The top-down world.
pub struct World {
    pipeline: PhysicsPipeline,
    params: IntegrationParameters,
    islands: IslandManager,
    broad_phase: BroadPhaseBvh,
    narrow_phase: NarrowPhase,
    bodies: RigidBodySet,
    colliders: ColliderSet,
    impulse_joints: ImpulseJointSet,
    multibody_joints: MultibodyJointSet,
    ccd: CCDSolver,
    objects: Vec<(RigidBodyHandle, Support)>,
    pusher: Option<RigidBodyHandle>,
    /// Seconds simulated.
    time: f64,
}

/// A footprint as a 2D collider shape.
fn shape(footprint: &Footprint) -> Option<SharedShape> {
    match footprint {
        Footprint::Circle { radius } => Some(SharedShape::ball(*radius)),
        Footprint::Polygon { vertices } => {
            let points: Vec<Point2<f64>> = vertices.iter().map(|v| Point2::from(*v)).collect();
            SharedShape::convex_hull(&points)
        }
    }
}

fn isometry(pose: &Pose2) -> Isometry2<f64> {
    Isometry2::new(Vector2::new(pose.x, pose.y), pose.theta)
}

impl World {
    /// Objects at `poses`, and a pusher of footprint `pusher` at its pose, if any.
    /// `None` if a footprint has no area.
    pub fn new(
        objects: &[(Body, Pose2)],
        pusher: Option<(&Footprint, Pose2, f64)>,
    ) -> Option<World> {
        let mut bodies = RigidBodySet::new();
        let mut colliders = ColliderSet::new();
        let mut handles = Vec::with_capacity(objects.len());
        for (body, pose) in objects {
            let handle = bodies.insert(
                RigidBodyBuilder::dynamic()
                    .pose(isometry(pose))
                    .can_sleep(false),
            );
            let collider = ColliderBuilder::new(shape(&body.footprint)?)
                .mass(body.mass)
                .friction(body.mu_c)
                .restitution(0.0);
            colliders.insert_with_parent(collider, handle, &mut bodies);
            let inertia = bodies[handle]
                .mass_properties()
                .local_mprops
                .principal_inertia();
            handles.push((
                handle,
                Support {
                    force: body.mu_g * body.mass * GRAVITY,
                    c: body.footprint.characteristic_length(),
                    mass: body.mass,
                    inertia,
                },
            ));
        }
        let pusher = match pusher {
            Some((footprint, pose, mu_c)) => {
                let handle = bodies
                    .insert(RigidBodyBuilder::kinematic_velocity_based().pose(isometry(&pose)));
                let collider = ColliderBuilder::new(shape(footprint)?)
                    .friction(mu_c)
                    .restitution(0.0);
                colliders.insert_with_parent(collider, handle, &mut bodies);
                Some(handle)
            }
            None => None,
        };
        Some(World {
            pipeline: PhysicsPipeline::new(),
            params: IntegrationParameters {
                dt: STEP,
                ..IntegrationParameters::default()
            },
            islands: IslandManager::new(),
            broad_phase: BroadPhaseBvh::new(),
            narrow_phase: NarrowPhase::new(),
            bodies,
            colliders,
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            ccd: CCDSolver::new(),
            objects: handles,
            pusher,
            time: 0.0,
        })
    }

    /// Moves the pusher at `velocity` for `duration` seconds (whole engine steps), then
    /// holds it still.
    pub fn push(&mut self, velocity: PusherVelocity, duration: f64) {
        if let Some(pusher) = self.pusher {
            self.bodies[pusher].set_linvel(Vector2::new(velocity.vx, velocity.vy), true);
            self.bodies[pusher].set_angvel(velocity.omega, true);
        }
        for _ in 0..(duration / STEP).round() as usize {
            self.step();
        }
        if let Some(pusher) = self.pusher {
            self.bodies[pusher].set_linvel(Vector2::zeros(), true);
            self.bodies[pusher].set_angvel(0.0, true);
        }
    }

    /// Runs on until every object rests; the time it took (s), or the fastest object
    /// still moving after `rest.t_max`.
    pub fn settle(&mut self, rest: &RestSettings) -> Result<f64, Unsettled> {
        let start = self.time;
        loop {
            let fastest = self
                .objects
                .iter()
                .enumerate()
                .map(|(i, (handle, support))| {
                    let body = &self.bodies[*handle];
                    (i, body.linvel().norm().max(body.angvel().abs() * support.c))
                })
                .fold((0, 0.0_f64), |a, b| if b.1 > a.1 { b } else { a });
            if fastest.1 < rest.speed {
                return Ok(self.time - start);
            }
            if self.time - start >= rest.t_max {
                return Err(Unsettled {
                    object: fastest.0,
                    speed: fastest.1,
                });
            }
            self.step();
        }
    }

    /// Advances the world by [`STEP`], support friction acting half before and half
    /// after the engine's step.
    pub fn step(&mut self) {
        self.support_friction(STEP / 2.0);
        self.pipeline.step(
            &Vector2::zeros(),
            &self.params,
            &mut self.islands,
            &mut self.broad_phase,
            &mut self.narrow_phase,
            &mut self.bodies,
            &mut self.colliders,
            &mut self.impulse_joints,
            &mut self.multibody_joints,
            &mut self.ccd,
            &(),
            &(),
        );
        self.support_friction(STEP / 2.0);
        self.time += STEP;
    }

    /// Removes `dt` seconds' worth of the support's friction from every object's velocity.
    /// The ellipsoidal limit surface's wrench opposes the twist scaled by c: (f, tau / c)
    /// = -force (v, omega c) / |(v, omega c)|.
    fn support_friction(&mut self, dt: f64) {
        for (handle, s) in &self.objects {
            let body = &mut self.bodies[*handle];
            let (v, omega) = (*body.linvel(), body.angvel());
            let size = (v.norm_squared() + (omega * s.c).powi(2)).sqrt();
            if size < 1e-12 {
                continue;
            }
            let force = -s.force * v / size;
            let torque = -s.force * s.c * (omega * s.c) / size;
            let mut v_new = v + force / s.mass * dt;
            let mut omega_new = omega + torque / s.inertia * dt;
            // Friction stops a body; it never turns it around.
            if v_new.dot(&v) <= 0.0 {
                v_new = Vector2::zeros();
            }
            if omega_new * omega <= 0.0 {
                omega_new = 0.0;
            }
            body.set_linvel(v_new, true);
            body.set_angvel(omega_new, true);
        }
    }

    /// Sets object `i`'s velocity (m/s, world frame; rad/s): a strike.
    pub fn set_velocity(&mut self, i: usize, v: Vector2<f64>, omega: f64) {
        let body = &mut self.bodies[self.objects[i].0];
        body.set_linvel(v, true);
        body.set_angvel(omega, true);
    }

    /// Object `i`'s pose.
    pub fn pose(&self, i: usize) -> Pose2 {
        let p = self.bodies[self.objects[i].0].position();
        Pose2::new(p.translation.x, p.translation.y, p.rotation.angle())
    }

    /// Seconds simulated so far.
    pub fn time(&self) -> f64 {
        self.time
    }
}
