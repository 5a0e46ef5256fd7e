//! `pushplan replan`: the rest of a plan from an observed state. Kept when the world is
//! where the plan said; when an object was moved, repaired (kept as far as it is valid, an
//! ending searched from there) or searched anew, and checked by `check`; refused with the
//! file and field named when the observation is wrong.

use crate::common::{self, pushplan_in, Scratch};
use pushplan::planning::observed::ObservedState;
use pushplan::planning::plan_file::PlanFile;
use std::path::Path;

/// Plans `scene` into the scratch folder: the plan file and its path.
fn planned(scratch: &Scratch, scene: &str) -> (PlanFile, std::path::PathBuf) {
    let path = scratch.join("plan.json");
    common::plan_solved(scene, &path, &["--threads", "1"]);
    (PlanFile::read(&path).unwrap(), path)
}

/// Writes the state after control `k` of `plan` (its scene's names), changed by `change`,
/// as an observed-state file.
fn observe(
    plan: &PlanFile,
    plan_path: &Path,
    k: usize,
    change: impl FnOnce(&mut pushplan::State),
) -> std::path::PathBuf {
    let scene = plan.load_scene(plan_path).unwrap();
    let mut state = match k {
        0 => plan.start.state(),
        k => plan.controls[k - 1].state.state(),
    };
    change(&mut state);
    let path = plan_path.with_file_name(format!("observed-{k}.json"));
    std::fs::write(&path, ObservedState::of(&scene, &state).to_json()).unwrap();
    path
}

fn replan(plan: &Path, observed: &Path, extra: &[&str]) -> (i32, String, String, Option<PlanFile>) {
    let out = plan.with_file_name("replanned.json");
    let _ = std::fs::remove_file(&out);
    let mut args = vec![
        "replan",
        plan.to_str().unwrap(),
        "--observed",
        observed.to_str().unwrap(),
    ];
    args.extend(["--quiet", "--threads", "1", "--out", out.to_str().unwrap()]);
    args.extend(extra);
    let (code, stdout, stderr) = pushplan_in(Path::new("."), &args);
    (code, stdout, stderr, PlanFile::read(&out).ok())
}

