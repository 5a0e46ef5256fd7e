//! State validity (Sec. II-A): which states are in `X_free`.
//!
//! A state is invalid when a joint is outside its limits, the arm collides with itself
//! (adjacent links excluded), with the table or with a static obstacle, penetrates an
//! object beyond the tolerance, presses on top of an object (a near-vertical contact
//! normal), when two objects overlap, an object overlaps an obstacle, or an object's
//! centre leaves the table (it would fall). Arm-object *contact* is allowed: that is how
//! the robot pushes.

use crate::collision::footprint;
use crate::collision::query::{intersects, overlaps_beyond, signed_distance};
use crate::collision::Geometry;
use crate::contact::{find_arm_contacts, object_bounds, ArmBounds, ArmContact};
use crate::math::Pose2;
use crate::robot::ProjectionFailure;
use crate::scene::{MovableObject, Scene};
use crate::state::State;
use nalgebra::{DVector, Isometry3};
use parry3d_f64::bounding_volume::Aabb;
use std::fmt;

/// Why a state is invalid. Names are the scene's link, object and obstacle names.
#[derive(Clone, Debug, PartialEq)]
pub enum Invalid {
    /// A joint is outside its limits.
    JointLimit {
        /// The joint's name.
        joint: String,
        /// Its value (rad or m).
        value: f64,
    },
    /// The step could not be projected onto the pushing plane.
    Projection(ProjectionFailure),
    /// Two links collide.
    SelfCollision {
        /// One link.
        link_a: String,
        /// The other.
        link_b: String,
    },
    /// A link collides with the table.
    ArmHitsTable {
        /// The link.
        link: String,
    },
    /// A link collides with an obstacle.
    ArmHitsObstacle {
        /// The link.
        link: String,
        /// The obstacle.
        obstacle: String,
    },
    /// A link sinks into an object deeper than the overlap tolerance.
    ArmPenetratesObject {
        /// The link.
        link: String,
        /// The object.
        object: String,
        /// How deep (m).
        depth: f64,
    },
    /// A link presses down on an object's top (the planar model cannot push from above).
    PressesOnTop {
        /// The link.
        link: String,
        /// The object.
        object: String,
    },
    /// Two objects overlap.
    ObjectsOverlap {
        /// One object.
        object_a: String,
        /// The other.
        object_b: String,
    },
    /// A moving object came closer to another object or an obstacle than the clearance
    /// (`physics.object_clearance`, or the pair's distance at the start when smaller).
    TooClose {
        /// The moving object.
        object: String,
        /// The object or obstacle it came close to.
        other: String,
        /// Their distance (m).
        distance: f64,
    },
    /// An object collides with an obstacle.
    ObjectHitsObstacle {
        /// The object.
        object: String,
        /// The obstacle.
        obstacle: String,
    },
    /// An object's footprint is not wholly on the table, or comes closer to its edge
    /// than `physics.edge_clearance` (from a start observed in the world: hangs further
    /// over than it did there and than its support allows,
    /// `Clearances::with_start_overhangs`).
    ObjectOffTable {
        /// The object.
        object: String,
        /// How far its footprint reaches past the table's edge (m, [`Table::overhang`];
        /// negative: minus its least distance from an edge).
        ///
        /// [`Table::overhang`]: crate::scene::Table::overhang
        overhang: f64,
    },
    /// An object is squeezed between pushers: no motion satisfies every contact.
    Jammed {
        /// The object.
        object: String,
    },
    /// The pushers' forces would tip the object over (its support pressure would leave
    /// the footprint); `link` pushes with the largest tipping moment.
    Tips {
        /// The object.
        object: String,
        /// The link.
        link: String,
    },
    /// A link closes in on an object closer than `physics.arm_clearance` (m) at a height
    /// where a push that slides the object would tip it.
    ClosesInAtTippingHeight {
        /// The link.
        link: String,
        /// The object.
        object: String,
        /// Their distance (m).
        distance: f64,
    },
    /// Semi-dynamic model: an object still moves `physics.t_max` after the step, at
    /// `speed` (m/s).
    Unsettled {
        /// The fastest object.
        object: String,
        /// Its speed (m/s).
        speed: f64,
    },
    /// A grasp goal whose object must stay where it starts (`goal.object_may_move: false`):
    /// a push moved it.
    MovesObjectToGrasp {
        /// The object.
        object: String,
    },
}

