//! Every file the program writes is written whole or not at all (issue 59): with the
//! file-size limit too small for the new file (`ulimit -f`, as a full disk), each command
//! exits with a clear error naming the file, and the file that was there before is left
//! as it was, with no temporary file beside it.

use crate::common;

use std::path::Path;
use std::process::Command;

/// Runs `pushplan ARGS` in `dir` under `ulimit -f BLOCKS` (1 KiB blocks): its exit code
/// and what it printed.
fn pushplan_limited(dir: &Path, blocks: u32, args: &[&str]) -> (i32, String) {
    let out = Command::new("sh")
        .current_dir(dir)
        .arg("-c")
        .arg(format!("ulimit -f {blocks}; exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_pushplan"))
        .args(args)
        .output()
        .unwrap();
    let text =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    (out.status.code().unwrap_or(-1), text)
}

/// The names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Asserts that a write of `file` in `dir` failed cleanly: exit 2, the file named, the
/// old contents kept, nothing else left in the folder.
fn assert_kept(dir: &Path, file: &str, old: &str, (code, text): (i32, String)) {
    assert_eq!(code, 2, "{text}");
    assert!(
        text.contains(file) && text.contains("the previous file is left as it was"),
        "{text}"
    );
    assert_eq!(std::fs::read_to_string(dir.join(file)).unwrap(), old);
    assert!(
        listing(dir).iter().all(|n| !n.ends_with(".tmp")),
        "a temporary file stayed: {:?}",
        listing(dir)
    );
}

#[test]
fn a_failed_write_leaves_the_previous_file_as_it_was() {
    let scratch = common::Scratch::new("writes-whole");
    let dir = scratch.path();
    let scene = std::fs::canonicalize("scenes/herb_single_object.yaml").unwrap();
    let scene = scene.to_str().unwrap();
    let plan = dir.join("plan.json");
    common::plan_solved(scene, &plan, &[]);
    let good = std::fs::read_to_string(&plan).unwrap();
    assert!(
        good.len() > 8 << 10,
        "the plan must outgrow the limit below"
    );

    // A plan written over a good one: the search succeeds, the write fails.
    let old_plan = dir.join("old.json");
    std::fs::write(&old_plan, "{\"the previous\": \"plan\"}").unwrap();
    let args = [
        "plan",
        scene,
        "--robust",
        "0",
        "--seed",
        "2",
        "--shortcut",
        "0",
    ];
    let limited = pushplan_limited(dir, 8, &[&args[..], &["--out", "old.json"]].concat());
    assert_kept(dir, "old.json", "{\"the previous\": \"plan\"}", limited);

    // An execution report.
    std::fs::write(dir.join("report.json"), "old report").unwrap();
    let limited = pushplan_limited(
        dir,
        1,
        &[
            "execute",
            "plan.json",
            "--trials",
            "1",
            "--json",
            "report.json",
        ],
    );
    assert_kept(dir, "report.json", "old report", limited);

    // Pictures.
    let pictures = dir.join("pictures");
    std::fs::create_dir(&pictures).unwrap();
    std::fs::write(pictures.join("snapshots.svg"), "old picture").unwrap();
    let limited = pushplan_limited(dir, 8, &["render", "plan.json", "--out", "pictures"]);
    assert_kept(&pictures, "snapshots.svg", "old picture", limited);

    // Generated scenes (generated once first, so that the robot they name is there).
    let generate = ["scenes", "generate", "--count", "1", "--out", "scenes"];
    let scenes = dir.join("scenes");
    let scene_file = scenes.join("scene_00.yaml");
    let (code, text) = pushplan_limited(dir, 1 << 20, &generate);
    assert_eq!(code, 0, "{text}");
    let generated = std::fs::read_to_string(&scene_file).unwrap();
    std::fs::write(&scene_file, "old scene").unwrap();
    let limited = pushplan_limited(dir, 1, &generate);
    assert_kept(&scenes, "scene_00.yaml", "old scene", limited);
    // Without the limit the old file is replaced whole.
    let (code, text) = pushplan_limited(dir, 1 << 20, &generate);
    assert_eq!(code, 0, "{text}");
    assert_eq!(std::fs::read_to_string(&scene_file).unwrap(), generated);
}

#[test]
fn the_plans_folder_is_tried_before_the_search() {
    let scratch = common::Scratch::new("writes-folder");
    let dir = scratch.path();
    let scene = std::fs::canonicalize("scenes/herb_single_object.yaml").unwrap();
    // A file where the folder should be, and a folder where the plan should be: refused
    // before searching (no search summary printed), each named.
    std::fs::write(dir.join("blocker"), "").unwrap();
    std::fs::create_dir(dir.join("taken.json")).unwrap();
    let plan_to = |out: &str| {
        common::pushplan_in(
            dir,
            &[
                "plan",
                scene.to_str().unwrap(),
                "--time",
                "30",
                "--out",
                out,
            ],
        )
    };
    for (out, named) in [
        ("blocker/plan.json", "blocker"),
        ("taken.json", "taken.json"),
    ] {
        let (code, stdout, stderr) = plan_to(out);
        assert_eq!(code, 2, "{stdout}{stderr}");
        assert!(stderr.contains(named), "{stderr}");
        assert!(!stdout.contains("propagations"), "searched first: {stdout}");
    }
    // A missing folder is made.
    let (code, stdout, stderr) = plan_to("new/folder/plan.json");
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(dir.join("new/folder/plan.json").is_file());
}
