//! Tipping (`physics.md`, "Tipping"): the support balance against closed forms computed
//! here, and pushes through the whole pipeline at heights around the tipping height.

use crate::common;

use nalgebra::Vector2;
use pushplan_model::physics::limit_surface::GRAVITY;
use pushplan_model::physics::tipping::{pusher_forces, sliding_push_tips, support_balance};
use pushplan_model::physics::{
    object_motion, ContactElevation, Footprint, LimitSurface, PlanarContact,
};
use pushplan_model::{EeAction, Invalid, Propagator, Scene};

const MU_G: f64 = 0.4;
const MASS: f64 = 1.0;

fn square(b: f64) -> Footprint {
    Footprint::Polygon {
        vertices: vec![
            Vector2::new(-b, -b),
            Vector2::new(b, -b),
            Vector2::new(b, b),
            Vector2::new(-b, b),
        ],
    }
}

/// Mean distance from the centre of a square of half-width b: b (sqrt 2 + asinh 1) / 3.
fn square_c(b: f64) -> f64 {
    b * (2f64.sqrt() + 1f64.asinh()) / 3.0
}

/// Solves the push of one contact at `height` and returns (normal force, friction force,
/// does the object stay flat with no margin).
fn push(
    footprint: &Footprint,
    c: f64,
    mu_c: f64,
    contact: PlanarContact,
    height: f64,
) -> (f64, f64, bool) {
    let surface = LimitSurface {
        c,
        f_max: MU_G * MASS * GRAVITY,
        centre: Vector2::zeros(),
    };
    let motion = object_motion(&[contact], &surface, mu_c, 0.01).unwrap();
    let mut forces = Vec::new();
    let elevation = ContactElevation { height, slope: 0.0 };
    pusher_forces(&[contact], &[elevation], &motion, &mut forces);
    let balance = support_balance(MASS, footprint.centroid(), &forces);
    (
        motion.normal_forces[0],
        motion.friction_forces[0],
        balance.stays_flat(footprint, 0.0),
    )
}

fn flat_on(point: [f64; 2], velocity: [f64; 2]) -> PlanarContact {
    PlanarContact {
        point: Vector2::new(point[0], point[1]),
        normal: Vector2::new(1.0, 0.0),
        pusher_velocity: Vector2::new(velocity[0], velocity[1]),
        gap: 0.0,
    }
}

#[test]
fn a_box_pushed_flat_on_tips_above_half_width_over_mu_g() {
    let b = 0.051;
    let h_max = b / MU_G; // 0.1275 m, physics.md
    let contact = flat_on([-b, 0.0], [0.1, 0.0]);
    let (normal, friction, flat) = push(&square(b), square_c(b), 0.3, contact, 0.99 * h_max);
    assert!(flat);
    // A push through the centre translates the box: the whole table friction, mu_g m g.
    assert!((normal - MU_G * MASS * GRAVITY).abs() < 1e-9 && friction.abs() < 1e-9);
    assert!(!push(&square(b), square_c(b), 0.3, contact, 1.01 * h_max).2);
}

#[test]
fn a_cylinder_pushed_flat_on_tips_above_radius_over_mu_g() {
    let r = 0.035;
    let h_max = r / MU_G;
    let disc = Footprint::Circle { radius: r };
    let contact = flat_on([-r, 0.0], [0.1, 0.0]);
    assert!(push(&disc, 2.0 * r / 3.0, 0.3, contact, 0.99 * h_max).2);
    assert!(!push(&disc, 2.0 * r / 3.0, 0.3, contact, 1.01 * h_max).2);
}

#[test]
fn friction_at_a_sliding_contact_raises_the_tipping_height() {
    // The pusher slides along the face (its velocity is outside the motion cone): the
    // force lies on the friction cone's edge, f = fn (1, mu_c), and the limit surface
    // fixes fn: fn^2 (1 + mu_c^2 + (b mu_c / c)^2) = (mu_g m g)^2. The box tips when the
    // centre of pressure h fn / (m g) passes b.
    let (b, mu_c) = (0.051, 0.3);
    let c = square_c(b);
    let fn_closed = MU_G * MASS * GRAVITY / (1.0 + mu_c * mu_c * (1.0 + b * b / (c * c))).sqrt();
    let h_max = b * MASS * GRAVITY / fn_closed;
    assert!(h_max > 1.02 * b / MU_G, "friction matters here");
    let contact = flat_on([-b, 0.0], [0.1, 0.3]);
    let (normal, friction, flat) = push(&square(b), c, mu_c, contact, 0.99 * h_max);
    assert!((normal - fn_closed).abs() < 1e-9, "{normal} vs {fn_closed}");
    assert!(
        (friction - mu_c * normal).abs() < 1e-9,
        "sliding: at the cone's edge"
    );
    assert!(flat);
    assert!(!push(&square(b), c, mu_c, contact, 1.01 * h_max).2);
}

