//! Quasistatic pushing against closed forms from `shared/docs/physics.md`, computed here
//! independently of the solver.

use nalgebra::Vector2;
use pushplan_model::physics::{object_motion, Footprint, LimitSurface, PlanarContact};

const DT: f64 = 0.01;

fn surface(c: f64) -> LimitSurface {
    LimitSurface {
        c,
        f_max: 0.4 * 1.0 * 9.81,
        centre: Vector2::zeros(),
    }
}

fn contact(point: [f64; 2], normal: [f64; 2], velocity: [f64; 2]) -> PlanarContact {
    PlanarContact {
        point: Vector2::new(point[0], point[1]),
        normal: Vector2::new(normal[0], normal[1]).normalize(),
        pusher_velocity: Vector2::new(velocity[0], velocity[1]),
        gap: 0.0,
    }
}

/// physics.md, sticking case with A = diag(1, 1, 1/c^2).
fn sticking_twist(c: f64, x: f64, y: f64, vpx: f64, vpy: f64) -> [f64; 3] {
    let d = c * c + x * x + y * y;
    let vx = ((c * c + x * x) * vpx + x * y * vpy) / d;
    let vy = (x * y * vpx + (c * c + y * y) * vpy) / d;
    [vx, vy, (x * vy - y * vx) / (c * c)]
}

fn assert_twist(got: &pushplan_model::math::Twist2, want: [f64; 3], tol: f64) {
    let g = [got.vx, got.vy, got.omega];
    for i in 0..3 {
        assert!(
            (g[i] - want[i]).abs() < tol,
            "twist {g:?} != expected {want:?}"
        );
    }
}

#[test]
fn a_push_through_the_centroid_turns_a_box_whose_centre_of_friction_is_off_it() {
    // The support pressure loaded towards +y moves the centre of friction to (0, d): a
    // push through the centroid along +x passes below it and turns the box
    // counter-clockwise. Sticking, in the frame of the centre of friction the contact is
    // at (-b, -d); the origin then moves with the pusher (it lies on the push line).
    let (b, c, d) = (0.05, 0.038, 0.01);
    let surface = LimitSurface {
        centre: Vector2::new(0.0, d),
        ..surface(c)
    };
    let m = object_motion(
        &[contact([-b, 0.0], [1.0, 0.0], [0.1, 0.0])],
        &surface,
        0.6,
        DT,
    )
    .unwrap();
    let about_centre = sticking_twist(c, -b, -d, 0.1, 0.0);
    let omega = about_centre[2];
    assert!(omega > 0.0);
    // v_origin = v_centre + omega z x (origin - centre) = v_centre + omega (d, 0).
    assert_twist(
        &m.twist,
        [about_centre[0] + omega * d, about_centre[1], omega],
        1e-12,
    );
    assert!(
        (m.twist.vx - 0.1).abs() < 1e-12,
        "the origin keeps up with the pusher"
    );
    // Mirrored: the centre of friction at (0, -d) turns it the other way.
    let mirrored = object_motion(
        &[contact([-b, 0.0], [1.0, 0.0], [0.1, 0.0])],
        &LimitSurface {
            centre: Vector2::new(0.0, -d),
            ..surface
        },
        0.6,
        DT,
    )
    .unwrap();
    assert!((mirrored.twist.omega + omega).abs() < 1e-12);
}

#[test]
fn push_through_the_centre_of_a_symmetric_box_translates_it_without_rotation() {
    // Box of half-width 0.05: push the face x = -0.05 at its midpoint along +x.
    let c = Footprint::Polygon {
        vertices: vec![
            Vector2::new(-0.05, -0.05),
            Vector2::new(0.05, -0.05),
            Vector2::new(0.05, 0.05),
            Vector2::new(-0.05, 0.05),
        ],
    }
    .characteristic_length();
    let m = object_motion(
        &[contact([-0.05, 0.0], [1.0, 0.0], [0.1, 0.0])],
        &surface(c),
        0.3,
        DT,
    )
    .unwrap();
    assert_twist(&m.twist, [0.1, 0.0, 0.0], 1e-12);
}

