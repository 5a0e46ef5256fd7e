//! The benchmark pipeline in one command: OMPL's benchmark tooling on a few generated
//! scenes, logs merged by ompl_benchmark_statistics into a Planner Arena database with
//! the expected planners, runs and pushplan's own columns; and the same grid run in
//! shards and merged.

use crate::common;

use pushplan::benchmark::grid::{Grid, Shard};
use pushplan::planning::PlannerKind;
use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::process::Command;

fn pushplan(args: &[&str], dirs: &[&Path]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_pushplan"))
        .args(args)
        .args(dirs)
        .output()
        .unwrap()
}

#[test]
fn shards_partition_the_grid() {
    let grid = Grid {
        scenes: vec![
            PathBuf::from("a.yaml"),
            PathBuf::from("b.yaml"),
            PathBuf::from("c.yaml"),
        ],
        planners: vec![PlannerKind::PcRrt, PlannerKind::Kpiece],
        runs: 5,
        time: 1.0,
        shortcut: 0.0,
        seed: 1,
        restart: None,
        fallback: None,
        threads: 1,
    };
    let all: Vec<_> = grid.cells().collect();
    assert_eq!(all.len(), 30);
    for count in [1, 2, 7, 30, 31] {
        let mut seen = HashSet::new();
        for index in 1..=count {
            for cell in grid.shard(Shard { index, count }) {
                assert!(seen.insert(cell), "{cell:?} in two shards of {count}");
            }
        }
        assert_eq!(seen.len(), all.len(), "{count} shards miss cells");
    }
    // Every shard of a few gets a share of every scene.
    for index in 1..=3 {
        let scenes: HashSet<usize> = grid
            .shard(Shard { index, count: 3 })
            .iter()
            .map(|c| c.scene)
            .collect();
        assert_eq!(scenes.len(), 3);
    }
    for bad in ["0/3", "4/3", "1/0", "3", "a/b", "-1/2"] {
        let err = bad.parse::<Shard>().unwrap_err();
        assert!(err.contains("K/N"), "{bad}: {err}");
    }
    assert_eq!("2/8".parse::<Shard>(), Ok(Shard { index: 2, count: 8 }));
}