#[test]
fn pressing_down_is_not_counted_on_and_lifting_tips() {
    // A downward push would pull the centre of pressure toward its point, but friction
    // in the 3D contact may cancel it: the model does not count on it. A contact that
    // lifts the whole weight leaves no support (N <= 0).
    let (b, mu_c) = (0.051, 0.3);
    let contact = flat_on([-b, 0.0], [0.1, 0.0]);
    let surface = LimitSurface {
        c: square_c(b),
        f_max: MU_G * MASS * GRAVITY,
        centre: Vector2::zeros(),
    };
    let motion = object_motion(&[contact], &surface, mu_c, 0.01).unwrap();
    let balance = |slope: f64, height: f64| {
        let mut forces = Vec::new();
        pusher_forces(
            &[contact],
            &[ContactElevation { height, slope }],
            &motion,
            &mut forces,
        );
        support_balance(MASS, Vector2::zeros(), &forces)
    };
    let h = 1.2 * b / MU_G;
    assert!(!balance(0.0, h).stays_flat(&square(b), 0.0));
    // Pressing down, gently or steeply: no help.
    for slope in [0.2, 2.0, 10.0] {
        assert_eq!(balance(slope, h), balance(0.0, h));
    }
    // Pushing up at slope s lifts s fn at x = -b: N = m g - s fn, N x_P = fn h + s fn b;
    let (s, fn_) = (0.5, MU_G * MASS * GRAVITY);
    let lifted = balance(-s, 0.5 * h);
    let n = MASS * GRAVITY - s * fn_;
    assert!((lifted.normal - n).abs() < 1e-9);
    assert!((lifted.p_OP.x - (fn_ * 0.5 * h + s * fn_ * b) / n).abs() < 1e-12);
    // ... and a slope that lifts more than the weight leaves no support.
    assert!(!balance(-(1.0 / MU_G + 0.01), 0.0).stays_flat(&square(b), 0.0));
    assert_eq!(
        support_balance(MASS, Vector2::zeros(), &[]).p_OP,
        Vector2::zeros()
    );
}

/// A thin planar hand (1 cm tall) at `height` pushing `shape` flat-on along +x. The arm
/// clearance is off: these pushes reach the object, to test the balance on contact.
fn hand_scene(shape: &str, radius: f64, height: f64, mu_g: f64, margin: f64) -> Scene {
    let physics = format!("physics: {{tipping_margin: {margin}, arm_clearance: 0.0}}");
    common::thin_hand_scene("thing", shape, 0.42 + radius + 0.01, height, mu_g, &physics)
}

fn push_with_hand(scene: &Scene) -> Option<Invalid> {
    let mut propagator = Propagator::new(scene);
    let run = propagator.propagate(&scene.start, &EeAction::planar(0.2, 0.0, 0.0), 0.5);
    run.stopped_by
}

#[test]
fn the_hand_slides_a_box_below_the_tipping_height_and_tips_it_above() {
    // The contact's lowest point is 5 mm below the hand's centre.
    let box_shape = "{type: box, size: [0.1, 0.1, 0.3]}";
    let h_max = 0.05 / MU_G + 0.005;
    let below = hand_scene(box_shape, 0.05, 0.97 * h_max, MU_G, 0.0);
    assert_eq!(push_with_hand(&below), None);
    let above = hand_scene(box_shape, 0.05, 1.03 * h_max, MU_G, 0.0);
    assert_eq!(
        push_with_hand(&above),
        Some(Invalid::Tips {
            object: "thing".into(),
            link: "hand".into()
        })
    );
    // Slipperier tables let a push go higher: mu_g 0.3 gives h_max = 0.167 m.
    let slippery = hand_scene(box_shape, 0.05, 1.03 * h_max, 0.3, 0.0);
    assert_eq!(push_with_hand(&slippery), None);
    // A margin of 0.2 keeps the centre of pressure within 80 % of the edge.
    let margin = hand_scene(box_shape, 0.05, 0.85 * h_max, MU_G, 0.2);
    assert!(matches!(
        push_with_hand(&margin),
        Some(Invalid::Tips { .. })
    ));
}

