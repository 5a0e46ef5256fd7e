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

/// The size of the largest file under `dir` (bytes).
fn largest_file(dir: &Path) -> u64 {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let path = e.unwrap().path();
            match path.is_dir() {
                true => largest_file(&path),
                false => std::fs::metadata(&path).unwrap().len(),
            }
        })
        .max()
        .unwrap_or(0)
}

/// Seeded fuzzing of write failures: `render` (several pictures) and `scenes generate`
/// under file-size limits drawn at random, from none to more than the files need. Each
/// run either writes every file whole (as an unlimited run writes them) or fails with
/// exit 2, the file named, the previous files as they were and no temporary file left:
/// a limit anywhere inside a file, or between two files, never leaves a part.
#[test]
fn writes_under_random_size_limits_are_whole_or_not_at_all() {
    use pushplan::random::SplitMix64;
    let scratch = common::Scratch::new("writes-fuzz");
    let dir = scratch.path();
    let scene = std::fs::canonicalize("scenes/herb_single_object.yaml").unwrap();
    common::plan_solved(scene.to_str().unwrap(), &dir.join("plan.json"), &[]);
    let commands: [(&str, Vec<&str>); 2] = [
        ("pictures", vec!["render", "plan.json", "--out", "pictures"]),
        (
            "scenes",
            vec!["scenes", "generate", "--count", "3", "--out", "scenes"],
        ),
    ];
    let mut rng = SplitMix64::new(590);
    let (mut whole, mut refused) = (0, 0);
    for (folder, args) in &commands {
        // What an unlimited run writes, file by file.
        let (code, text) = pushplan_limited(dir, 1 << 20, args);
        assert_eq!(code, 0, "{text}");
        let written: Vec<(String, Vec<u8>)> = listing(&dir.join(folder))
            .into_iter()
            .filter(|name| {
                !std::fs::metadata(dir.join(folder).join(name))
                    .unwrap()
                    .is_dir()
            })
            .map(|name| {
                let bytes = std::fs::read(dir.join(folder).join(&name)).unwrap();
                (name, bytes)
            })
            .collect();
        // The largest file the command writes, its folders' included (a generated set
        // carries its robot), in 1 KiB blocks: limits up to twice it.
        let largest = largest_file(&dir.join(folder)) / 1024 + 2;
        for case in 0..20 {
            // The previous files: marked, so that a part of a new one would show.
            for (name, _) in &written {
                std::fs::write(dir.join(folder).join(name), format!("old {name}")).unwrap();
            }
            let blocks = rng.below(2 * largest as usize) as u32;
            let (code, text) = pushplan_limited(dir, blocks, args);
            let what = format!("{folder}, case {case}, ulimit -f {blocks}: {text}");
            let names = listing(&dir.join(folder));
            assert!(
                names.iter().all(|n| !n.ends_with(".tmp")),
                "{what}: {names:?}"
            );
            for (name, bytes) in &written {
                let now = std::fs::read(dir.join(folder).join(name)).unwrap();
                assert!(
                    now == *bytes || now == format!("old {name}").into_bytes(),
                    "{what}: {name} is neither the new file nor the old one"
                );
            }
            match code {
                0 => whole += 1,
                2 => {
                    assert!(
                        text.contains("the previous file is left as it was"),
                        "{what}"
                    );
                    refused += 1;
                }
                _ => panic!("{what}: exit {code}"),
            }
        }
    }
    assert!(whole > 0 && refused > 0, "{whole} whole, {refused} refused");
}
