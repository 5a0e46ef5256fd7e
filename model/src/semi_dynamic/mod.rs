//! The workshop paper's semi-dynamic transition function (issue 14): the table seen from
//! above as a 2D rigid-body world (rapier2d), objects as dynamic bodies that may be
//! struck, slide, push one another and coast, pushers as kinematic bodies. An action moves
//! the pushers for its duration; then the world runs on with them still until every object
//! rests, or the state is invalid after `t_max`. States stay
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
//! Pushers are kinematic bodies: each link's cut at the objects' heights ([`sweep`]; the
//! planar hand's is its outline). Objects of different heights are kept in height classes,
//! and a link's cut for a class meets only that class's objects, so that a forearm above a
//! short can still pushes a tall bottle. Obstacles are fixed outlines: what an obstacle
//! covers of the objects' height range, seen from above.
//!
//! Frames: world x, y on the table (m); yaw about world z (rad).

use crate::math::Pose2;
use crate::physics::limit_surface::GRAVITY;
use crate::physics::Footprint;
use nalgebra::{Isometry2, Point2, Vector2};
use rapier2d_f64::prelude::*;

pub mod sweep;
pub use sweep::{Sweep, Sweeps};

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
    /// Footprint in the object frame (m).
    pub footprint: Footprint,
    /// kg
    pub mass: f64,
    /// Support friction against the table, and contact friction against others.
    pub mu_g: f64,
    /// Friction coefficient against other bodies (objects and pushers).
    pub mu_c: f64,
}

/// Objects still moving `t_max` after the action: the state is invalid.
#[derive(Clone, Debug, PartialEq)]
pub struct Unsettled {
    /// The fastest object and its speed (m/s) when time ran out.
    pub object: usize,
    /// Its speed (m/s).
    pub speed: f64,
}

/// A pusher's motion: planar velocity in the world frame (m/s, m/s, rad/s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PusherVelocity {
    /// Velocity along world x (m/s).
    pub vx: f64,
    /// Velocity along world y (m/s).
    pub vy: f64,
    /// Turn rate about z (rad/s).
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
    /// Kinematic pushers and their colliders.
    pushers: Vec<(RigidBodyHandle, ColliderHandle)>,
    /// Normal impulse each pusher has given each object so far, `[pusher][object]`: its
    /// magnitude summed over the steps (N s), and the sum of its vectors on the object
    /// (N s, world frame).
    impulses: Vec<Vec<(f64, Vector2<f64>)>>,
    /// Every step's time and object poses, when recording ([`World::record`]).
    trace: Option<Vec<TracePoint>>,
    /// Seconds simulated.
    time: f64,
}

/// The objects' poses at a time (s since the world was built).
#[derive(Clone, Debug, PartialEq)]
pub struct TracePoint {
    /// Seconds since the world was built.
    pub time: f64,
    /// Every object's pose then, in the scene's order.
    pub poses: Vec<Pose2>,
}

/// A pusher to put in a world: its collider's shape (in its frame), its pose, its contact
/// friction, and the height class of the objects it meets (`None`: every object).
struct PusherBody {
    shape: SharedShape,
    pose: Pose2,
    mu_c: f64,
    class: Option<usize>,
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

fn pose2(isometry: &Isometry2<f64>) -> Pose2 {
    Pose2::new(
        isometry.translation.x,
        isometry.translation.y,
        isometry.rotation.angle(),
    )
}

/// Interaction groups: an object of height class `c` is in group `c` and meets everything;
/// a pusher of class `c` meets group `c` only. Pushers and fixed obstacles never meet
/// (rapier skips kinematic-fixed pairs).
fn object_groups(class: usize) -> InteractionGroups {
    InteractionGroups::new(Group::from_bits_retain(1 << class), Group::ALL)
}

fn pusher_groups(class: Option<usize>) -> InteractionGroups {
    match class {
        Some(c) => InteractionGroups::new(
            Group::from_bits_retain(1 << c),
            Group::from_bits_retain(1 << c),
        ),
        None => InteractionGroups::all(),
    }
}

/// Height classes a world tells apart (rapier's interaction groups have 32 bits).
pub const MAX_CLASSES: usize = 32;

impl World {
    /// Objects at `poses`, and a pusher of footprint `pusher` at its pose with its
    /// contact friction, if any. `None` if a footprint has no area.
    pub fn new(
        objects: &[(Body, Pose2)],
        pusher: Option<(&Footprint, Pose2, f64)>,
    ) -> Option<World> {
        let solids = objects
            .iter()
            .map(|(body, _)| Solid::of(body))
            .collect::<Option<Vec<_>>>()?;
        let pushers = match pusher {
            Some((footprint, pose, mu_c)) => vec![PusherBody {
                shape: shape(footprint)?,
                pose,
                mu_c,
                class: None,
            }],
            None => vec![],
        };
        Some(World::build(
            solids
                .iter()
                .zip(objects.iter().map(|(_, pose)| pose))
                .map(|(solid, pose)| (solid, pose, 0)),
            pushers,
        ))
    }