#[test]
fn shipped_tall_objects_tip_where_the_closed_form_says() {
    // Every object kind of the benchmark scenes, pushed flat-on by the hand just below
    // and just above b / mu_g (b: the half-width or radius), with the default margin.
    let margin = pushplan_model::scene::PhysicsParams::default().tipping_margin;
    let mut kinds: Vec<String> = Vec::new();
    for entry in std::fs::read_dir("scenes/benchmark").unwrap() {
        let scene = Scene::load(entry.unwrap().path()).unwrap();
        for o in &scene.objects {
            let (shape, half_width) = match &o.footprint {
                Footprint::Circle { radius } => (
                    format!("{{type: cylinder, radius: {radius}, height: {}}}", o.height),
                    *radius,
                ),
                Footprint::Polygon { vertices } => {
                    let w = vertices.iter().map(|v| v.x).fold(0.0, f64::max);
                    let d = vertices.iter().map(|v| v.y).fold(0.0, f64::max);
                    (
                        format!(
                            "{{type: box, size: [{}, {}, {}]}}",
                            2.0 * w,
                            2.0 * d,
                            o.height
                        ),
                        w,
                    )
                }
            };
            if kinds.contains(&shape) {
                continue;
            }
            kinds.push(shape.clone());
            let h_max = (1.0 - margin) * half_width / o.mu_g + 0.005;
            let below = hand_scene(&shape, half_width, 0.95 * h_max, o.mu_g, margin);
            assert_eq!(push_with_hand(&below), None, "{shape} at {}", 0.95 * h_max);
            let above = 1.05 * h_max;
            if above + 0.005 < o.height {
                let scene = hand_scene(&shape, half_width, above, o.mu_g, margin);
                assert!(
                    matches!(push_with_hand(&scene), Some(Invalid::Tips { .. })),
                    "{shape} at {above}"
                );
            }
        }
    }
    assert!(
        kinds.len() >= 4,
        "box, glass, bottle, bowl and the goal box: {kinds:?}"
    );
}

#[test]
fn a_sliding_push_tips_where_the_closed_form_says() {
    let (b, margin) = (0.051, 0.2);
    let edge = (1.0 - margin) * b;
    let tips = |footprint: &Footprint, contact: &PlanarContact, height: f64, slope: f64| {
        let elevation = ContactElevation { height, slope };
        sliding_push_tips(MASS, MU_G, footprint, contact, &elevation, margin)
    };
    // Flat on a box's face, anywhere along it: the sliding force mu_g m g at h moves the
    // centre of pressure by mu_g h (the weight is m g), so it tips above (1 - m) b / mu_g.
    let h = edge / MU_G;
    for y in [0.0, 0.8 * b] {
        let contact = flat_on([-b, y], [0.1, 0.0]);
        assert!(!tips(&square(b), &contact, 0.99 * h, 0.0), "y {y}");
        assert!(tips(&square(b), &contact, 1.01 * h, 0.0), "y {y}");
    }
    // A cylinder from any side: the same with its radius.
    let r = 0.035;
    let circle = Footprint::Circle { radius: r };
    let h = (1.0 - margin) * r / MU_G;
    for angle in [0.3f64, 2.0, -2.5] {
        let out = Vector2::new(angle.cos(), angle.sin());
        let contact = PlanarContact {
            point: r * out,
            normal: -out,
            pusher_velocity: -0.1 * out,
            gap: 0.005,
        };
        assert!(!tips(&circle, &contact, 0.99 * h, 0.0), "angle {angle}");
        assert!(tips(&circle, &contact, 1.01 * h, 0.0), "angle {angle}");
    }
    // A contact that pushes up as well (slope -s) unloads the table by s mu_g m g and
    // lifts at the face: N = m g (1 - s mu_g), N p = mu_g m g (h + s b), so it tips above
    // h = (1 - m) b (1 - s mu_g) / mu_g - s b.
    let s = 0.5;
    let h = edge * (1.0 - s * MU_G) / MU_G - s * b;
    let contact = flat_on([-b, 0.0], [0.1, 0.0]);
    assert!(!tips(&square(b), &contact, 0.99 * h, -s));
    assert!(tips(&square(b), &contact, 1.01 * h, -s));
}

