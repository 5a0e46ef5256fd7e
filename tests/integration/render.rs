//! Pictures of a real plan: snapshot positions match the plan's object poses, the
//! timeline shows the plan's contacts, and the HTML animation draws in a browser.

use pushplan::planning::plan_file::PlanFile;
use pushplan::render::render;

use crate::common;
use pushplan::Scene;

const SCENE: &str = "scenes/herb_fig1_clutter.yaml";

/// The default scene's plan for seed 2, written to a temporary folder (removed with it).
fn plan() -> (PlanFile, common::Scratch) {
    let (scene, controls) = common::default_scene_plan(2);
    let settings = common::plan_settings("pcrrt", 2, 0.0);
    // One folder per call: the tests run at once.
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = common::Scratch::new(&format!("render-{call}"));
    let path = dir.join("plan.json");
    let reference = PlanFile::scene_reference(SCENE.as_ref(), &path);
    let plan = PlanFile::build(&reference, scene, &settings, &controls, None).unwrap();
    std::fs::write(&path, plan.to_json()).unwrap();
    (plan, dir)
}

/// The value of attribute `name` in an element's text.
fn attribute<'a>(element: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = element.find(&key)? + key.len();
    Some(&element[start..start + element[start..].find('"')?])
}

fn number(element: &str, name: &str) -> f64 {
    attribute(element, name)
        .unwrap_or_else(|| panic!("no {name} in {element}"))
        .parse()
        .unwrap()
}

#[test]
fn snapshots_draw_the_objects_where_the_plan_puts_them() {
    let (plan, dir) = plan();
    let files = render(&plan, &dir.join("plan.json"), &dir.join("pictures"), &[]).unwrap();
    let svg = std::fs::read_to_string(&files.snapshots).unwrap();
    let root = &svg[..svg.find('>').unwrap()];
    let (scale, x_top, y_left, margin) = (
        number(root, "data-scale"),
        number(root, "data-x-top"),
        number(root, "data-y-left"),
        number(root, "data-margin"),
    );

    // Control boundaries: times at which the plan file records the state.
    let mut boundary_times = vec![0.0];
    for c in &plan.controls {
        boundary_times.push(boundary_times.last().unwrap() + c.steps as f64 * plan.step);
    }
    let panels: Vec<&str> = svg.split("<g class=\"snapshot\"").skip(1).collect();
    assert_eq!(panels.len(), 4, "four snapshots by default");
    for panel in panels {
        let time = number(panel, "data-time");
        let boundary = boundary_times
            .iter()
            .position(|t| (t - time).abs() < 1e-6)
            .expect("snapshots at control boundaries");
        let state = if boundary == 0 {
            &plan.start
        } else {
            &plan.controls[boundary - 1].state
        };
        for element in panel.split("<polygon class=\"object\"").skip(1) {
            let element = &element[..element.find("/>").unwrap()];
            let name = attribute(element, "data-object").unwrap();
            let index = plan.objects.iter().position(|o| o == name).unwrap();
            let expected = state.objects[index];
            assert!(
                (number(element, "data-x") - expected[0]).abs() < 1e-12
                    && (number(element, "data-y") - expected[1]).abs() < 1e-12
            );
            // The drawn footprint is centred where the plan says (pixels back to metres).
            let corners: Vec<(f64, f64)> = attribute(element, "points")
                .unwrap()
                .split(' ')
                .map(|p| {
                    let (u, v) = p.split_once(',').unwrap();
                    (u.parse::<f64>().unwrap(), v.parse::<f64>().unwrap())
                })
                .collect();
            let (u, v) = corners
                .iter()
                .fold((0.0, 0.0), |(a, b), (u, v)| (a + u, b + v));
            let (u, v) = (u / corners.len() as f64, v / corners.len() as f64);
            let y = y_left - (u - margin) / scale;
            let x = x_top - (v - margin - 20.0) / scale;
            assert!(
                (x - expected[0]).abs() < 1e-3 && (y - expected[1]).abs() < 1e-3,
                "{name} drawn at ({x}, {y}), plan says {expected:?}"
            );
        }
        // The arm is drawn; links pushing at that moment are highlighted.
        assert!(panel.contains("class=\"link"));
    }
    assert!(
        svg.contains("class=\"link contact\""),
        "some snapshot shows a pushing link"
    );

    // The timeline has a bar for every link-object pair that pushed.
    let timeline = std::fs::read_to_string(&files.timeline).unwrap();
    for c in plan.controls.iter().flat_map(|c| &c.contacts) {
        assert!(
            timeline.contains(&format!(
                "data-link=\"{}\" data-object=\"{}\"",
                c.link, c.object
            )),
            "{} -> {} missing",
            c.link,
            c.object
        );
    }
}