impl Invalid {
    /// The rule broken, without the names and numbers (to count reasons).
    pub fn kind(&self) -> &'static str {
        match self {
            Invalid::JointLimit { .. } => "joint limit",
            Invalid::Projection(ProjectionFailure::JointTooFast { .. }) => "singular step",
            Invalid::Projection(ProjectionFailure::OffPlane { .. }) => "tool off its plane",
            Invalid::Projection(ProjectionFailure::NotFinite) => "not finite",
            Invalid::SelfCollision { .. } => "self-collision",
            Invalid::ArmHitsTable { .. } => "arm hits table",
            Invalid::ArmHitsObstacle { .. } => "arm hits obstacle",
            Invalid::ArmPenetratesObject { .. } => "arm penetrates object",
            Invalid::PressesOnTop { .. } => "presses on top",
            Invalid::ObjectsOverlap { .. } => "objects overlap",
            Invalid::TooClose { .. } => "objects too close",
            Invalid::ObjectHitsObstacle { .. } => "object hits obstacle",
            Invalid::ObjectOffTable { .. } => "object off table",
            Invalid::Jammed { .. } => "jammed",
            Invalid::Tips { .. } => "tips",
            Invalid::ClosesInAtTippingHeight { .. } => "closes in at tipping height",
            Invalid::Unsettled { .. } => "does not come to rest",
            Invalid::MovesObjectToGrasp { .. } => "moves the object to grasp",
        }
    }
}

impl fmt::Display for Invalid {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Invalid::JointLimit { joint, value } => {
                write!(f, "joint '{joint}' at {value:.4} is outside its limits")
            }
            Invalid::Projection(p) => write!(f, "projection failed: {p}"),
            Invalid::SelfCollision { link_a, link_b } => {
                write!(f, "links '{link_a}' and '{link_b}' collide")
            }
            Invalid::ArmHitsTable { link } => write!(f, "link '{link}' hits the table"),
            Invalid::ArmHitsObstacle { link, obstacle } => {
                write!(f, "link '{link}' hits obstacle '{obstacle}'")
            }
            Invalid::ArmPenetratesObject {
                link,
                object,
                depth,
            } => {
                write!(
                    f,
                    "link '{link}' penetrates object '{object}' by {:.1} mm",
                    depth * 1e3
                )
            }
            Invalid::PressesOnTop { link, object } => {
                write!(f, "link '{link}' presses on top of object '{object}'")
            }
            Invalid::ObjectsOverlap { object_a, object_b } => {
                write!(f, "objects '{object_a}' and '{object_b}' overlap")
            }
            Invalid::TooClose {
                object,
                other,
                distance,
            } => write!(
                f,
                "object '{object}' passes {:.1} mm from '{other}', closer than the clearance",
                distance * 1e3
            ),
            Invalid::ObjectHitsObstacle { object, obstacle } => {
                write!(f, "object '{object}' overlaps obstacle '{obstacle}'")
            }
            Invalid::ObjectOffTable { object, overhang } if *overhang > 0.0 => {
                let mm = overhang * 1e3;
                write!(f, "object '{object}' reaches {mm:.1} mm past the table's edge")
            }
            Invalid::ObjectOffTable { object, overhang } => {
                let mm = -overhang * 1e3;
                write!(
                    f,
                    "object '{object}' comes {mm:.1} mm from the table's edge, closer than the clearance"
                )
            }
            Invalid::Jammed { object } => write!(f, "object '{object}' is jammed between pushers"),
            Invalid::Tips { object, link } => {
                write!(f, "link '{link}' would tip object '{object}' over")
            }
            Invalid::ClosesInAtTippingHeight {
                link,
                object,
                distance,
            } => write!(
                f,
                "link '{link}' closes in on object '{object}' ({:.1} mm) where a sliding push would tip it",
                distance * 1e3
            ),
            Invalid::Unsettled { object, speed } => write!(
                f,
                "object '{object}' still moves at {:.3} m/s when physics.t_max has passed",
                speed
            ),
            Invalid::MovesObjectToGrasp { object } => write!(
                f,
                "object '{object}' is to be grasped where it stands (goal.object_may_move is false) and was pushed"
            ),
        }
    }
}

impl std::error::Error for Invalid {}

/// Checks every validity rule for `state`.
pub fn check_state(scene: &Scene, state: &State) -> Result<(), Invalid> {
    let (poses, bounds) = check_arm(scene, &state.q)?;
    let mut contacts = Vec::new();
    let mut boxes = Vec::new();
    object_bounds(scene, &state.objects, &mut boxes);
    check_arm_objects(
        scene,
        &poses,
        &bounds,
        &state.objects,
        &boxes,
        &mut contacts,
    )?;
    check_objects(scene, &state.objects, |_| true)
}

