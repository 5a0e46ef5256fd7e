//! Arm-object contacts: the broad phase, the 3D contact manifolds between links and
//! objects, and their reduction to the planar contacts of the pushing model
//! (`physics.md`, "Whole-arm contact in 3D").

use crate::collision::footprint::{self, FootprintContact};
use crate::collision::geometry::union_aabb;
use crate::collision::query::{contact_points, ContactPoint};
use crate::math::Pose2;
use crate::physics::{sliding_push_tips, ContactElevation, PlanarContact};
use crate::scene::MovableObject;
use crate::scene::Scene;
use nalgebra::{Isometry3, Vector2};
use parry3d_f64::bounding_volume::{Aabb, BoundingVolume};
use std::ops::Range;

/// One contact point between a link and an object, world frame.
#[derive(Clone, Copy, Debug)]
pub struct ArmContact {
    /// Index of the link in the robot's chain.
    pub link: usize,
    /// Index of the object in the scene.
    pub object: usize,
    /// `point_a` on the object, `point_b` on the link, normal out of the object.
    pub point: ContactPoint,
}

/// Bounding boxes of the robot's solid links at one configuration (the broad phase).
#[derive(Clone, Debug, Default)]
pub struct ArmBounds {
    /// Each solid link's index and world bounding box.
    pub links: Vec<(usize, Aabb)>,
    /// Box around the whole arm.
    pub all: Option<Aabb>,
    /// Per link of the robot, fixed from the first computation on (empty before it).
    layout: Vec<LinkSlot>,
}

/// Where a link's box stands in [`ArmBounds::links`] (None: no geometry), and the box
/// itself if the link never moves (a base column: no planning joint between it and the
/// root).
#[derive(Clone, Copy, Debug, Default)]
struct LinkSlot {
    index: Option<usize>,
    still: Option<Aabb>,
}

impl ArmBounds {
    /// The boxes at link poses `poses` (world frame), for `scene`'s robot: one `ArmBounds`
    /// serves one robot.
    pub fn compute(scene: &Scene, poses: &[Isometry3<f64>], out: &mut ArmBounds) {
        let chain = &scene.robot.chain;
        let link_box = |link: usize| {
            union_aabb(&chain.links[link].geometry, &poses[link])
                .expect("solid links have geometry")
        };
        if out.layout.is_empty() {
            out.layout = vec![LinkSlot::default(); chain.links.len()];
            for (index, link) in scene.robot.solid_links().enumerate() {
                out.layout[link] = LinkSlot {
                    index: Some(index),
                    still: (!chain.moves_with_configuration(link)).then(|| link_box(link)),
                };
            }
        }
        out.links.clear();
        out.all = None;
        for link in scene.robot.solid_links() {
            let aabb = out.layout[link].still.unwrap_or_else(|| link_box(link));
            out.all = Some(out.all.map_or(aabb, |a: Aabb| a.merged(&aabb)));
            out.links.push((link, aabb));
        }
    }

    /// The box of `link`, if it has geometry.
    pub fn of(&self, link: usize) -> Option<&Aabb> {
        let index = self.layout.get(link)?.index?;
        self.links.get(index).map(|(_, aabb)| aabb)
    }
}

/// World bounding box of each object at its pose (the objects' side of the broad phase).
pub fn object_bounds(scene: &Scene, objects: &[Pose2], out: &mut Vec<Aabb>) {
    out.clear();
    out.extend(
        scene
            .objects
            .iter()
            .zip(objects)
            .map(|(o, pose)| o.geometry.aabb(&pose.to_isometry(scene.table.top))),
    );
}

/// Appends every link-object contact point closer than `margin` (m), object by object.
/// `object_boxes` are the objects' bounding boxes ([`object_bounds`]).
pub fn find_arm_contacts(
    scene: &Scene,
    poses: &[Isometry3<f64>],
    bounds: &ArmBounds,
    objects: &[Pose2],
    object_boxes: &[Aabb],
    margin: f64,
    out: &mut Vec<ArmContact>,
) {
    let Some(all) = bounds.all.map(|a| a.loosened(margin)) else {
        return;
    };
    let mut points = Vec::new();
    for (index, object_box) in object_boxes.iter().enumerate() {
        if !all.intersects(object_box) {
            continue;
        }
        let object = &scene.objects[index];
        let object_pose = objects[index].to_isometry(scene.table.top);
        for (link, link_box) in &bounds.links {
            if !link_box.loosened(margin).intersects(object_box) {
                continue;
            }
            for g in &scene.robot.chain.links[*link].geometry {
                points.clear();
                contact_points(
                    &object.geometry,
                    &object_pose,
                    g,
                    &poses[*link],
                    margin,
                    &mut points,
                );
                out.extend(points.iter().map(|&point| ArmContact {
                    link: *link,
                    object: index,
                    point,
                }));
            }
        }
    }
}

