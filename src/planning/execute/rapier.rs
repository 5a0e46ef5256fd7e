//! rapier as the 3D world of an execution, with the arm's links as kinematic
//! bodies, the objects as free dynamic bodies (mass, support friction `mu_g` against the
//! table, contact friction `mu_c` against the arm) and the table and obstacles fixed.
//!
//! Frames: world `W` with z up. An object's body frame is its planar frame lifted onto
//! the table top (`Pose2::to_isometry`), so its planar pose is read straight back. The
//! prism stands on small feet spread over its footprint ([`support_points`]).

use super::engine::{Engine, STEP};
use super::fresh_contacts::FreshContacts;
use super::FALLEN_DROP;
use crate::math::Pose2;
use crate::physics::Footprint;
use crate::scene::Scene;
use nalgebra::{Isometry3, Vector2, Vector3};
use rapier3d_f64::prelude::*;

/// How hard rapier's solver works per step. Pushes with several contacts at once (a
/// face against a face, a box squeezed between two links) need more than one
/// Gauss-Seidel sweep per iteration: with one, the outcome of a turning hand's push
/// changed by a radian when the iterations were doubled; with four it changes by less
/// than doubling them again does (`tests/integration/execute.rs`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolverSettings {
    /// Solver iterations (substeps) per step.
    pub iterations: usize,
    /// Projected Gauss-Seidel sweeps per iteration.
    pub pgs_iterations: usize,
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            iterations: 8,
            pgs_iterations: 4,
        }
    }
}

/// Radius of an object's feet (m): the prism stands this much above the table on them.
pub const FOOT_RADIUS: f64 = 5e-4;
/// Feet along each axis of the footprint's bounding box (at the cells' centres).
const FEET_PER_SIDE: usize = 7;
/// Feet on a disc's rim.
const RIM_FEET: usize = 12;

/// Where an object stands on the table: the centres of a grid of cells over its footprint,
/// and its corners (a polygon) or twelve points on its rim (a disc), so that it tips
/// about its edges (object frame, m). Their mean distance from the centroid is within
/// 12 % of the uniform-pressure characteristic length. A solid prism on a plane gets contact points at its
/// corners only, which resists turning as if all the weight sat there; evenly spread
/// feet carry the uniform pressure the planar model assumes, so the support's friction
/// is the same physical assumption in both, computed independently. A scene that gives
/// the characteristic length `c` (a bowl loaded on its rim) gets the feet drawn in or
/// out about the centroid so that their mean distance from it is `c` (the footprint's
/// edge at most).
pub fn support_points(footprint: &Footprint, c: f64) -> Vec<Vector2<f64>> {
    let points = uniform_support(footprint);
    if (c / footprint.characteristic_length() - 1.0).abs() < 1e-6 {
        return points;
    }
    let centroid = footprint.centroid();
    let mean = points.iter().map(|p| (p - centroid).norm()).sum::<f64>() / points.len() as f64;
    let scale = c / mean;
    // Scaled about the centroid; where that leaves the footprint, a ring of radius c (a
    // disc) or the corners (a polygon).
    let scaled: Vec<Vector2<f64>> = points
        .iter()
        .map(|p| centroid + (p - centroid) * scale)
        .collect();
    if scaled.iter().all(|p| footprint.contains(*p)) {
        scaled
    } else {
        match footprint {
            Footprint::Circle { radius } => ring(c.min(*radius), RIM_FEET),
            Footprint::Polygon { vertices } => vertices.clone(),
        }
    }
}

fn ring(radius: f64, count: usize) -> Vec<Vector2<f64>> {
    (0..count)
        .map(|k| {
            let angle = std::f64::consts::TAU * k as f64 / count as f64;
            Vector2::new(angle.cos(), angle.sin()) * radius
        })
        .collect()
}