/// The arm alone at `q` ([`check_robot`]); its link poses (world) and bounds if valid,
/// for the checks against objects.
pub fn check_arm(
    scene: &Scene,
    q: &DVector<f64>,
) -> Result<(Vec<Isometry3<f64>>, ArmBounds), Invalid> {
    let poses = scene.robot.link_poses(q);
    let mut bounds = ArmBounds::default();
    ArmBounds::compute(scene, &poses, &mut bounds);
    check_robot(scene, q, &poses, &bounds)?;
    Ok((poses, bounds))
}

/// Joint limits, self-collision, table and obstacles.
pub fn check_robot(
    scene: &Scene,
    q: &DVector<f64>,
    poses: &[Isometry3<f64>],
    bounds: &ArmBounds,
) -> Result<(), Invalid> {
    let robot = &scene.robot;
    let chain = &robot.chain;
    if let Err(i) = chain.within_limits(q) {
        return Err(Invalid::JointLimit {
            joint: chain.dof_joint(i).name.clone(),
            value: q[i],
        });
    }
    let link_name = |l: usize| chain.links[l].name.clone();
    use parry3d_f64::bounding_volume::BoundingVolume;
    for &(a, b) in &robot.self_collision_pairs {
        let (Some(ba), Some(bb)) = (bounds.of(a), bounds.of(b)) else {
            continue;
        };
        if ba.intersects(bb) && chain.links_intersect(poses, a, b) {
            return Err(Invalid::SelfCollision {
                link_a: link_name(a),
                link_b: link_name(b),
            });
        }
    }
    let identity = Isometry3::identity();
    let table_box = scene.table.geometry.aabb(&identity);
    for (link, aabb) in &bounds.links {
        let shapes = &chain.links[*link].geometry;
        if !scene.allowed.link_table(*link)
            && aabb.intersects(&table_box)
            && shapes
                .iter()
                .any(|g| intersects(g, &poses[*link], &scene.table.geometry, &identity))
        {
            return Err(Invalid::ArmHitsTable {
                link: link_name(*link),
            });
        }
        for (o, obstacle) in scene.obstacles.iter().enumerate() {
            if !scene.allowed.link_obstacle(*link, o)
                && aabb.intersects(&obstacle.geometry.aabb(&obstacle.pose))
                && shapes
                    .iter()
                    .any(|g| intersects(g, &poses[*link], &obstacle.geometry, &obstacle.pose))
            {
                return Err(Invalid::ArmHitsObstacle {
                    link: link_name(*link),
                    obstacle: obstacle.name.clone(),
                });
            }
        }
    }
    Ok(())
}

/// Finds the arm-object contacts within the contact margin (objects' bounding boxes in
/// `object_boxes`) (written to `contacts`, for
/// the physics of the next step) and rejects penetration and pressing on top.
pub fn check_arm_objects(
    scene: &Scene,
    poses: &[Isometry3<f64>],
    bounds: &ArmBounds,
    objects: &[Pose2],
    object_boxes: &[Aabb],
    contacts: &mut Vec<ArmContact>,
) -> Result<(), Invalid> {
    contacts.clear();
    find_arm_contacts(
        scene,
        poses,
        bounds,
        objects,
        object_boxes,
        scene.physics.contact_margin,
        contacts,
    );
    check_arm_contacts(scene, contacts)
}

/// Rejects penetration beyond the tolerance and pressing on top among `contacts`.
pub fn check_arm_contacts(scene: &Scene, contacts: &[ArmContact]) -> Result<(), Invalid> {
    let names = |c: &ArmContact| {
        (
            scene.robot.chain.links[c.link].name.clone(),
            scene.objects[c.object].name.clone(),
        )
    };
    let vertical = scene.physics.vertical_normal_angle.cos();
    for c in contacts.iter() {
        if c.point.distance < -scene.physics.penetration_tolerance {
            let (link, object) = names(c);
            return Err(Invalid::ArmPenetratesObject {
                link,
                object,
                depth: -c.point.distance,
            });
        }
        // Touching (within a millimetre) with a near-vertical normal.
        if c.point.distance <= 1e-3 && c.point.normal_a.z.abs() > vertical {
            let (link, object) = names(c);
            return Err(Invalid::PressesOnTop { link, object });
        }
    }
    Ok(())
}