#[test]
fn off_centre_push_rotates_with_the_sign_of_the_torque() {
    // Push along +x at y = +0.03: torque x fy - y fx = -0.03 fx < 0, so clockwise.
    let c = 0.04;
    let m = object_motion(
        &[contact([-0.05, 0.03], [1.0, 0.0], [0.1, 0.0])],
        &surface(c),
        0.8,
        DT,
    )
    .unwrap();
    assert!(
        m.twist.omega < 0.0,
        "expected clockwise rotation, got {:?}",
        m.twist
    );
    // Below y = 0 the torque and the rotation flip.
    let m = object_motion(
        &[contact([-0.05, -0.03], [1.0, 0.0], [0.1, 0.0])],
        &surface(c),
        0.8,
        DT,
    )
    .unwrap();
    assert!(m.twist.omega > 0.0);
}

#[test]
fn sticking_contact_matches_the_closed_form_twist() {
    let c = 0.045;
    for (point, v) in [
        ([-0.05, 0.02], [0.1, 0.01]),
        ([-0.05, -0.04], [0.08, -0.02]),
        ([-0.05, 0.0], [0.1, 0.03]),
    ] {
        // High friction: the contact sticks.
        let m = object_motion(&[contact(point, [1.0, 0.0], v)], &surface(c), 2.0, DT).unwrap();
        assert_twist(
            &m.twist,
            sticking_twist(c, point[0], point[1], v[0], v[1]),
            1e-10,
        );
    }
}

#[test]
fn push_outside_the_friction_cone_slides_with_matching_normal_velocity() {
    // Centre push with a large tangential component: |vt / vn| = 1 > mu = 0.2.
    let (c, mu) = (0.04, 0.2);
    let (x, y) = (-0.05, 0.0);
    let v = [0.05, 0.05];
    let m = object_motion(&[contact([x, y], [1.0, 0.0], v)], &surface(c), mu, DT).unwrap();
    // physics.md, sliding: V = kappa A w_b on the cone edge on the slip side (+t = +y).
    let f = [1.0, mu]; // n + mu t
    let w = [f[0], f[1], x * f[1] - y * f[0]];
    let aw = [w[0], w[1], w[2] / (c * c)];
    let point_velocity_n = aw[0] - y * aw[2]; // (J A w) . n with n = +x
    let kappa = v[0] / point_velocity_n;
    let expected = [kappa * aw[0], kappa * aw[1], kappa * aw[2]];
    assert_twist(&m.twist, expected, 1e-10);
    // Normal velocities agree, tangential ones do not (the pusher slips).
    let contact_vx = m.twist.vx - y * m.twist.omega;
    let contact_vy = m.twist.vy + x * m.twist.omega;
    assert!((contact_vx - v[0]).abs() < 1e-10);
    assert!((contact_vy - v[1]).abs() > 1e-3);
}

#[test]
fn a_pusher_moving_away_does_not_move_the_object() {
    let m = object_motion(
        &[contact([-0.05, 0.01], [1.0, 0.0], [-0.1, 0.05])],
        &surface(0.04),
        0.5,
        DT,
    )
    .unwrap();
    assert!(m.twist.is_zero());
    assert_eq!(m.normal_forces, vec![0.0]);
    // Nor does one that is still too far away to close its gap within the step.
    let mut far = contact([-0.05, 0.0], [1.0, 0.0], [0.1, 0.0]);
    far.gap = 0.002; // 2 mm, and the pusher covers 1 mm per step
    assert!(object_motion(&[far], &surface(0.04), 0.5, DT)
        .unwrap()
        .twist
        .is_zero());
}