#[test]
fn shards_merged_hold_the_runs_of_the_unsharded_benchmark() {
    let base = std::env::temp_dir().join(format!("pushplan-shards-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&base);
    let grid = [
        "scenes/benchmark/scene_00.yaml",
        "scenes/benchmark/scene_05.yaml",
        "--planners",
        "pcrrt,kpiece",
        "--runs",
        "3",
        "--time",
        "1",
        "--shortcut",
        "0",
        "--seed",
        "7",
    ];
    let whole = base.join("whole");
    let mut args = vec!["bench"];
    args.extend(grid);
    args.push("--out");
    let run = pushplan(&args, &[&whole]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let shards: Vec<PathBuf> = (1..=3).map(|k| base.join(format!("shard{k}"))).collect();
    for (k, dir) in shards.iter().enumerate() {
        let shard = format!("{}/3", k + 1);
        let mut args = args.clone();
        args.splice(args.len() - 1..args.len() - 1, ["--shard", shard.as_str()]);
        let run = pushplan(&args, &[dir]);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        assert!(
            !dir.join("results.db").exists(),
            "a shard alone is not merged"
        );
    }

    // Shard 1 interrupted: one run never ended (its log only half written), the others
    // did. --resume runs that one alone; a different grid or no benchmark is refused.
    let cells = shards[0].join("cells");
    let logs: Vec<PathBuf> = std::fs::read_dir(&cells)
        .unwrap()
        .flat_map(|scene| std::fs::read_dir(scene.unwrap().path()).unwrap())
        .map(|f| f.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "log"))
        .collect();
    assert_eq!(logs.len(), 4, "{logs:?}");
    let lost = &logs[0];
    let text = std::fs::read_to_string(lost).unwrap();
    std::fs::remove_file(lost).unwrap();
    std::fs::write(lost.with_extension("log.partial"), &text[..text.len() / 2]).unwrap();
    let mut resume = args.clone();
    resume.splice(
        resume.len() - 1..resume.len() - 1,
        ["--shard", "1/3", "--resume"],
    );
    let run = pushplan(&resume, &[&shards[0]]);
    let messages = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{messages}");
    assert!(
        messages.contains("benchmarking 1 of 12 runs") && messages.contains("3 kept from before"),
        "{messages}"
    );
    assert!(lost.is_file() && !lost.with_extension("log.partial").exists());
    let mut other_seed = resume.clone();
    let at = other_seed.iter().position(|a| *a == "7").unwrap();
    other_seed[at] = "8";
    let run = pushplan(&other_seed, &[&shards[0]]);
    let messages = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success());
    assert!(
        messages.contains("holds another benchmark or shard") && messages.contains("--resume"),
        "{messages}"
    );
    let run = pushplan(&resume, &[&base.join("never-run")]);
    let messages = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success());
    assert!(
        messages.contains("not a folder written by `pushplan bench`"),
        "{messages}"
    );

    let merged = base.join("merged");
    let dirs: Vec<&Path> = shards.iter().map(PathBuf::as_path).collect();
    let run = pushplan(
        &["bench", "merge", "--out", merged.to_str().unwrap()],
        &dirs,
    );
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let (a, b) = (
        common::benchmark_runs(&whole.join("results.db")),
        common::benchmark_runs(&merged.join("results.db")),
    );
    assert_eq!(a.len(), 2 * 2 * 3, "{a:?}");
    assert_eq!(a, b, "the merged shards hold the unsharded runs");
    assert!(
        a[0].starts_with("benchmark-00 7 3 control_KPIECE1 0"),
        "{a:?}"
    );
    assert!(merged.join("plots").join("success_vs_time.svg").is_file());

    // benches/acceptance.sh's table against the database read another way (Python's
    // sqlite3): per planner, exact solutions within 0.5 s and within the 1 s limit, and
    // the scenes with one.
    let table = Command::new("benches/acceptance.sh")
        .arg(&merged)
        .arg("0.5,1")
        .output()
        .unwrap();
    assert!(
        table.status.success(),
        "{}",
        String::from_utf8_lossy(&table.stderr)
    );
    let table = String::from_utf8_lossy(&table.stdout);
    let count = r#"
import sqlite3, sys
c = sqlite3.connect(sys.argv[1])
for (planner,) in c.execute("select name from plannerConfigs order by id"):
    runs = c.execute("""select e.name, r.status, r.time from runs r join experiments e on e.id = r.experimentid
        join plannerConfigs p on p.id = r.plannerid where p.name = ?""", (planner,)).fetchall()
    exact = [r for r in runs if r[1] == 6]
    fast = [r for r in exact if r[2] <= 0.5]
    print(f"| {planner.replace('control_', '')} | {len(runs)} | {len(fast)} / {len(exact)} | {len({r[0] for r in fast})} / {len({r[0] for r in exact})} |")
"#;
    let expected = common::query_database(count, &merged.join("results.db"));
    assert_eq!(expected.len(), 2, "{expected:?}");
    for row in &expected {
        assert!(
            table.lines().any(|l| l.starts_with(row)),
            "{row} not in\n{table}"
        );
    }

    // Merging refuses an incomplete, a doubled or a foreign set of shards.
    let out = base.join("refused");
    let run = pushplan(
        &["bench", "merge", "--out", out.to_str().unwrap()],
        &dirs[..2],
    );
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("shard 3/3 is missing"));
    let run = pushplan(
        &["bench", "merge", "--out", out.to_str().unwrap()],
        &[dirs[0], dirs[1], dirs[1]],
    );
    assert!(String::from_utf8_lossy(&run.stderr).contains("are the same shard 2/3"));
    let run = pushplan(
        &["bench", "merge", "--out", out.to_str().unwrap()],
        &[dirs[0], dirs[1], dirs[2], &whole],
    );
    assert!(String::from_utf8_lossy(&run.stderr).contains("is of 3 shards"));
    let _ = std::fs::remove_dir_all(&base);
}