#[test]
fn a_link_closing_in_where_a_sliding_push_would_tip_stops_before_the_touch() {
    // The hand approaches a tall box from 1 cm; its contact's lowest point is 5 mm below
    // its centre. Above the sliding tipping height it must keep `arm_clearance` away,
    // below it the push goes on; with no clearance the touch itself tips the box.
    let box_shape = "{type: box, size: [0.1, 0.1, 0.3]}";
    let margin = pushplan_model::scene::PhysicsParams::default().tipping_margin;
    let h_max = (1.0 - margin) * 0.05 / MU_G + 0.005;
    let scene = |height: f64, clearance: f64| {
        let physics = format!("physics: {{arm_clearance: {clearance}}}");
        common::thin_hand_scene("tall", box_shape, 0.42 + 0.06, height, MU_G, &physics)
    };
    let high = scene(1.05 * h_max, 0.01);
    match push_with_hand(&high) {
        Some(Invalid::ClosesInAtTippingHeight {
            link,
            object,
            distance,
        }) => {
            assert_eq!((link.as_str(), object.as_str()), ("hand", "tall"));
            assert!(distance > 0.0 && distance < 0.01, "{distance}");
        }
        other => panic!("expected the hand to stop closing in, got {other:?}"),
    }
    assert_eq!(push_with_hand(&scene(0.95 * h_max, 0.01)), None);
    assert!(matches!(
        push_with_hand(&scene(1.05 * h_max, 0.0)),
        Some(Invalid::Tips { .. })
    ));
}

#[test]
fn a_link_closing_in_at_tipping_height_keeps_the_clearance_at_any_speed() {
    // The hand's face (x = 0.42 m at the start) approaches the tall box's near face
    // (x = 0.50 m) at tipping height, at speeds from 0.5 to 9 mm a step. Whatever the
    // step, the approach stops with the face at least `arm_clearance` (10 mm) from the box,
    // and the refused step is the one that would have ended inside it: read from the
    // geometry here, the hand's own x against the box's face.
    let box_shape = "{type: box, size: [0.1, 0.1, 0.3]}";
    let margin = pushplan_model::scene::PhysicsParams::default().tipping_margin;
    let h_max = (1.0 - margin) * 0.05 / MU_G + 0.005;
    let physics = "physics: {arm_clearance: 0.01}";
    let scene = common::thin_hand_scene("tall", box_shape, 0.55, 1.05 * h_max, MU_G, physics);
    let (face, clearance) = (0.50, 0.01);
    let mut propagator = Propagator::new(&scene);
    let dt = propagator.step_size();
    for speed in [0.05, 0.1, 0.3, 0.73, 0.9] {
        // Long enough to cover the 80 mm and more.
        let run = propagator.propagate(
            &scene.start,
            &EeAction::planar(speed, 0.0, 0.0),
            0.1 / speed,
        );
        let gap = face - (run.state.q[0] + 0.02);
        let step = speed * dt;
        assert!(
            gap >= clearance - 1e-9 && gap - step < clearance,
            "{speed} m/s: stopped {gap} m from the box, steps of {step} m"
        );
        match run.stopped_by {
            Some(Invalid::ClosesInAtTippingHeight { distance, .. }) => assert!(
                (distance - (gap - step)).abs() < 1e-6,
                "{speed} m/s: refused at {distance} m, the step would end {} m off",
                gap - step
            ),
            other => panic!("{speed} m/s: expected the approach to stop, got {other:?}"),
        }
    }
}

#[test]
fn a_link_passing_over_a_tall_object_keeps_the_clearance_a_low_one_needs_none() {
    // The 1 cm hand at 0.12 m (its underside at 0.115 m) starts over a box 0.11 m tall
    // and moves on 5 mm over its top. A narrow box (half-width 2 cm) tips when pushed that high by a sliding push
    // (above 0.7 * 0.02 / 0.4 = 0.035 m, default margin): were it 5 mm further up or the hand lower, the
    // hand would knock it over. A wide one (half-width 10 cm) would slide.
    let scene = |half_width: f64, clearance: f64| {
        let shape = format!(
            "{{type: box, size: [{}, {}, 0.11]}}",
            2.0 * half_width,
            2.0 * half_width
        );
        let physics = format!("physics: {{arm_clearance: {clearance}}}");
        common::thin_hand_scene("under", &shape, 0.41, 0.12, MU_G, &physics)
    };
    assert!(matches!(
        push_with_hand(&scene(0.02, 0.01)),
        Some(Invalid::ClosesInAtTippingHeight { distance, .. }) if (0.004..0.006).contains(&distance)
    ));
    assert_eq!(push_with_hand(&scene(0.02, 0.0)), None);
    assert_eq!(push_with_hand(&scene(0.1, 0.01)), None);
}