fn uniform_support(footprint: &Footprint) -> Vec<Vector2<f64>> {
    let n = FEET_PER_SIDE;
    let grid = |half_x: f64, half_y: f64| {
        (0..n).flat_map(move |a| {
            (0..n).map(move |b| {
                let f = |k: usize| (2 * k + 1) as f64 / n as f64 - 1.0;
                Vector2::new(half_x * f(a), half_y * f(b))
            })
        })
    };
    match footprint {
        Footprint::Circle { radius } => {
            let mut points: Vec<Vector2<f64>> = grid(*radius, *radius)
                .filter(|p| p.norm() < *radius)
                .collect();
            points.extend(ring(*radius, RIM_FEET));
            points
        }
        Footprint::Polygon { vertices } => {
            let (lo, hi) = vertices.iter().fold(
                (
                    Vector2::repeat(f64::INFINITY),
                    Vector2::repeat(f64::NEG_INFINITY),
                ),
                |(lo, hi), v| (lo.inf(v), hi.sup(v)),
            );
            let centre = (lo + hi) / 2.0;
            let half = (hi - lo) / 2.0;
            let mut points: Vec<Vector2<f64>> = grid(half.x, half.y)
                .map(|p| p + centre)
                .filter(|p| footprint.contains(*p))
                .collect();
            for v in vertices {
                if !points.contains(v) {
                    points.push(*v);
                }
            }
            points
        }
    }
}

/// What a collider is, stored in its `user_data`.
const STATIC: u128 = 0;
const ARM: u128 = 1;
/// Object `i` is `OBJECT + i`.
const OBJECT: u128 = 2;

/// Per-pair friction: rapier combines one coefficient per collider, but an object has
/// two (against the table and against the arm), so the solver contacts are set here.
struct Friction {
    mu_g: Vec<f64>,
    mu_c: Vec<f64>,
}

impl PhysicsHooks for Friction {
    fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
        let role = |h: ColliderHandle| context.colliders[h].user_data;
        let (a, b) = (role(context.collider1), role(context.collider2));
        let object = |r: u128| (r >= OBJECT).then(|| (r - OBJECT) as usize);
        let friction = match (object(a), object(b)) {
            // Two objects: the mean of their contact frictions.
            (Some(i), Some(j)) => 0.5 * (self.mu_c[i] + self.mu_c[j]),
            (Some(i), None) | (None, Some(i)) => {
                if a == ARM || b == ARM {
                    self.mu_c[i]
                } else {
                    self.mu_g[i]
                }
            }
            (None, None) => return,
        };
        for contact in context.solver_contacts.iter_mut() {
            contact.friction = friction;
            contact.restitution = 0.0;
        }
    }
}

/// The rapier world of one execution.
pub struct RapierWorld {
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
    friction: Friction,
    /// (link index, body) of every solid link.
    links: Vec<(usize, RigidBodyHandle)>,
    /// Object bodies and their colliders, in scene order.
    objects: Vec<(RigidBodyHandle, ColliderHandle)>,
    /// Height of the table top (m, world z).
    table_top: f64,
}

impl RapierWorld {
    /// The scene's table, obstacles and objects (at `objects`, the start poses), and the
    /// arm's links at `link_poses` (`X_WL`, one per chain link).
    pub fn new(scene: &Scene, objects: &[Pose2], link_poses: &[Isometry3<f64>]) -> RapierWorld {
        RapierWorld::with_solver(scene, objects, link_poses, &SolverSettings::default())
    }