/// Every link-object contact point closer than `margin` (m) with the objects at
/// `objects`, object by object: their bounding boxes ([`object_bounds`]) and
/// [`find_arm_contacts`] in one call, for a single query (a loop that queries again keeps
/// its buffers and calls those two).
pub fn arm_contacts(
    scene: &Scene,
    poses: &[Isometry3<f64>],
    bounds: &ArmBounds,
    objects: &[Pose2],
    margin: f64,
) -> Vec<ArmContact> {
    let (mut boxes, mut contacts) = (Vec::new(), Vec::new());
    object_bounds(scene, objects, &mut boxes);
    find_arm_contacts(scene, poses, bounds, objects, &boxes, margin, &mut contacts);
    contacts
}

/// The runs of `contacts` (grouped by object, as [`find_arm_contacts`] appends them) that
/// touch one object: the object and the run's index range.
pub fn by_object(contacts: &[ArmContact]) -> impl Iterator<Item = (usize, Range<usize>)> + '_ {
    let mut start = 0;
    std::iter::from_fn(move || {
        let object = contacts.get(start)?.object;
        let end = start
            + contacts[start..]
                .iter()
                .take_while(|c| c.object == object)
                .count();
        let run = (object, start..end);
        start = end;
        Some(run)
    })
}

/// Reduces one object's 3D contacts to planar contacts in the object frame.
///
/// The normal is the horizontal part of the 3D normal (renormalised, pointing into the
/// object); the pusher velocity is the horizontal displacement over the step of the link's
/// material point at the contact, divided by `dt`. Points closer than 1 mm with the same
/// normal (the stacked corners of a face contact, seen from above) are merged,
/// keeping the lowest height (the tipping check's point of application). Each contact
/// also gets its gap at the step's end, were the object still: the gap plus the link
/// point's displacement along the 3D normal (first order; exact for a flat face).
pub fn planar_contacts(
    contacts: &[ArmContact],
    pose: &Pose2,
    table_top: f64,
    poses: &[Isometry3<f64>],
    poses_new: &[Isometry3<f64>],
    dt: f64,
    out: &mut ObjectContacts,
) {
    out.clear();
    for c in contacts {
        let n = c.point.normal_a;
        let horizontal = Vector2::new(-n.x, -n.y);
        let length = horizontal.norm();
        let p = c.point.point_b;
        // p_W moved with the link: X_WL(q_new) X_WL(q)^-1 p_W.
        let moved = poses_new[c.link] * (poses[c.link].inverse() * p);
        let v = (moved - p) / dt;
        // n points out of the object, at the link: moving against it closes the gap.
        let gap_at_end = c.point.distance + (moved - p).dot(&n);
        let elevation = ContactElevation {
            height: c.point.point_a.z - table_top,
            slope: 0.0,
        };
        if length < 1e-6 {
            // Vertical: outside the planar model (the validity check rejects a touch).
            // A link passing over the top would push the way it moves, were the object
            // a little elsewhere.
            let speed = v.xy().norm();
            if speed > 1e-9 {
                out.passing_over.push(PassingOver {
                    link: c.link,
                    contact: PlanarContact {
                        point: pose.point_to_local(c.point.point_a.xy().coords),
                        normal: pose.vector_to_local(v.xy() / speed),
                        pusher_velocity: pose.vector_to_local(v.xy()),
                        gap: c.point.distance,
                    },
                    elevation,
                    gap_at_end,
                });
            }
            continue;
        }
        let contact = PlanarContact {
            point: pose.point_to_local(c.point.point_a.xy().coords),
            normal: pose.vector_to_local(horizontal / length),
            pusher_velocity: pose.vector_to_local(v.xy()),
            gap: c.point.distance,
        };
        let elevation = ContactElevation {
            slope: n.z / length,
            ..elevation
        };
        let duplicate = out.planar.iter().position(|o| {
            (o.point - contact.point).norm() < 1e-3 && o.normal.dot(&contact.normal) > 0.99
        });
        match duplicate {
            Some(i) => {
                let lowest = out.elevations[i].height.min(elevation.height);
                if contact.gap < out.planar[i].gap {
                    out.planar[i] = contact;
                    out.links[i] = c.link;
                    out.elevations[i].slope = elevation.slope;
                }
                out.elevations[i].height = lowest;
                out.gaps_at_end[i] = out.gaps_at_end[i].min(gap_at_end);
            }
            None => {
                out.planar.push(contact);
                out.links.push(c.link);
                out.elevations.push(elevation);
                out.gaps_at_end.push(gap_at_end);
            }
        }
    }
}