#[test]
fn a_gap_closing_within_the_step_pushes_for_the_rest_of_it() {
    let mut c = contact([-0.05, 0.0], [1.0, 0.0], [0.1, 0.0]);
    c.gap = 0.0004; // closes after 0.4 of the 1 mm step
    let m = object_motion(&[c], &surface(0.04), 0.5, DT).unwrap();
    assert!((m.twist.vx * DT - 0.0006).abs() < 1e-12);
}

#[test]
fn two_symmetric_contacts_translate_straight() {
    // A flat pusher on the face x = -0.05 touches at its two ends.
    let contacts = [
        contact([-0.05, 0.04], [1.0, 0.0], [0.1, 0.0]),
        contact([-0.05, -0.04], [1.0, 0.0], [0.1, 0.0]),
    ];
    let m = object_motion(&contacts, &surface(0.04), 0.3, DT).unwrap();
    assert_twist(&m.twist, [0.1, 0.0, 0.0], 1e-10);
    // Equal shares of the load, summing to the support friction mu_g m g.
    assert!((m.normal_forces[0] - m.normal_forces[1]).abs() < 1e-9);
    assert!((m.normal_forces[0] + m.normal_forces[1] - 0.4 * 9.81).abs() < 1e-9);
}

#[test]
fn two_contacts_solve_exactly_not_by_averaging() {
    // Two pushers moving together at different points: the object moves rigidly with
    // both contacts sticking, so both contact points share the pusher velocity.
    let v = [0.1, 0.02];
    let contacts = [
        contact([-0.05, 0.03], [1.0, 0.0], v),
        contact([0.0, -0.05], [0.0, 1.0], v),
    ];
    let m = object_motion(&contacts, &surface(0.04), 1.0, DT).unwrap();
    // Translation with the pushers: no rotation, both contact points move at v.
    assert_twist(&m.twist, [v[0], v[1], 0.0], 1e-9);
    // Averaging the single-contact answers gives a different, wrong motion: the
    // contact points would not move with the pushers.
    let single = |c: &PlanarContact| object_motion(&[*c], &surface(0.04), 1.0, DT).unwrap().twist;
    let (a, b) = (single(&contacts[0]), single(&contacts[1]));
    let averaged = [
        (a.vx + b.vx) / 2.0,
        (a.vy + b.vy) / 2.0,
        (a.omega + b.omega) / 2.0,
    ];
    let error = ((averaged[0] - v[0]).powi(2) + (averaged[1] - v[1]).powi(2)).sqrt();
    assert!(error > 0.01, "averaged {averaged:?}");
}

#[test]
fn opposing_pushers_jam_the_object() {
    let contacts = [
        contact([-0.05, 0.0], [1.0, 0.0], [0.1, 0.0]),
        contact([0.05, 0.0], [-1.0, 0.0], [-0.1, 0.0]),
    ];
    assert!(object_motion(&contacts, &surface(0.04), 0.3, DT).is_err());
    // Pushers that move together (one leading, one trailing) do not jam.
    let together = [
        contact([-0.05, 0.0], [1.0, 0.0], [0.1, 0.0]),
        contact([0.05, 0.0], [-1.0, 0.0], [0.1, 0.0]),
    ];
    assert!(object_motion(&together, &surface(0.04), 0.3, DT).is_ok());
}

