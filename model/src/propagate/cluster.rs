//! One quasistatic step where pushed objects push others (`physics.object_pushing`).
//!
//! The cluster is every object the arm touches and, transitively, every object within
//! `contact_margin` of a member; its motion is one complementarity problem
//! ([`cluster_motion`]). Forces between objects act along vertical contact lines from the
//! table up, so when a pushed object starts to tip they settle at its foot: they add no
//! tipping moment (only the arm's forces, now larger, do).

#![allow(non_snake_case)] // frame-named quantities: v_WO, the origin's velocity in the world

use super::{keeps_flat, no_link_closes_in, Contact, Propagator};
use crate::contact::{
    by_object, object_pair_contacts, planar_contacts, ObjectContacts, ObjectPairContact,
};
use crate::math::{Pose2, Twist2};
use crate::physics::tipping::{pusher_forces, support_balance};
use crate::physics::{
    cluster_motion, ClusterContact, ClusterMotion, LimitSurface, ObjectMotion, Pusher, PusherForce,
};
use crate::state::State;
use crate::validity::Invalid;
use std::sync::Arc;

/// The objects of a cluster and the contacts between them.
#[derive(Default)]
pub(super) struct Cluster {
    /// Scene indices of the members: those the arm touches first, in the order of its
    /// contacts.
    members: Vec<usize>,
    pairs: Vec<ObjectPairContact>,
}

impl Cluster {
    fn member(&self, object: usize) -> usize {
        self.members
            .iter()
            .position(|&m| m == object)
            .expect("a member")
    }
}

/// An arm-touched member's contacts and where they sit among the cluster's contacts.
struct ArmPushes {
    object: usize,
    contacts: ObjectContacts,
    first: usize,
}

impl Propagator {
    /// The cluster of the objects the arm touches in the prepared state; `None` when no
    /// two of its objects are within `contact_margin` of each other (each pushed object
    /// moves alone).
    pub(super) fn find_cluster(&mut self, state: &State) -> Option<Cluster> {
        let scene = &*self.scene;
        let mut cluster = Cluster::default();
        for c in &self.contacts {
            if !cluster.members.contains(&c.object) {
                cluster.members.push(c.object);
            }
        }
        let mut scratch = Vec::new();
        let mut found = Vec::new();
        let mut k = 0;
        while k < cluster.members.len() {
            found.clear();
            let from = cluster.members[k];
            let margin = scene.physics.contact_margin;
            object_pair_contacts(
                scene,
                &state.objects,
                from,
                margin,
                &mut scratch,
                &mut found,
            );
            for c in &found {
                match cluster.members.iter().position(|&m| m == c.into) {
                    Some(earlier) if earlier < k => continue, // found from its side
                    Some(_) => {}
                    None => cluster.members.push(c.into),
                }
                cluster.pairs.push(*c);
            }
            k += 1;
        }
        (!cluster.pairs.is_empty()).then_some(cluster)
    }