#[test]
fn bench_runs_planners_on_scenes_and_merges_a_database() {
    let scratch = common::Scratch::new("bench");
    let out = scratch.path().to_path_buf();
    let scenes = [
        "scenes/benchmark/scene_00.yaml",
        "scenes/benchmark/scene_10.yaml",
        "scenes/benchmark/scene_20.yaml",
    ];
    let run = Command::new(env!("CARGO_BIN_EXE_pushplan"))
        .arg("bench")
        .args(scenes)
        .args([
            "--planners",
            "pcrrt,static,darrt,kpiece",
            "--runs",
            "2",
            "--time",
            "2",
            "--shortcut",
            "0.5",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(stderr.contains("[24/24]"), "progress is shown: {stderr}");
    let db = out.join("results.db");
    assert!(db.is_file());
    // The plots, one curve or bar per planner.
    let plots = out.join("plots");
    let curves = std::fs::read_to_string(plots.join("success_vs_time.svg")).unwrap();
    // The papers' names with the number of runs in the legend (3 scenes x 2 runs).
    for planner in ["PC RRT", "Static RRT", "DARRT", "KPIECE1"] {
        assert!(
            curves.contains(&format!("{planner} (n = 6)")),
            "{planner} missing from success_vs_time.svg"
        );
    }
    let boxes = std::fs::read_to_string(plots.join("plan_time.svg")).unwrap();
    assert!(boxes.contains("PC RRT, n = "), "plan_time.svg names n");
    for plot in [
        "plan_time.svg",
        "shortcut_path_length.svg",
        "shortcut_object_displacement.svg",
        "success_vs_objects.svg",
    ] {
        assert!(plots.join(plot).is_file(), "{plot} missing");
    }
    // Log axes labelled at 1, 2 and 5 of each decade, up to the 2 s limit.
    for tick in ["0.01", "0.02", "0.05", "0.1", "0.5", "1", "2"] {
        assert!(
            curves.contains(&format!(">\n{tick}\n</text>")),
            "no tick {tick} on the time axis"
        );
    }
    // A panel per scene, each named with its runs; every bar with its spread.
    let panels = std::fs::read_to_string(plots.join("success_vs_time_per_scene.svg")).unwrap();
    for scene in ["benchmark-00", "benchmark-10", "benchmark-20"] {
        assert!(
            panels.contains(&format!("{scene} (n = 2)")),
            "no panel of {scene}"
        );
    }
    let bars = std::fs::read_to_string(plots.join("shortcut_path_length.svg")).unwrap();
    assert!(bars.contains("95 % confidence interval"));
    let rates = std::fs::read_to_string(plots.join("success_vs_objects.svg")).unwrap();
    assert!(rates.contains("95 % Wilson intervals"));
    // A log that is not a benchmark log is refused, named; the plots are left as they were.
    std::fs::write(out.join("notes.log"), "shortcutting took long\n").unwrap();
    let refused = Command::new(env!("CARGO_BIN_EXE_pushplan"))
        .arg("plots")
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(refused.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.contains("notes.log: not an OMPL benchmark log"),
        "{stderr}"
    );
    std::fs::remove_file(out.join("notes.log")).unwrap();

    // Read the database as Planner Arena would (ompl_benchmark_statistics is Python, so
    // Python's sqlite3 is there wherever the pipeline runs).
    let query = r#"
import sqlite3, sys
c = sqlite3.connect(sys.argv[1])
print(c.execute("select count(*) from experiments").fetchone()[0])
print(",".join(sorted(r[0] for r in c.execute("select distinct name from plannerConfigs"))))
print(c.execute("select count(*) from runs").fetchone()[0])
cols = {r[1] for r in c.execute("pragma table_info(runs)")}
need = ["objects_moved", "object_displacement", "manipulator_path_length", "manipulator_path_length_shortcut", "propagation_steps_per_second"]
print(",".join(n for n in need if n not in cols) or "all columns")
print(c.execute("select count(*) from runs where solved = 1 and manipulator_path_length_shortcut <= manipulator_path_length + 1e-9").fetchone()[0],
      c.execute("select count(*) from runs where solved = 1 and manipulator_path_length_shortcut is not null").fetchone()[0])
darrt = "(select id from plannerConfigs where name = 'control_DARRT')"
print(*c.execute(f"""select count(*), sum(correct_solution), sum(objects_moved >= 1), sum(manipulator_path_length > 0),
    sum(manipulator_path_length_shortcut is null), sum(propagation_steps_per_second is null)
    from runs where plannerid in {darrt} and solved = 1""").fetchone())
print(",".join(sorted({r[0] for r in c.execute("select version from experiments")})))
"#;
    let lines = common::query_database(query, &db);
    assert_eq!(lines.len(), 7, "{lines:?}");
    assert_eq!(lines[0], "3", "one experiment per scene");
    assert_eq!(
        lines[1],
        "control_DARRT,control_KPIECE1,control_PCRRT,control_StaticRRT"
    );
    assert_eq!(lines[2], "24", "3 scenes x 4 planners x 2 runs");
    assert_eq!(lines[3], "all columns");
    let (shorter, solved) = lines[4].split_once(' ').unwrap();
    assert_eq!(shorter, solved, "shortcutting never lengthens a path");
    assert!(solved.parse::<u32>().unwrap() > 0);
    // DARRT solves the one-object scene (a single Push); each of its solutions passed the
    // primitive check, moved the goal object and has its measures, but neither a
    // shortcut (its paths are primitives, not controls) nor a propagation rate.
    let darrt: Vec<u32> = lines[5].split(' ').map(|v| v.parse().unwrap()).collect();
    assert!(darrt[0] >= 2, "DARRT solved {} runs", darrt[0]);
    assert!(darrt.iter().all(|&v| v == darrt[0]), "{darrt:?}");
    // The OMPL version the library was built with (Debian's leaves OMPL_VERSION empty).
    assert!(
        lines[6].starts_with("OMPL 1.") && lines[6].matches('.').count() == 2,
        "{}",
        lines[6]
    );
}

#[test]
fn bench_rejects_unknown_planners_and_bad_scenes() {
    let scratch = common::Scratch::new("bench-bad");
    let out = scratch.path().to_path_buf();
    let run = Command::new(env!("CARGO_BIN_EXE_pushplan"))
        .args([
            "bench",
            "scenes/benchmark/scene_00.yaml",
            "--planners",
            "pcrrt,rrtstar",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("unknown planner 'rrtstar'"));
    let run = Command::new(env!("CARGO_BIN_EXE_pushplan"))
        .args(["bench", "scenes/none.yaml", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("scenes/none.yaml"));
}

/// `bench --threads 2`: the KPIECE planners' runs search on two threads (one search whose
/// propagations run on lanes, as `plan --threads 2`), the others on one; each run records
/// its threads, and its search statistics count every lane's propagation steps. A planner that
/// runs one search per thread is refused several threads in a run of its own.
#[test]
fn bench_runs_the_kpiece_planners_on_threads() {
    let scratch = common::Scratch::new("bench-threads");
    let out = scratch.path().to_path_buf();
    let run = pushplan(
        &[
            "bench",
            "scenes/benchmark/scene_10.yaml",
            "--planners",
            "push_kpiece,kpiece,pcrrt",
            "--runs",
            "1",
            "--time",
            "5",
            "--shortcut",
            "0",
            "--threads",
            "2",
            "--out",
        ],
        &[&out],
    );
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    // Two threads a run, two cores or fewer: one run at a time unless told.
    let expected_jobs = (std::thread::available_parallelism().map_or(1, |n| n.get()) / 2).max(1);
    assert!(
        stderr.contains(&format!("{expected_jobs} at a time")),
        "{stderr}"
    );
    let query = r#"
import sqlite3, sys
c = sqlite3.connect(sys.argv[1])
# The steps the search statistics count (every model's) against those the rate counts
# (the search's model, credited with its lanes' steps as their iterations join the tree).
for name, threads, counted, credited, solved in c.execute("""select p.name, r.threads, r.propagation_steps,
        r.propagation_steps_per_second * r.time, r.status = 6
        from runs r join plannerConfigs p on r.plannerid = p.id order by p.name"""):
    print(name, threads, int(counted >= 0.99 * credited > 0), solved)
"#;
    let lines = common::query_database(query, &out.join("results.db"));
    assert_eq!(
        lines,
        [
            "control_KPIECE1 2 1 1",
            "control_PCRRT 1 1 1",
            "control_PushKPIECE 2 1 1"
        ],
        "threads, every lane's steps counted, solved"
    );

    // A cell runs with its grid's settings, read from the folder's manifest (the threads
    // above: two for the KPIECE planners, one for PC RRT). A cell outside the grid, or a
    // folder without a manifest, is refused with the reason.
    let log = out.join("refused.log");
    let cell = |folder: &std::path::Path, planner: &str| {
        Command::new(env!("CARGO_BIN_EXE_pushplan"))
            .arg("bench-scene")
            .arg(folder)
            .args(["--scene", "0", "--planner", planner, "--run", "0", "--log"])
            .arg(&log)
            .output()
            .unwrap()
    };
    let outside = cell(&out, "3");
    let messages = String::from_utf8_lossy(&outside.stderr);
    assert_eq!(outside.status.code(), Some(2), "{messages}");
    assert!(
        messages.contains("outside the grid of 1 scenes, 3 planners and 1 runs"),
        "{messages}"
    );
    let elsewhere = cell(&out.join("cells"), "0");
    let messages = String::from_utf8_lossy(&elsewhere.stderr);
    assert_eq!(elsewhere.status.code(), Some(2), "{messages}");
    assert!(messages.contains("grid.json"), "{messages}");
    assert!(!log.exists());
    let zero = pushplan(
        &[
            "bench",
            "scenes/benchmark/scene_10.yaml",
            "--threads",
            "0",
            "--out",
        ],
        &[&out.join("zero")],
    );
    assert_eq!(zero.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&zero.stderr).contains("--threads: must be in [1, 256]"));
}

/// The scene's `planner.goal_bias` reaches every planner, not only the RRTs: OMPL's
/// benchmark records each planner's parameters, so the database shows what each one ran
/// with (OMPL's own default, 0.05, would hide a planner that ignored the scene).
#[test]
fn every_planner_takes_the_scenes_goal_bias() {
    let scratch = common::Scratch::new("bench_goal_bias");
    let text = std::fs::read_to_string("scenes/benchmark/scene_00.yaml").unwrap();
    let scene = text.replace(
        "urdf: ../../robots/",
        &format!("urdf: {}/robots/", env!("CARGO_MANIFEST_DIR")),
    ) + "planner: {goal_bias: 0.25}\n";
    let path = scratch.join("goal_bias.yaml");
    std::fs::write(&path, scene).unwrap();
    let out = scratch.join("out");
    let planners = PlannerKind::ALL
        .iter()
        .map(|kind| kind.name())
        .collect::<Vec<_>>()
        .join(",");
    let run = pushplan(
        &[
            "bench",
            path.to_str().unwrap(),
            "--planners",
            &planners,
            "--runs",
            "1",
            "--time",
            "0.2",
            "--out",
            out.to_str().unwrap(),
        ],
        &[],
    );
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let query = r#"
import sqlite3, sys
c = sqlite3.connect(sys.argv[1])
for name, settings in c.execute("select name, settings from plannerConfigs order by name"):
    bias = [s.strip() for s in settings.split(";") if s.strip().startswith("goal_bias")]
    print(name, bias[0] if bias else "none")
"#;
    let lines = common::query_database(query, &out.join("results.db"));
    assert_eq!(lines.len(), planners.split(',').count(), "{lines:?}");
    for line in lines {
        assert!(line.ends_with("goal_bias = 0.25"), "{line}");
    }
}

#[test]
fn ab_script_counts_each_binarys_solved_runs_and_their_time_ratio() {
    // B: a stand-in that never solves (the first line of `plan`'s report of such a run).
    let scratch = common::Scratch::new("ab");
    let never = scratch.join("never-solves");
    std::fs::write(
        &never,
        "#!/bin/sh\necho 'not solved (approximate path written) in 2.000 s'\n",
    )
    .unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&never, std::fs::Permissions::from_mode(0o755)).unwrap();
    let run = Command::new("benches/ab.sh")
        .arg(env!("CARGO_BIN_EXE_pushplan"))
        .arg(&never)
        .args(["2", "1", "3", "scenes/benchmark/scene_00.yaml"])
        .output()
        .unwrap();
    let table = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{table}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    // Each pair: A, pushplan, solves scene 00 within the limit; B counts as the limit.
    // (Pair rows end with whether the plan files are the same; B writes none.)
    let rows: Vec<Vec<&str>> = table
        .lines()
        .map(|l| l.split('|').map(str::trim).collect::<Vec<_>>())
        .filter(|cells| cells.len() == 7 && cells[1] == "scene_00")
        .filter(|cells| ["same", "differ", "none"].contains(&cells[5]))
        .collect();
    assert!(rows.iter().all(|cells| cells[5] == "differ"), "{table}");
    assert!(
        table.contains("plan files: 0 same, 3 differ, 0 written by neither"),
        "{table}"
    );
    let pairs: Vec<(f64, f64)> = rows
        .iter()
        .map(|cells| (cells[3].parse().unwrap(), cells[4].parse().unwrap()))
        .collect();
    assert_eq!(pairs.len(), 3, "{table}");
    assert!(pairs.iter().all(|&(a, b)| a < 2.0 && b == 2.0), "{table}");
    // The summary, recomputed from the pairs as printed (rounded to the millisecond).
    let ratio = (pairs.iter().map(|&(a, b)| (b / a).ln()).sum::<f64>() / 3.0).exp();
    let all = table
        .lines()
        .find(|l| l.starts_with("| all |"))
        .unwrap_or_else(|| panic!("no summary in\n{table}"));
    let cells: Vec<&str> = all.split('|').map(str::trim).collect();
    assert_eq!(&cells[2..5], ["3", "3", "0"], "{all}");
    let printed: f64 = cells[5].parse().unwrap();
    assert!(
        (printed - ratio).abs() <= 0.01 * ratio + 0.005,
        "{printed} against {ratio}: {table}"
    );
}

#[test]
fn ab_script_finds_the_same_plan_files_from_the_same_binary() {
    let pushplan = env!("CARGO_BIN_EXE_pushplan");
    let run = Command::new("benches/ab.sh")
        .args([
            pushplan,
            pushplan,
            "10",
            "1",
            "2",
            "scenes/benchmark/scene_00.yaml",
        ])
        .output()
        .unwrap();
    let table = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "{table}");
    assert!(
        table.contains("plan files: 2 same, 0 differ, 0 written by neither"),
        "{table}"
    );
}
