//! Objects that start to tip, and tip, in a trial's world: when, and what touched them.
//!
//! The closed loop cannot be replayed bit for bit (its searches run on the clock), so a
//! trial keeps, for every object that starts to tip, the world then and the links the
//! model's geometry has at it: where a push the planner never meant to make began.

use super::observe;
use crate::contact::{find_arm_contacts, object_bounds, ArmBounds};
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
    let mut boxes = Vec::new();
    object_bounds(scene, &state.objects, &mut boxes);
    let mut contacts = Vec::new();
    find_arm_contacts(
        scene,
        &poses,
        &bounds,
        &state.objects,
        &boxes,
        TOUCH_DISTANCE,
        &mut contacts,
    );
    let mut touches: Vec<TiltTouch> = Vec::new();
    for c in contacts.iter().filter(|c| c.object == object) {
        let link = &scene.robot.chain.links[c.link].name;
        let touch = TiltTouch {
            link: link.clone(),
            distance: c.point.distance,
            height: c.point.point_a.z - scene.table.top,
        };
        match touches.iter_mut().find(|t| &t.link == link) {
            Some(t) if t.distance > touch.distance => *t = touch,
            Some(_) => {}
            None => touches.push(touch),
        }
    }
    touches.sort_by(|a, b| a.distance.total_cmp(&b.distance));
    touches
}