    /// Moves the cluster's objects one step (into `objects_new`, `object_boxes_new`,
    /// `moved`), checking that the table keeps each pushed object flat. Returns the links'
    /// pushes.
    pub(super) fn push_cluster(
        &mut self,
        state: &State,
        cluster: &Cluster,
    ) -> Result<Vec<Contact>, Invalid> {
        let scene = Arc::clone(&self.scene);
        let scene = &*scene;
        let dt = self.dt;

        // The arm's contacts, per touched member, in the world frame.
        let mut arm = Vec::new();
        let mut contacts = Vec::new();
        for (object, run) in by_object(&self.contacts) {
            let pose = state.objects[object];
            let mut planar = ObjectContacts::default();
            planar_contacts(
                &self.contacts[run],
                &pose,
                scene.table.top,
                &self.poses,
                &self.poses_new,
                dt,
                &mut planar,
            );
            let (body, mu) = (cluster.member(object), scene.objects[object].mu_c);
            let first = contacts.len();
            contacts.extend(planar.planar.iter().map(|c| ClusterContact {
                body,
                pusher: Pusher::Moving(pose.vector_to_world(c.pusher_velocity)),
                point: pose.point_to_world(c.point),
                normal: pose.vector_to_world(c.normal),
                gap: c.gap,
                mu,
            }));
            arm.push(ArmPushes {
                object,
                contacts: planar,
                first,
            });
        }
        // Between objects: friction the mean of the two surfaces' (rapier's rule too).
        contacts.extend(cluster.pairs.iter().map(|p| ClusterContact {
            body: cluster.member(p.into),
            pusher: Pusher::Body(cluster.member(p.from)),
            point: p.point,
            normal: p.normal,
            gap: p.gap,
            mu: 0.5 * (scene.objects[p.from].mu_c + scene.objects[p.into].mu_c),
        }));

        // Limit surfaces with their centres of friction in the world frame.
        let in_world = |object: usize, surface: LimitSurface| LimitSurface {
            centre: state.objects[object].point_to_world(surface.centre),
            ..surface
        };
        let mut surfaces: Vec<LimitSurface> = cluster
            .members
            .iter()
            .map(|&o| in_world(o, scene.objects[o].limit_surface))
            .collect();
        let jammed = |_| Invalid::Jammed {
            object: scene.objects[cluster.members[0]].name.clone(),
        };
        let mut motion = cluster_motion(&surfaces, &contacts, dt).map_err(jammed)?;
        if scene.physics.pressure_shift {
            // As for one object: the centre of friction follows the centre of pressure
            // the arm's pushes load; one re-solve.
            let mut shifted = false;
            for (member, push) in arm.iter().enumerate() {
                let body = &scene.objects[push.object];
                let balance = support_balance(
                    body.mass,
                    body.footprint.centroid(),
                    &self.arm_forces(push, &motion),
                );
                if motion.twists[member] != nalgebra::Vector3::zeros()
                    && balance.stays_flat(&body.footprint, 0.0)
                {
                    surfaces[member] = in_world(push.object, body.loaded_surface(&balance));
                    shifted = true;
                }
            }
            if shifted {
                motion = cluster_motion(&surfaces, &contacts, dt).map_err(jammed)?;
            }
        }

        let mut pushes = Vec::new();
        for (member, push) in arm.iter().enumerate() {
            let body = &scene.objects[push.object];
            let forces = self.arm_forces(push, &motion);
            let balance = support_balance(body.mass, body.footprint.centroid(), &forces);
            if motion.twists[member] != nalgebra::Vector3::zeros() {
                keeps_flat(scene, push.object, &push.contacts, &balance, &forces)?;
            }
            let normal_forces = &motion.normal_forces[push.first..][..push.contacts.planar.len()];
            no_link_closes_in(scene, push.object, &push.contacts, normal_forces)?;
            for (&link, &force) in push.contacts.links.iter().zip(normal_forces) {
                super::record_push(&mut pushes, link, push.object, force);
            }
        }

        for (member, &object) in cluster.members.iter().enumerate() {
            let v = motion.twists[member];
            if v == nalgebra::Vector3::zeros() {
                continue;
            }
            let pose = state.objects[object];
            // The origin moves at v_C + omega z x (p_WO - p_WC); integrate in the body frame.
            let v_WO = motion.point_velocity(member, surfaces[member].centre, pose.translation());
            let v_O = pose.vector_to_local(v_WO);
            let twist = Twist2 {
                vx: v_O.x,
                vy: v_O.y,
                omega: v.z,
            };
            let moved: Pose2 = pose.integrate(&twist, dt);
            self.objects_new[object] = moved;
            self.object_boxes_new[object] = scene.objects[object]
                .geometry
                .aabb(&moved.to_isometry(scene.table.top));
            self.moved[object] = true;
        }
        Ok(pushes)
    }

    /// The arm's forces on a touched member (object frame, heights above the table).
    fn arm_forces(&self, push: &ArmPushes, motion: &ClusterMotion) -> Vec<PusherForce> {
        let n = push.contacts.planar.len();
        let object_motion = ObjectMotion {
            twist: Twist2::ZERO,
            normal_forces: motion.normal_forces[push.first..][..n].to_vec(),
            friction_forces: motion.friction_forces[push.first..][..n].to_vec(),
        };
        let mut forces = Vec::new();
        pusher_forces(
            &push.contacts.planar,
            &push.contacts.elevations,
            &object_motion,
            &mut forces,
        );
        forces
    }
}