    /// As [`RapierWorld::new`], with the given solver effort.
    pub fn with_solver(
        scene: &Scene,
        objects: &[Pose2],
        link_poses: &[Isometry3<f64>],
        solver: &SolverSettings,
    ) -> RapierWorld {
        let mut bodies = RigidBodySet::new();
        let mut colliders = ColliderSet::new();
        let fixed = bodies.insert(RigidBodyBuilder::fixed());
        let table = ColliderBuilder::new(scene.table.geometry.shape.clone())
            .position(scene.table.geometry.local)
            .user_data(STATIC);
        colliders.insert_with_parent(table, fixed, &mut bodies);
        for obstacle in &scene.obstacles {
            let collider = ColliderBuilder::new(obstacle.geometry.shape.clone())
                .position(obstacle.geometry.world_pose(&obstacle.pose))
                .user_data(STATIC);
            colliders.insert_with_parent(collider, fixed, &mut bodies);
        }
        let mut links = Vec::new();
        for link in scene.robot.solid_links() {
            let body =
                bodies.insert(RigidBodyBuilder::kinematic_position_based().pose(link_poses[link]));
            for g in &scene.robot.chain.links[link].geometry {
                let collider = ColliderBuilder::new(g.shape.clone())
                    .position(g.local)
                    .user_data(ARM);
                colliders.insert_with_parent(collider, body, &mut bodies);
            }
            links.push((link, body));
        }
        let mut object_bodies = Vec::new();
        for (i, (object, pose)) in scene.objects.iter().zip(objects).enumerate() {
            let body = bodies.insert(
                RigidBodyBuilder::dynamic()
                    .pose(pose.to_isometry(scene.table.top))
                    .can_sleep(false),
            );
            // The prism, raised by the feet's height, carries the mass.
            let raised = Isometry3::translation(0.0, 0.0, FOOT_RADIUS) * object.geometry.local;
            let collider = ColliderBuilder::new(object.geometry.shape.clone())
                .position(raised)
                .mass(object.mass)
                .user_data(OBJECT + i as u128)
                .active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS);
            let handle = colliders.insert_with_parent(collider, body, &mut bodies);
            for p in support_points(&object.footprint, object.limit_surface.c) {
                let foot = ColliderBuilder::ball(FOOT_RADIUS)
                    .translation(Vector3::new(p.x, p.y, FOOT_RADIUS))
                    .density(0.0)
                    .user_data(OBJECT + i as u128)
                    .active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS);
                colliders.insert_with_parent(foot, body, &mut bodies);
            }
            object_bodies.push((body, handle));
        }
        let params = IntegrationParameters {
            dt: STEP,
            num_solver_iterations: solver.iterations,
            num_internal_pgs_iterations: solver.pgs_iterations,
            // Coulomb's friction at every contact point. Rapier's default, "simplified",
            // gives each contact manifold one friction constraint and a twist constraint
            // that resists turning up to `mu sum(lambda_i d_i)` whether or not the body
            // slides: a box whose face rests on the table beside its feet was then held
            // from turning (scene 32's first push: 0.2 rad where MuJoCo and the model
            // turn it 0.4 rad, and the box 37 mm from MuJoCo's).
            friction_model: FrictionModel::Coulomb,
            ..IntegrationParameters::default()
        };
        RapierWorld {
            pipeline: PhysicsPipeline::new(),
            params,
            islands: IslandManager::new(),
            broad_phase: BroadPhaseBvh::new(),
            narrow_phase: NarrowPhase::with_query_dispatcher(FreshContacts),
            bodies,
            colliders,
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            ccd: CCDSolver::new(),
            friction: Friction {
                mu_g: scene.objects.iter().map(|o| o.mu_g).collect(),
                mu_c: scene.objects.iter().map(|o| o.mu_c).collect(),
            },
            links,
            objects: object_bodies,
            table_top: scene.table.top,
        }
    }
}

impl Engine for RapierWorld {
    fn move_arm(&mut self, link_poses: &[Isometry3<f64>]) {
        for (link, body) in &self.links {
            self.bodies[*body].set_next_kinematic_position(link_poses[*link]);
        }
    }

    fn step(&mut self) {
        self.pipeline.step(
            &Vector3::new(0.0, 0.0, -crate::physics::limit_surface::GRAVITY),
            &self.params,
            &mut self.islands,
            &mut self.broad_phase,
            &mut self.narrow_phase,
            &mut self.bodies,
            &mut self.colliders,
            &mut self.impulse_joints,
            &mut self.multibody_joints,
            &mut self.ccd,
            &self.friction,
            &(),
        );
    }

    fn object_pose(&self, i: usize) -> Isometry3<f64> {
        *self.bodies[self.objects[i].0].position()
    }

    /// Its base is more than [`FALLEN_DROP`] below the table top.
    fn object_fell_off(&self, i: usize) -> bool {
        self.object_pose(i).translation.z < self.table_top - FALLEN_DROP
    }

    fn set_object_velocity(&mut self, i: usize, v: Vector3<f64>) {
        let body = &mut self.bodies[self.objects[i].0];
        body.set_linvel(v, true);
        body.set_angvel(Vector3::zeros(), true);
    }

    fn object_velocity(&self, i: usize) -> Vector3<f64> {
        *self.bodies[self.objects[i].0].linvel()
    }

    fn touching_objects(&self) -> Option<(usize, usize)> {
        for (i, (_, a)) in self.objects.iter().enumerate() {
            for (j, (_, b)) in self.objects.iter().enumerate().skip(i + 1) {
                if self
                    .narrow_phase
                    .contact_pair(*a, *b)
                    .is_some_and(|p| p.has_any_active_contact)
                {
                    return Some((i, j));
                }
            }
        }
        None
    }
}
