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
//! Obstacles are fixed outlines: what an obstacle covers of the objects' height range, seen
//! from above.
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

/// A body as the world needs it, derived once from a [`Body`]: its collider's shape and
/// its support's friction.
#[derive(Clone)]
struct Solid {
    shape: SharedShape,
    mass: f64,
    mu_c: f64,
    /// Largest support friction force (N): mu_g m g.
    force: f64,
    /// Characteristic length c (m): the torque for pure turning is force * c.
    c: f64,
}

impl Solid {
    /// `None` for a footprint without area.
    fn of(body: &Body) -> Option<Solid> {
        Some(Solid {
            shape: shape(&body.footprint)?,
            mass: body.mass,
            mu_c: body.mu_c,
            force: body.mu_g * body.mass * GRAVITY,
            c: body.footprint.characteristic_length(),
        })
    }
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
        Footprint::Polygon { vertices } => hull(vertices),
    }
}

/// The convex hull of points as a collider shape; `None` without area.
fn hull(points: &[Vector2<f64>]) -> Option<SharedShape> {
    let points: Vec<Point2<f64>> = points.iter().map(|v| Point2::from(*v)).collect();
    SharedShape::convex_hull(&points)
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
        let solids = objects
            .iter()
            .map(|(body, _)| Solid::of(body))
            .collect::<Option<Vec<_>>>()?;
        let pusher = match pusher {
            Some((footprint, pose, mu_c)) => Some((shape(footprint)?, pose, mu_c)),
            None => None,
        };
        Some(World::build(
            solids.iter().zip(objects.iter().map(|(_, pose)| pose)),
            pusher,
        ))
    }

    /// The world of solids at their poses and a pusher (its shape, pose and friction).
    fn build<'a>(
        objects: impl Iterator<Item = (&'a Solid, &'a Pose2)>,
        pusher: Option<(SharedShape, Pose2, f64)>,
    ) -> World {
        let mut bodies = RigidBodySet::new();
        let mut colliders = ColliderSet::new();
        let mut handles = Vec::new();
        for (solid, pose) in objects {
            let handle = bodies.insert(
                RigidBodyBuilder::dynamic()
                    .pose(isometry(pose))
                    .can_sleep(false),
            );
            let collider = ColliderBuilder::new(solid.shape.clone())
                .mass(solid.mass)
                .friction(solid.mu_c)
                .restitution(0.0);
            colliders.insert_with_parent(collider, handle, &mut bodies);
            let inertia = bodies[handle]
                .mass_properties()
                .local_mprops
                .principal_inertia();
            handles.push((
                handle,
                Support {
                    force: solid.force,
                    c: solid.c,
                    mass: solid.mass,
                    inertia,
                },
            ));
        }
        let pusher = pusher.map(|(shape, pose, mu_c)| {
            let handle =
                bodies.insert(RigidBodyBuilder::kinematic_position_based().pose(isometry(&pose)));
            let collider = ColliderBuilder::new(shape)
                .friction(mu_c)
                .friction_combine_rule(CoefficientCombineRule::Max)
                .restitution(0.0);
            colliders.insert_with_parent(collider, handle, &mut bodies);
            handle
        });
        World {
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
        }
    }

    /// Adds a fixed obstacle: the convex hull of `outline` (world x, y; m). Objects meet it
    /// with their own contact friction. `None` for an outline without area.
    pub fn add_obstacle(&mut self, outline: &[Vector2<f64>]) -> Option<()> {
        self.add_fixed(hull(outline)?);
        Some(())
    }

    fn add_fixed(&mut self, shape: SharedShape) {
        let collider = ColliderBuilder::new(shape)
            .friction(0.0)
            .friction_combine_rule(CoefficientCombineRule::Max)
            .restitution(0.0);
        self.colliders.insert(collider);
    }

    /// Moves the pusher at `velocity` for `duration` seconds, then holds it still.
    pub fn push(&mut self, velocity: PusherVelocity, duration: f64) {
        let Some(pusher) = self.pusher else { return };
        let p = self.bodies[pusher].position();
        let from = Pose2::new(p.translation.x, p.translation.y, p.rotation.angle());
        let to = Pose2::new(
            from.x + velocity.vx * duration,
            from.y + velocity.vy * duration,
            from.theta + velocity.omega * duration,
        );
        self.move_pusher(&from, &to, duration);
    }

    /// Moves the pusher from `from` to `to` (its yaw unwrapped) at constant speed over
    /// `duration` seconds, ending exactly at `to`: in engine steps of at most [`STEP`]
    /// that divide the duration, so that the pusher's speed is the one asked for.
    pub fn move_pusher(&mut self, from: &Pose2, to: &Pose2, duration: f64) {
        let Some(pusher) = self.pusher else { return };
        let steps = (duration / STEP).ceil().max(1.0) as usize;
        self.params.dt = duration / steps as f64;
        for k in 1..=steps {
            let f = k as f64 / steps as f64;
            let at = Pose2::new(
                from.x + f * (to.x - from.x),
                from.y + f * (to.y - from.y),
                from.theta + f * (to.theta - from.theta),
            );
            self.bodies[pusher].set_next_kinematic_position(isometry(&at));
            self.step();
        }
        self.params.dt = STEP;
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

    /// Advances the world by one engine step ([`STEP`], or less while the pusher moves),
    /// support friction acting half before and half after it.
    pub fn step(&mut self) {
        let dt = self.params.dt;
        self.support_friction(dt / 2.0);
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
        self.support_friction(dt / 2.0);
        self.time += dt;
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

/// The semi-dynamic transition of a scene's objects under a planar pusher: the world is
/// rebuilt from the state for every step (so a step from a stored state is reproduced
/// exactly), the pusher moves, and the objects come to rest.
#[derive(Clone)]
pub struct Transition {
    solids: Vec<Solid>,
    pusher: SharedShape,
    /// Obstacles' outlines in the world, as fixed shapes.
    obstacles: Vec<SharedShape>,
    rest: RestSettings,
}

impl Transition {
    /// The scene's objects as bodies, the pusher's footprint (in its link frame) and the
    /// outlines of the obstacles the objects can meet (world frame; one without area is
    /// left out). `None` if a body's or the pusher's footprint has no area.
    pub fn new(
        bodies: &[Body],
        pusher: &Footprint,
        obstacles: &[Vec<Vector2<f64>>],
        rest: RestSettings,
    ) -> Option<Transition> {
        Some(Transition {
            solids: bodies.iter().map(Solid::of).collect::<Option<_>>()?,
            pusher: shape(pusher)?,
            obstacles: obstacles.iter().filter_map(|o| hull(o)).collect(),
            rest,
        })
    }

    /// The objects' poses after the pusher moves from `from` to `to` in `dt` seconds and
    /// everything comes to rest, or the object still moving at `t_max`.
    pub fn step(
        &self,
        objects: &[Pose2],
        from: &Pose2,
        to: &Pose2,
        dt: f64,
    ) -> Result<Vec<Pose2>, Unsettled> {
        // The pusher's friction combines as the larger with each object's mu_c: an
        // object's contact friction is the object's.
        let mut world = World::build(
            self.solids.iter().zip(objects),
            Some((self.pusher.clone(), *from, 0.0)),
        );
        for obstacle in &self.obstacles {
            world.add_fixed(obstacle.clone());
        }
        let mut to = *to;
        to.theta = from.theta + crate::math::wrap_angle(to.theta - from.theta);
        world.move_pusher(from, &to, dt);
        world.settle(&self.rest)?;
        Ok((0..objects.len()).map(|i| world.pose(i)).collect())
    }
}
