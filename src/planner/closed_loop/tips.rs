//! Objects that start to tip, and tip, in a trial's world: when, and what touched them.
//!
//! The closed loop cannot be replayed bit for bit (its searches run on the clock), so a
//! trial keeps, for every object that starts to tip, the world then and the links the
//! model's geometry has at it: where a push the planner never meant to make began.

use super::observe;
use crate::contact::{arm_contacts, object_pair_contacts, ArmBounds};
use crate::planning::execute::{Engine, TIPPED_TILT};
use crate::planning::observed::ObservedState;
use crate::scene::Scene;
use crate::state::State;
use nalgebra::DVector;
use serde::Serialize;

/// Tilt beyond which an object in a trial's world is taken to be starting to tip (rad,
/// about 1.1 degrees): an object pushed below its tipping height rocks on its support by
/// a few thousandths of a radian at most, and one that tipped in MuJoCo had passed 0.03
/// two controls before it reached [`TIPPED_TILT`] (BENCHMARKS.md, "Dense scenes, closed
/// loop").
pub const TILT_ONSET: f64 = 0.02;

/// How far from an object a link is named as touching it where it starts to tip (m): the
/// world's object stands tilted, the model's upright at its planar pose, which moves a
/// point `z` above the table by about `z` times the tilt (2 mm at 0.1 m), and the arm's
/// clearance at tipping height is 0.01 m by default.
pub const TOUCH_DISTANCE: f64 = 0.01;

/// An object starting to tip in a trial's world: the first step it tilted beyond
/// [`TILT_ONSET`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TiltOnset {
    /// The object's name.
    pub object: String,
    /// The control playing then (counted from 1 among the controls played, as
    /// [`super::ClosedLoopTrial::tipped_during`]), or the last played while the world
    /// settled.
    pub control: usize,
    /// Its tilt then (rad).
    pub tilt: f64,
    /// The world then, in `replan --observed`'s format: the arm's joints as driven and
    /// every object's planar pose. `check` and `replan` on it say what the model makes of
    /// the contacts there.
    pub world: ObservedState,
    /// The links within [`TOUCH_DISTANCE`] of the object in that world, in the model's
    /// geometry (the object upright at its planar pose), nearest first.
    pub touching: Vec<TiltTouch>,
    /// The other objects within [`TOUCH_DISTANCE`] of it then, nearest first: an object
    /// pushed into a neighbour, or pushed by one, tips at other heights than alone.
    pub neighbours: Vec<TiltNeighbour>,
}

/// A link at an object where it started to tip, in the model's geometry.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TiltTouch {
    /// The link's name.
    pub link: String,
    /// Their signed distance (m; negative: the link overlaps the upright object).
    pub distance: f64,
    /// Height above the table top of the object's point nearest the link (m): compare
    /// it with the object's tipping height r / `mu_g`.
    pub height: f64,
}

/// An object beside one that started to tip, in the model's geometry.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TiltNeighbour {
    /// The neighbour's name.
    pub object: String,
    /// The gap between their footprints (m; negative: overlapping).
    pub gap: f64,
}

/// Which objects have started to tip and tipped in a trial's world, and when.
pub(super) struct Tips {
    /// Per object, the control during or after which it first tilted beyond
    /// [`TIPPED_TILT`] (counted from 1 among the controls played).
    pub(super) first: Vec<Option<usize>>,
    /// The objects that tilted beyond [`TILT_ONSET`], in order, each once: the object,
    /// the control, its tilt and the world's state then.
    onsets: Vec<(usize, usize, f64, State)>,
    /// The control playing, or the last played while the world settles.
    pub(super) control: usize,
}

impl Tips {
    /// No object tipped or tilting yet among `objects`.
    pub(super) fn new(objects: usize) -> Tips {
        Tips {
            first: vec![None; objects],
            onsets: Vec::new(),
            control: 0,
        }
    }

    /// Notes the objects that tilt beyond [`TILT_ONSET`] or [`TIPPED_TILT`] now for the
    /// first time, the arm at `q`.
    pub(super) fn note(&mut self, world: &dyn Engine, q: &DVector<f64>) {
        let objects = self.first.len();
        for i in 0..objects {
            let tilt = world.object_tilt(i);
            if tilt > TILT_ONSET && !self.onsets.iter().any(|(o, ..)| *o == i) {
                self.onsets
                    .push((i, self.control, tilt, observe(world, q, objects)));
            }
            if self.first[i].is_none() && tilt > TIPPED_TILT {
                self.first[i] = Some(self.control);
            }
        }
    }

    /// The onsets by name, the worlds in `replan --observed`'s format.
    pub(super) fn onsets(&self, scene: &Scene) -> Vec<TiltOnset> {
        self.onsets
            .iter()
            .map(|(i, control, tilt, state)| TiltOnset {
                object: scene.objects[*i].name.clone(),
                control: *control,
                tilt: *tilt,
                world: ObservedState::of(scene, state),
                touching: touching(scene, state, *i),
                neighbours: neighbours(scene, state, *i),
            })
            .collect()
    }
}