    /// The world of solids at their poses (with their height classes) and pushers.
    fn build<'a>(
        objects: impl Iterator<Item = (&'a Solid, &'a Pose2, usize)>,
        pushers: Vec<PusherBody>,
    ) -> World {
        let mut bodies = RigidBodySet::new();
        let mut colliders = ColliderSet::new();
        let mut handles = Vec::new();
        for (i, (solid, pose, class)) in objects.enumerate() {
            let handle = bodies.insert(
                RigidBodyBuilder::dynamic()
                    .pose(isometry(pose))
                    .can_sleep(false),
            );
            let collider = ColliderBuilder::new(solid.shape.clone())
                .mass(solid.mass)
                .friction(solid.mu_c)
                .restitution(0.0)
                .collision_groups(object_groups(class))
                .user_data(i as u128 + 1);
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
        let pushers: Vec<_> = pushers
            .into_iter()
            .map(|p| {
                let handle = bodies
                    .insert(RigidBodyBuilder::kinematic_position_based().pose(isometry(&p.pose)));
                // The larger of the pusher's and each object's contact friction.
                let collider = ColliderBuilder::new(p.shape)
                    .friction(p.mu_c)
                    .friction_combine_rule(CoefficientCombineRule::Max)
                    .restitution(0.0)
                    .collision_groups(pusher_groups(p.class));
                let collider = colliders.insert_with_parent(collider, handle, &mut bodies);
                (handle, collider)
            })
            .collect();
        World {
            pipeline: PhysicsPipeline::new(),
            params: IntegrationParameters {
                dt: STEP,
                ..IntegrationParameters::default()
            },
            islands: IslandManager::new(),
            broad_phase: BroadPhaseBvh::new(),
            narrow_phase: NarrowPhase::new(),
            impulses: vec![vec![(0.0, Vector2::zeros()); handles.len()]; pushers.len()],
            bodies,
            colliders,
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            ccd: CCDSolver::new(),
            objects: handles,
            pushers,
            trace: None,
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

    /// From now on, records the objects' poses after every step ([`World::trace`]), and
    /// now.
    pub fn record(&mut self) {
        self.trace = Some(vec![self.trace_point()]);
    }

    /// The recorded poses (empty unless [`World::record`] was called).
    pub fn trace(&self) -> &[TracePoint] {
        self.trace.as_deref().unwrap_or(&[])
    }

    fn trace_point(&self) -> TracePoint {
        TracePoint {
            time: self.time,
            poses: (0..self.objects.len()).map(|i| self.pose(i)).collect(),
        }
    }

    /// Moves the (first) pusher at `velocity` for `duration` seconds, then holds it still.
    pub fn push(&mut self, velocity: PusherVelocity, duration: f64) {
        let Some(&(pusher, _)) = self.pushers.first() else {
            return;
        };
        let from = pose2(self.bodies[pusher].position());
        let to = Pose2::new(
            from.x + velocity.vx * duration,
            from.y + velocity.vy * duration,
            from.theta + velocity.omega * duration,
        );
        self.move_pushers(&[(from, to)], duration);
    }

    /// Moves each pusher from its `from` to its `to` (yaw unwrapped) at constant speed
    /// over `duration` seconds, ending exactly at `to`: in engine steps of at most
    /// [`STEP`] that divide the duration, so that every pusher has the speed asked for.
    pub fn move_pushers(&mut self, motions: &[(Pose2, Pose2)], duration: f64) {
        let steps = (duration / STEP).ceil().max(1.0) as usize;
        self.params.dt = duration / steps as f64;
        for k in 1..=steps {
            let f = k as f64 / steps as f64;
            for (&(pusher, _), (from, to)) in self.pushers.iter().zip(motions) {
                let at = Pose2::new(
                    from.x + f * (to.x - from.x),
                    from.y + f * (to.y - from.y),
                    from.theta + f * (to.theta - from.theta),
                );
                self.bodies[pusher].set_next_kinematic_position(isometry(&at));
            }
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

    /// Advances the world by one engine step ([`STEP`], or less while pushers move),
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
        self.add_pusher_impulses();
        if let Some(mut trace) = self.trace.take() {
            trace.push(self.trace_point());
            self.trace = Some(trace);
        }
    }

    /// Adds this step's normal impulses between pushers and objects.
    fn add_pusher_impulses(&mut self) {
        for (p, &(_, collider)) in self.pushers.iter().enumerate() {
            for pair in self.narrow_phase.contact_pairs_with(collider) {
                // Manifold normals point from collider 1 to collider 2, and the impulse
                // pushes collider 2 along them.
                let (other, on_other) = if pair.collider1 == collider {
                    (pair.collider2, pair.total_impulse())
                } else {
                    (pair.collider1, -pair.total_impulse())
                };
                let Some(object) = self.colliders.get(other).map(|c| c.user_data) else {
                    continue;
                };
                if object > 0 {
                    let sum = &mut self.impulses[p][object as usize - 1];
                    sum.0 += pair.total_impulse_magnitude();
                    sum.1 += on_other;
                }
            }
        }
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
        pose2(self.bodies[self.objects[i].0].position())
    }

    /// The normal impulse (N s) pusher `p` has given object `i` so far.
    pub fn impulse(&self, p: usize, i: usize) -> f64 {
        self.impulses[p][i].0
    }

    /// The sum of the impulses pusher `p` has given object `i` so far (N s, world frame).
    pub fn impulse_vector(&self, p: usize, i: usize) -> Vector2<f64> {
        self.impulses[p][i].1
    }

    /// Seconds simulated so far.
    pub fn time(&self) -> f64 {
        self.time
    }
}

/// A pusher pressing on an object during a transition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Push {
    /// Index of the [`Sweep`] that pushed.
    pub pusher: usize,
    /// The object it pushed.
    pub object: usize,
    /// Normal impulse over the whole transition (N s).
    pub impulse: f64,
    /// The way it pushed: the unit direction of the summed impulse on the object (world
    /// frame; zero if the impulses cancel).
    pub direction: Vector2<f64>,
}

/// Where a transition leaves the objects.
#[derive(Clone, Debug, PartialEq)]
pub struct Rest {
    /// The objects' poses at rest.
    pub poses: Vec<Pose2>,
    /// How long they took to come to rest after the pushers stopped (s).
    pub settle_time: f64,
    /// Which pushers pressed on which objects.
    pub pushes: Vec<Push>,
    /// The objects' poses at every engine step (when asked for), from the start.
    pub trace: Vec<TracePoint>,
}

/// The semi-dynamic transition of a scene's objects under kinematic pushers: the world is
/// rebuilt from the state for every step (so a step from a stored state is reproduced
/// exactly), the pushers move, and the objects come to rest.
#[derive(Clone)]
pub struct Transition {
    solids: Vec<Solid>,
    /// Each object's height class (see [`Sweeps`]).
    classes: Vec<usize>,
    /// Obstacles' outlines in the world, as fixed shapes.
    obstacles: Vec<SharedShape>,
    rest: RestSettings,
}

impl Transition {
    /// The scene's objects as bodies with their height classes (below [`MAX_CLASSES`]),
    /// and the outlines of the obstacles the objects can meet (world frame; one without
    /// area is left out). `None` if a body's footprint has no area.
    pub fn new(
        bodies: &[Body],
        classes: &[usize],
        obstacles: &[Vec<Vector2<f64>>],
        rest: RestSettings,
    ) -> Option<Transition> {
        Some(Transition {
            solids: bodies.iter().map(Solid::of).collect::<Option<_>>()?,
            classes: classes.to_vec(),
            obstacles: obstacles.iter().filter_map(|o| hull(o)).collect(),
            rest,
        })
    }

    /// The objects' poses after the pushers sweep for `dt` seconds and everything comes
    /// to rest, or the object still moving at `t_max`. With `record`, the poses at every
    /// engine step too.
    pub fn step(
        &self,
        objects: &[Pose2],
        sweeps: &[Sweep],
        dt: f64,
        record: bool,
    ) -> Result<Rest, Unsettled> {
        // The pushers' friction combines as the larger with each object's mu_c: an
        // object's contact friction is the object's.
        let pushers = sweeps
            .iter()
            .map(|s| PusherBody {
                shape: s.shape.clone(),
                pose: s.from,
                mu_c: 0.0,
                class: Some(s.class),
            })
            .collect();
        let objects_in = self
            .solids
            .iter()
            .zip(objects)
            .zip(&self.classes)
            .map(|((solid, pose), &class)| (solid, pose, class));
        let mut world = World::build(objects_in, pushers);
        for obstacle in &self.obstacles {
            world.add_fixed(obstacle.clone());
        }
        if record {
            world.record();
        }
        // A sweep's frame starts at yaw 0 and turns by less than a half turn: its yaws
        // need no unwrapping.
        let motions: Vec<(Pose2, Pose2)> = sweeps.iter().map(|s| (s.from, s.to)).collect();
        world.move_pushers(&motions, dt);
        let settle_time = world.settle(&self.rest)?;
        let pushes = (0..sweeps.len())
            .flat_map(|p| (0..objects.len()).map(move |i| (p, i)))
            .filter(|&(p, i)| world.impulse(p, i) > 0.0)
            .map(|(pusher, object)| Push {
                pusher,
                object,
                impulse: world.impulse(pusher, object),
                direction: world
                    .impulse_vector(pusher, object)
                    .try_normalize(1e-12)
                    .unwrap_or_else(Vector2::zeros),
            })
            .collect();
        Ok(Rest {
            poses: (0..objects.len()).map(|i| world.pose(i)).collect(),
            settle_time,
            pushes,
            trace: world.trace.take().unwrap_or_default(),
        })
    }
}