#[test]
fn characteristic_lengths_match_their_integrals() {
    // Disc: 2R/3 (physics.md).
    assert!((Footprint::Circle { radius: 0.09 }.characteristic_length() - 0.06).abs() < 1e-15);
    // Square of side s: s (sqrt(2) + ln(1 + sqrt(2))) / 6.
    let s = 0.1;
    let square = Footprint::Polygon {
        vertices: vec![
            Vector2::new(-s / 2.0, -s / 2.0),
            Vector2::new(s / 2.0, -s / 2.0),
            Vector2::new(s / 2.0, s / 2.0),
            Vector2::new(-s / 2.0, s / 2.0),
        ],
    };
    let closed = s * (2f64.sqrt() + (1.0 + 2f64.sqrt()).ln()) / 6.0;
    assert!((square.characteristic_length() - closed).abs() < 1e-12);
    // A 0.2 x 0.06 rectangle against a midpoint-rule integral.
    let (a, b) = (0.2, 0.06);
    let rect = Footprint::Polygon {
        vertices: vec![
            Vector2::new(-a / 2.0, -b / 2.0),
            Vector2::new(a / 2.0, -b / 2.0),
            Vector2::new(a / 2.0, b / 2.0),
            Vector2::new(-a / 2.0, b / 2.0),
        ],
    };
    let n = 1000;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let x = -a / 2.0 + a * (i as f64 + 0.5) / n as f64;
            let y = -b / 2.0 + b * (j as f64 + 0.5) / n as f64;
            sum += (x * x + y * y).sqrt();
        }
    }
    let numeric = sum / (n * n) as f64;
    assert!((rect.characteristic_length() - numeric).abs() < 1e-6);
}

#[test]
fn a_support_pressure_loaded_toward_one_edge_has_the_closed_form_centre_and_c() {
    use pushplan_model::physics::{LoadedSupport, SupportGrid};
    // A thin strip of length a along x: a planar pressure is linear in x. With its centre
    // at d (at most a/6 from the middle) it is p = 1 + k x, k = 12 d / a^2; further out
    // only the triangle p = x - x0 from x0 = 3 d - a carries the strip. Then
    // c = int p |x - d| / int p, in closed form from the antiderivatives below.
    let a = 0.1;
    let strip = Footprint::Polygon {
        vertices: [
            [-0.05, -0.001],
            [0.05, -0.001],
            [0.05, 0.001],
            [-0.05, 0.001],
        ]
        .iter()
        .map(|v| Vector2::new(v[0], v[1]))
        .collect(),
    };
    let (grid, table) = (SupportGrid::new(&strip), LoadedSupport::new(&strip));
    // int (alpha + beta x)(x - d) dx and int (alpha + beta x) dx.
    let moment = |alpha: f64, beta: f64, d: f64, x: f64| {
        alpha * (x * x / 2.0 - d * x) + beta * (x.powi(3) / 3.0 - d * x * x / 2.0)
    };
    let c_of = |alpha: f64, beta: f64, from: f64, d: f64| {
        let m = |x| moment(alpha, beta, d, x);
        let load = |x: f64| alpha * x + beta * x * x / 2.0;
        ((m(a / 2.0) - m(d)) - (m(d) - m(from))) / (load(a / 2.0) - load(from))
    };
    let uniform_c = c_of(1.0, 0.0, -a / 2.0, 0.0);
    assert!((uniform_c - a / 4.0).abs() < 1e-12);
    for d in [0.0, a / 10.0, a / 6.0, a / 4.0, 0.4 * a] {
        let want = if d <= a / 6.0 {
            c_of(1.0, 12.0 * d / (a * a), -a / 2.0, d)
        } else {
            let x0 = 3.0 * d - a;
            c_of(-x0, 1.0, x0, d)
        };
        let (centre, ratio) = grid.loaded(Vector2::new(d, 0.0));
        assert!(
            (centre - Vector2::new(d, 0.0)).norm() < 2e-4,
            "d {d}: centre {centre:?}"
        );
        assert!(
            (ratio - want / uniform_c).abs() < 0.02,
            "d {d}: c ratio {ratio}, closed form {}",
            want / uniform_c
        );
        // The propagator's table, interpolated, in either direction along the strip.
        for sign in [1.0, -1.0] {
            let tabled = table.c_ratio(Vector2::new(sign * d, 0.0));
            assert!(
                (tabled - want / uniform_c).abs() < 0.03,
                "d {d}: tabled c ratio {tabled}, closed form {}",
                want / uniform_c
            );
        }
    }
    // Loaded toward an edge, friction resists turning less.
    let (_, ratio) = grid.loaded(Vector2::new(0.4 * a, 0.0));
    assert!(ratio < 0.6, "{ratio}");
}