/// The links within [`TOUCH_DISTANCE`] of `object` in `state`, each at its nearest
/// contact point, nearest first.
fn touching(scene: &Scene, state: &State, object: usize) -> Vec<TiltTouch> {
    let poses = scene.robot.link_poses(&state.q);
    let mut bounds = ArmBounds::default();
    ArmBounds::compute(scene, &poses, &mut bounds);
    let contacts = arm_contacts(scene, &poses, &bounds, &state.objects, TOUCH_DISTANCE);
    let touches = contacts
        .iter()
        .filter(|c| c.object == object)
        .map(|c| TiltTouch {
            link: scene.robot.chain.links[c.link].name.clone(),
            distance: c.point.distance,
            height: c.point.point_a.z - scene.table.top,
        });
    nearest_of_each(touches, |t| (&t.link, t.distance))
}

/// The objects within [`TOUCH_DISTANCE`] of `object` in `state`, nearest first (upright
/// prisms on one table: their footprints' gap).
fn neighbours(scene: &Scene, state: &State, object: usize) -> Vec<TiltNeighbour> {
    let (mut scratch, mut contacts) = (Vec::new(), Vec::new());
    object_pair_contacts(
        scene,
        &state.objects,
        object,
        TOUCH_DISTANCE,
        &mut scratch,
        &mut contacts,
    );
    let near = contacts.iter().map(|c| TiltNeighbour {
        object: scene.objects[c.into].name.clone(),
        gap: c.gap,
    });
    nearest_of_each(near, |n| (&n.object, n.gap))
}

/// The nearest of `items` per name, nearest first: `by` gives an item's name and
/// distance. Of equally near items of one name, the first is kept.
fn nearest_of_each<T>(items: impl Iterator<Item = T>, by: impl Fn(&T) -> (&String, f64)) -> Vec<T> {
    let mut items: Vec<T> = items.collect();
    // A stable sort: the first of equals stays first.
    items.sort_by(|a, b| by(a).1.total_cmp(&by(b).1));
    let mut seen = std::collections::BTreeSet::new();
    items.retain(|item| seen.insert(by(item).0.clone()));
    items
}

#[cfg(test)]
mod tests {
    use super::{neighbours, touching};
    use crate::scene::Scene;
    use std::path::Path;

    /// The planar hand (a disc 5 mm in radius, 8 mm tall, centred 0.05 m above the
    /// table) at `hand_x` on the x axis, and three boxes 0.1 m square: `a` with its near
    /// face at x = 0.55, `b` beside it 5 mm off, `c` 30 mm off.
    fn scene(hand_x: f64) -> Scene {
        let yaml = format!(
            "robot:
  type: planar_hand
  shape: {{type: cylinder, radius: 0.005, height: 0.008}}
  start: [{hand_x}, 0.0, 0.0]
  height: 0.05
table: {{height: 0.76, x: [0.2, 1.0], y: [-0.6, 0.6]}}
objects:
  - {{name: a, shape: {{type: box, size: [0.1, 0.1, 0.2]}}, pose: [0.6, 0.0, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.3}}
  - {{name: b, shape: {{type: box, size: [0.1, 0.1, 0.2]}}, pose: [0.6, 0.105, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.3}}
  - {{name: c, shape: {{type: box, size: [0.1, 0.1, 0.2]}}, pose: [0.6, -0.13, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.3}}
goal: {{object: a, center: [0.8, 0.3], radius: 0.1}}
"
        );
        Scene::from_yaml(&yaml, Path::new("tips.yaml")).unwrap()
    }

    #[test]
    fn an_onset_names_the_links_and_objects_within_a_centimetre_at_their_distances() {
        // The hand 3 mm short of a's near face (its centre 8 mm short).
        let near = scene(0.542);
        let touches = touching(&near, &near.start, 0);
        let [touch] = touches.as_slice() else {
            panic!("{touches:?}")
        };
        assert_eq!(touch.link, "hand");
        assert!((touch.distance - 0.003).abs() < 1e-6, "{touch:?}");
        // On a's face, within the hand's height span (0.046 to 0.054 m).
        assert!((0.046..=0.054).contains(&touch.height), "{touch:?}");
        // b's footprint 5 mm from a's; c's 30 mm, beyond the centimetre.
        let beside = neighbours(&near, &near.start, 0);
        assert_eq!(beside.len(), 1, "{beside:?}");
        assert_eq!(beside[0].object, "b");
        assert!((beside[0].gap - 0.005).abs() < 1e-6, "{beside:?}");
        // The hand 20 mm short: nothing touches a.
        let far = scene(0.525);
        assert!(touching(&far, &far.start, 0).is_empty());
    }
}