#[test]
fn the_animation_draws_the_arm_and_the_objects_in_a_browser() {
    let (plan, dir) = plan();
    let files = render(
        &plan,
        &dir.join("plan.json"),
        &dir.join("pictures"),
        &[0.5, 1.0],
    )
    .unwrap();
    let html = std::fs::read_to_string(&files.animation).unwrap();
    assert!(
        !html.contains("<script src") && !html.contains("<link"),
        "the page must be self-contained"
    );
    let chromium = std::env::var("CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into());
    let profile = dir.join("chromium-profile");
    let out = std::process::Command::new(&chromium)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg("--dump-dom")
        .arg(format!(
            "file://{}",
            files.animation.canonicalize().unwrap().display()
        ))
        .output()
        .unwrap_or_else(|e| {
            panic!("{chromium} does not run ({e}): install it with .ci/install-packages")
        });
    let dom = String::from_utf8_lossy(&out.stdout);
    // The script ran and drew frame 0: every object and every link shape.
    assert!(
        dom.contains("data-frame=\"0\""),
        "the script did not run:\n{}",
        &dom[..dom.len().min(2000)]
    );
    let scene = Scene::load(SCENE).unwrap();
    let shapes: usize = scene
        .robot
        .solid_links()
        .map(|l| scene.robot.chain.links[l].geometry.len())
        .sum();
    assert_eq!(dom.matches("class=\"object\"").count(), scene.objects.len());
    assert_eq!(dom.matches("class=\"link").count(), shapes);
    assert!(dom.contains("id=\"play\"") && dom.contains("type=\"range\""));
    // The 3D view drew without a WebGL error and covers part of its canvas (of 256 pixels
    // sampled, the table, the arm and the objects take more than a tenth); each object
    // has its name over it, and the scale bar its length.
    assert!(
        dom.contains("data-webgl=\"drawn\""),
        "{}",
        &dom[..dom.len().min(600)]
    );
    let painted: usize = dom
        .split("data-painted=\"")
        .nth(1)
        .and_then(|rest| rest.split('"').next())
        .and_then(|n| n.parse().ok())
        .expect("the page counts its painted pixels");
    assert!(
        (26..256).contains(&painted),
        "{painted} of 256 sampled pixels painted"
    );
    assert_eq!(
        dom.matches("<div class=\"label\"").count(),
        scene.objects.len()
    );
    assert!(dom.contains(">20 cm</div>"));
    // True speed unless the reader chooses otherwise; a legend names every object.
    assert!(dom.contains("<option value=\"1\" selected=\"\">1x (true speed)</option>"));
    for object in &scene.objects {
        assert!(
            dom.contains(&format!("</span>{}", object.name)),
            "{}",
            object.name
        );
    }
}

#[test]
fn snapshot_times_outside_the_plan_are_errors() {
    let (plan, dir) = plan();
    let err = render(&plan, &dir.join("plan.json"), &dir.join("bad"), &[1e6])
        .err()
        .unwrap();
    assert!(err.contains("outside the plan"), "{err}");
}

/// The snapshots sit two to a row under a legend; each has a 20 cm scale bar and the
/// objects' names; the goal object, the goal region and pushing links have colours of
/// their own; the timeline is at least as wide as its title.
#[test]
fn snapshots_have_a_grid_legend_scale_bar_and_names() {
    let (plan, dir) = plan();
    let files = render(&plan, &dir.join("plan.json"), &dir.join("pictures"), &[]).unwrap();
    let svg = std::fs::read_to_string(&files.snapshots).unwrap();
    let offsets: Vec<(f64, f64)> = svg
        .split("<g class=\"snapshot\"")
        .skip(1)
        .map(|panel| {
            let t = attribute(panel, "transform").unwrap();
            let (x, y) = t
                .trim_start_matches("translate(")
                .trim_end_matches(')')
                .split_once(',')
                .unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect();
    assert_eq!(offsets.len(), 4);
    assert!(
        offsets[1].0 > offsets[0].0 && offsets[1].1 == offsets[0].1,
        "{offsets:?}"
    );
    assert!(
        offsets[2].0 == offsets[0].0 && offsets[2].1 > offsets[0].1,
        "{offsets:?}"
    );
    for label in ["goal object", "goal region", "arm", "link pushing"] {
        assert!(
            svg.contains(&format!(">{label}</text>")),
            "legend lacks {label}"
        );
    }
    for panel in svg.split("<g class=\"snapshot\"").skip(1) {
        assert!(panel.contains("class=\"scale-bar\"") && panel.contains(">20 cm</text>"));
        for name in &plan.objects {
            assert!(panel.contains(&format!(">{name}</text>")), "{name} unnamed");
        }
    }
    // The legend's four swatches, four colours.
    let mut colours: Vec<&str> = svg
        .split("<g class=\"legend\">")
        .skip(1)
        .map(|swatch| attribute(swatch, "fill").unwrap())
        .collect();
    assert_eq!(colours.len(), 4);
    colours.sort_unstable();
    colours.dedup();
    assert_eq!(colours.len(), 4, "{colours:?}");

    let timeline = std::fs::read_to_string(&files.timeline).unwrap();
    let root = &timeline[..timeline.find('>').unwrap()];
    let title_start = timeline.find("font-size=\"14\">").unwrap() + "font-size=\"14\">".len();
    let title = &timeline[title_start..title_start + timeline[title_start..].find('<').unwrap()];
    // About 7 px a character at 14 px.
    assert!(
        number(root, "width") >= 7.0 * title.chars().count() as f64,
        "{title}"
    );
}