/// Objects on the table, apart from each other and from obstacles, and no closer to them
/// than the clearance; a grasp goal's object that must stay put where it starts. Only
/// pairs with at least one object for which `moved` is true are checked.
pub fn check_objects(
    scene: &Scene,
    objects: &[Pose2],
    moved: impl Fn(usize) -> bool,
) -> Result<(), Invalid> {
    let top = scene.table.top;
    for (i, pose) in objects.iter().enumerate() {
        if !moved(i) {
            continue;
        }
        let object = &scene.objects[i];
        if !scene
            .clearances
            .on_table(&scene.table, i, &object.footprint, pose)
        {
            return Err(Invalid::ObjectOffTable {
                object: object.name.clone(),
                overhang: scene.table.overhang(&object.footprint, pose),
            });
        }
        for (j, other_pose) in objects.iter().enumerate() {
            if j == i || (j < i && moved(j)) {
                continue; // itself, or a pair already checked
            }
            let other = &scene.objects[j];
            let clearance = scene.clearances.between_objects(i, j);
            let reach = object.bounding_radius + other.bounding_radius + clearance.max(0.0);
            if (pose.translation() - other_pose.translation()).norm() >= reach {
                continue;
            }
            // Upright prisms on one table: their footprints decide, exactly.
            let gap = footprint::gap(&object.footprint, pose, &other.footprint, other_pose);
            keep_apart(
                separation_of_gap(scene, gap, clearance),
                object,
                &other.name,
                || Invalid::ObjectsOverlap {
                    object_a: object.name.clone(),
                    object_b: other.name.clone(),
                },
            )?;
        }
        let iso = pose.to_isometry(top);
        for (k, obstacle) in scene.obstacles.iter().enumerate() {
            let clearance = scene.clearances.to_obstacle(i, k);
            keep_apart(
                separation(
                    scene,
                    &object.geometry,
                    &iso,
                    &obstacle.geometry,
                    &obstacle.pose,
                    clearance,
                ),
                object,
                &obstacle.name,
                || Invalid::ObjectHitsObstacle {
                    object: object.name.clone(),
                    obstacle: obstacle.name.clone(),
                },
            )?;
        }
    }
    if let Some(i) = scene.goal.pinned_object() {
        if moved(i) && objects[i] != scene.start.objects[i] {
            return Err(Invalid::MovesObjectToGrasp {
                object: scene.objects[i].name.clone(),
            });
        }
    }
    Ok(())
}

/// `object` must not overlap the other solid, named `other` (`overlap` says how that is
/// reported), nor come closer to it than the clearance `separation` was measured against.
fn keep_apart(
    separation: Separation,
    object: &MovableObject,
    other: &str,
    overlap: impl FnOnce() -> Invalid,
) -> Result<(), Invalid> {
    match separation {
        Separation::Overlap => Err(overlap()),
        Separation::TooClose(distance) => Err(Invalid::TooClose {
            object: object.name.clone(),
            other: other.to_string(),
            distance,
        }),
        Separation::Clear => Ok(()),
    }
}

/// How two solids stand to each other, measured against a clearance.
enum Separation {
    /// Overlapping beyond `physics.overlap_tolerance`.
    Overlap,
    /// Closer than the clearance (m apart, negative when overlapping within tolerance).
    TooClose(f64),
    Clear,
}

/// Numerical slack on the clearance (m): a pair held at its start distance may wobble by
/// rounding.
const CLEARANCE_SLACK: f64 = 1e-7;

fn separation(
    scene: &Scene,
    a: &Geometry,
    pose_a: &Isometry3<f64>,
    b: &Geometry,
    pose_b: &Isometry3<f64>,
    clearance: f64,
) -> Separation {
    let tolerance = scene.physics.overlap_tolerance;
    if clearance <= -tolerance {
        return if overlaps_beyond(a, pose_a, b, pose_b, tolerance) {
            Separation::Overlap
        } else {
            Separation::Clear
        };
    }
    match signed_distance(a, pose_a, b, pose_b, clearance.max(0.0)) {
        Some(d) => separation_of_gap(scene, d, clearance),
        None => Separation::Clear,
    }
}

/// How two solids `gap` apart (m, negative overlapping) stand, measured against a
/// clearance.
fn separation_of_gap(scene: &Scene, gap: f64, clearance: f64) -> Separation {
    if gap < -scene.physics.overlap_tolerance {
        Separation::Overlap
    } else if gap < clearance - CLEARANCE_SLACK {
        Separation::TooClose(gap)
    } else {
        Separation::Clear
    }
}