/// A contact between two objects seen from above, world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectPairContact {
    /// The object the normal points out of, and the one it points into.
    pub from: usize,
    /// The object the normal points into.
    pub into: usize,
    /// Midpoint of the two surface points (m).
    pub point: Vector2<f64>,
    /// Horizontal unit normal from `from` into `into`.
    pub normal: Vector2<f64>,
    /// Distance between the surfaces (m); negative when overlapping.
    pub gap: f64,
}

/// Appends the contacts of object `from` with every other object closer than `margin`
/// (m): upright prisms on one table touch along vertical lines, so each contact is a
/// point seen from above, between their footprints ([`footprint::contacts`]).
pub fn object_pair_contacts(
    scene: &Scene,
    objects: &[Pose2],
    from: usize,
    margin: f64,
    scratch: &mut Vec<FootprintContact>,
    out: &mut Vec<ObjectPairContact>,
) {
    let object = &scene.objects[from];
    for (into, other) in scene.objects.iter().enumerate() {
        let reach = object.bounding_radius + other.bounding_radius + margin;
        if into == from
            || (objects[from].translation() - objects[into].translation()).norm() >= reach
        {
            continue;
        }
        scratch.clear();
        footprint::contacts(
            &object.footprint,
            &objects[from],
            &other.footprint,
            &objects[into],
            margin,
            scratch,
        );
        out.extend(scratch.iter().map(|c| ObjectPairContact {
            from,
            into,
            point: (c.point_a + c.point_b) / 2.0,
            normal: c.normal,
            gap: c.gap,
        }));
    }
}

/// One object's planar contacts, with the link and the 3D elevation of each.
#[derive(Clone, Debug, Default)]
pub struct ObjectContacts {
    /// The contacts as the planar pushing problem takes them (object frame).
    pub planar: Vec<PlanarContact>,
    /// The link of each contact.
    pub links: Vec<usize>,
    /// Where each contact lies in 3D (its height on the object).
    pub elevations: Vec<ContactElevation>,
    /// Per planar contact: its gap at the step's end were the object still (m).
    pub gaps_at_end: Vec<f64>,
    /// Links passing over the object's top (vertical normals).
    pub passing_over: Vec<PassingOver>,
}

/// A link passing over an object's top (a vertical normal): outside the planar model,
/// but were the object a little elsewhere the link would push the way it moves.
#[derive(Clone, Debug)]
pub struct PassingOver {
    /// The link.
    pub link: usize,
    /// The contact, its normal the way the link moves (object frame).
    pub contact: PlanarContact,
    /// Its height on the object.
    pub elevation: ContactElevation,
    /// Its gap at the step's end were the object still (m).
    pub gap_at_end: f64,
}

impl ObjectContacts {
    fn clear(&mut self) {
        self.planar.clear();
        self.links.clear();
        self.elevations.clear();
        self.gaps_at_end.clear();
        self.passing_over.clear();
    }

    /// The first link that comes closer than `clearance` (m) to the object during the
    /// step, closing in where a push that slid it would tip it ([`sliding_push_tips`],
    /// `margin` as in the tipping balance): a planar contact that does not push
    /// (`normal_forces[i] <= 0`) with the link moving into the object, or a link passing
    /// over its top. The gap is read at both ends of the step (at the end as if the object
    /// stood still, as "closing in" takes it), so the rule is the same for a step of any
    /// length: a fast step that stops inside the clearance is refused as a slow one is.
    /// Returns the link and the smaller of the two gaps (m).
    pub fn closing_in_at_tipping_height(
        &self,
        object: &MovableObject,
        normal_forces: &[f64],
        clearance: f64,
        margin: f64,
    ) -> Option<(usize, f64)> {
        let planar = self
            .planar
            .iter()
            .zip(&self.links)
            .zip(&self.elevations)
            .zip(&self.gaps_at_end)
            .zip(normal_forces)
            .filter(|((((c, _), _), _), &force)| {
                force <= 0.0 && c.pusher_velocity.dot(&c.normal) > 0.0
            })
            .map(|((((c, &link), e), &end), _)| (link, c, e, c.gap.min(end)));
        let over = self.passing_over.iter().map(|o| {
            (
                o.link,
                &o.contact,
                &o.elevation,
                o.contact.gap.min(o.gap_at_end),
            )
        });
        planar
            .chain(over)
            .find(|&(_, c, e, closest)| {
                clearance > 0.0
                    && closest < clearance
                    && sliding_push_tips(object.mass, object.mu_g, &object.footprint, c, e, margin)
            })
            .map(|(link, _, _, closest)| (link, closest.max(0.0)))
    }
}