/// `pushplan check` passes on the plan file at `path`.
fn checks(path: &Path) {
    let (code, stdout, stderr) = pushplan_in(Path::new("."), &["check", path.to_str().unwrap()]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(stdout.contains("plan OK"), "{stdout}");
}

#[test]
fn the_rest_of_the_plan_is_kept_when_the_world_is_where_the_plan_said() {
    // The arm: the observed joints are brought onto the pushing plane as a scene's start
    // is, and the rest of the plan still reaches the goal from there.
    let scratch = Scratch::new("replan-kept");
    let (plan, path) = planned(&scratch, "scenes/herb_fig1_clutter.yaml");
    let k = plan.controls.len() / 2;
    let observed = observe(&plan, &path, k, |_| {});
    for extra in [&["--at", &k.to_string()][..], &[]] {
        let (code, stdout, stderr, new) = replan(&path, &observed, extra);
        assert_eq!(code, 0, "{stdout}{stderr}");
        assert!(stdout.starts_with("kept:"), "{stdout}");
        let new = new.expect("a plan written");
        let record = new.replanned.as_ref().expect("a replan record");
        assert!(record.kept && record.at == k, "{record:?}");
        assert!(new.solved);
        let old_rest: Vec<_> = plan.controls[k..]
            .iter()
            .map(|c| (&c.ee_velocity, c.steps))
            .collect();
        let new_all: Vec<_> = new
            .controls
            .iter()
            .map(|c| (&c.ee_velocity, c.steps))
            .collect();
        assert_eq!(old_rest, new_all, "the rest of the plan, as it was");
        checks(&path.with_file_name("replanned.json"));
    }
}

/// Moves the box of `state` 5 cm further from the planar hand and 10 cm to the side away
/// from the goal disc's centre, (0.85, 0.1).
fn move_the_box(state: &mut pushplan::State) {
    let (hand, pose) = (&state.q, &mut state.objects[0]);
    let (dx, dy) = (pose.x - hand[0], pose.y - hand[1]);
    let length = dx.hypot(dy);
    let (ux, uy) = (dx / length, dy / length);
    let side = if (0.85 - pose.x) * -uy + (0.1 - pose.y) * ux > 0.0 {
        -1.0
    } else {
        1.0
    };
    pose.x += 0.05 * ux - side * 0.10 * uy;
    pose.y += 0.05 * uy + side * 0.10 * ux;
}

/// The controls of `plan` as (velocity, steps) pairs, to compare.
fn controls(plan: &PlanFile) -> Vec<(&[f64; 3], usize)> {
    plan.controls
        .iter()
        .map(|c| (&c.ee_velocity, c.steps))
        .collect()
}

#[test]
fn a_moved_object_is_pushed_on_from_where_the_rest_of_the_plan_ends() {
    // The planar hand pushes one box into the goal disc. Halfway, the box is found 5 cm
    // further from the hand and 10 cm to the side of where the plan put it: the rest of
    // the plan is still valid but misses the goal, so it is kept and an ending is searched
    // from where it ends (a repair), and the whole reaches the goal.
    let scratch = Scratch::new("replan-repaired");
    let (plan, path) = planned(&scratch, "scenes/planar_hand_single_object.yaml");
    let k = plan.controls.len() / 2;
    let observed = observe(&plan, &path, k, move_the_box);
    let (code, stdout, stderr, new) = replan(&path, &observed, &["--at", &k.to_string()]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(stdout.starts_with("repaired"), "{stdout}");
    let new = new.expect("a plan written");
    let record = new.replanned.as_ref().expect("a replan record");
    let rest = plan.controls.len() - k;
    assert_eq!(
        (record.kept, record.at, record.repaired),
        (false, k, Some(rest)),
        "{record:?}"
    );
    assert!(new.solved && new.controls.len() > rest);
    assert_eq!(
        controls(&new)[..rest],
        controls(&plan)[k..],
        "the rest of the plan, as it was, begins the repaired plan"
    );
    let expected = ObservedState::read(&observed).unwrap();
    assert_eq!(new.start.objects[0], expected.objects[&new.objects[0]]);
    // `check` re-simulates it and makes it again (the repair's search, from where the
    // rest ends); a record claiming fewer controls kept is not so.
    let replanned = path.with_file_name("replanned.json");
    checks(&replanned);
    let text = std::fs::read_to_string(&replanned).unwrap();
    let claimed = path.with_file_name("claims-fewer.json");
    let field = format!("\"repaired\": {rest}");
    assert!(text.contains(&field), "{text}");
    std::fs::write(
        &claimed,
        text.replace(&field, &format!("\"repaired\": {}", rest - 1)),
    )
    .unwrap();
    let (code, stdout, stderr) = pushplan_in(Path::new("."), &["check", claimed.to_str().unwrap()]);
    assert_eq!(code, 1, "{stdout}{stderr}");
    assert!(
        stdout.contains(&format!(
            "replanned.repaired: {} controls of the rest",
            rest - 1
        )) && stdout.ends_with("plan FAILED\n"),
        "{stdout}"
    );
}

#[test]
fn a_moved_object_gets_a_new_search_from_where_it_is() {
    // The plan has ended with the box found 5 cm further from the hand and 10 cm to the
    // side: there is no rest to keep, and the new search from the observed state reaches
    // the goal.
    let scratch = Scratch::new("replan-moved");
    let (plan, path) = planned(&scratch, "scenes/planar_hand_single_object.yaml");
    let k = plan.controls.len();
    let observed = observe(&plan, &path, k, move_the_box);
    let (code, stdout, stderr, new) = replan(&path, &observed, &["--at", &k.to_string()]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(stdout.starts_with("solved"), "{stdout}");
    let new = new.expect("a plan written");
    let record = new.replanned.as_ref().expect("a replan record");
    assert_eq!(
        (record.kept, record.at, record.repaired),
        (false, k, None),
        "{record:?}"
    );
    assert!(new.solved);
    let expected = ObservedState::read(&observed).unwrap();
    assert_eq!(
        new.start.objects[0], expected.objects[&new.objects[0]],
        "the new plan starts where the box was observed"
    );
    let replanned = path.with_file_name("replanned.json");
    checks(&replanned);
    // `check` makes a re-plan again from the plan and observation it names: a record
    // claiming the rest was kept is not so; without the observation it cannot say.
    let text = std::fs::read_to_string(&replanned).unwrap();
    let claimed = path.with_file_name("claims-kept.json");
    std::fs::write(&claimed, text.replace("\"kept\": false", "\"kept\": true")).unwrap();
    let check = |file: &Path| pushplan_in(Path::new("."), &["check", file.to_str().unwrap()]);
    let (code, stdout, stderr) = check(&claimed);
    assert_eq!(code, 1, "{stdout}{stderr}");
    assert!(
        stdout.contains("replanned.kept: the rest of") && stdout.ends_with("plan FAILED\n"),
        "{stdout}"
    );
    std::fs::remove_file(&observed).unwrap();
    let (code, stdout, stderr) = check(&replanned);
    assert_eq!(code, 1, "{stdout}{stderr}");
    assert!(
        stdout.contains("not made again: replanned: ")
            && stdout.contains("observed-")
            && stdout.ends_with("path OK, plan not confirmed\n"),
        "{stdout}"
    );
}

#[test]
fn a_wrong_observation_is_refused_with_its_file_and_field() {
    let scratch = Scratch::new("replan-bad");
    let (plan, path) = planned(&scratch, "scenes/planar_hand_single_object.yaml");
    let observed = observe(&plan, &path, 1, |_| {});
    let text = std::fs::read_to_string(&observed).unwrap();
    let object = &plan.objects[0];
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    let with = |edit: &dyn Fn(&mut serde_json::Value)| {
        let mut v = value.clone();
        edit(&mut v);
        let bad = scratch.join("bad.json");
        std::fs::write(&bad, serde_json::to_string(&v).unwrap()).unwrap();
        let (code, stdout, stderr, new) = replan(&path, &bad, &[]);
        assert_eq!(code, 2, "{stdout}{stderr}");
        assert!(new.is_none(), "no plan written");
        assert!(stderr.contains("bad.json"), "names the file: {stderr}");
        stderr
    };
    let err = with(&|v| {
        v["objects"]["ghost"] = serde_json::json!([0.5, 0.0, 0.0]);
    });
    assert!(
        err.contains("objects: 'ghost' is not in the scene"),
        "{err}"
    );
    let err = with(&|v| {
        v["objects"].as_object_mut().unwrap().remove(object);
    });
    assert!(
        err.contains(&format!("objects: '{object}' is missing")),
        "{err}"
    );
    let err = with(&|v| {
        v["format"] = "pushplan-observed/0".into();
    });
    assert!(err.contains("format"), "{err}");
    // The box centred on the hand, deeper than an observation may be off: not a valid
    // start, the object named.
    let hand = plan.controls[0].state.q.clone();
    let err = with(&|v| {
        v["objects"][object] = serde_json::json!([hand[0], hand[1], 0.0]);
    });
    assert!(
        err.contains(&format!("objects.{object}")) && err.contains("an observation may be off"),
        "{err}"
    );
    let err = with(&|v| {
        v["joints"] = serde_json::json!({});
    });
    assert!(err.contains("is missing"), "{err}");
}
