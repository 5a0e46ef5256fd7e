//! The `pushplan` command: plan a scene with OMPL, check a plan by re-simulating it.

use clap::{Parser, Subcommand};
use pushplan::execute::{ExecuteSettings, ExecutionReport};
use pushplan::ffi::{benchmark_scene, solve, BenchOptions, SolveOptions};
use pushplan::path::PathControl;
use pushplan::plan::{PlanFile, PlanSettings, RobustnessRecord};
use pushplan::planner::PlannerKind;
use pushplan::robustness::{robustness, Noise};
use pushplan::shortcut::{shortcut, ShortcutSettings};
use pushplan::Propagator;
use pushplan::Scene;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The built-in default scene: the whole-arm paper's Fig. 1 situation.
const DEFAULT_SCENE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/herb_fig1_clutter.yaml");

#[derive(Parser)]
#[command(
    name = "pushplan",
    version,
    about = "Whole-arm rearrangement planning by quasistatic pushing"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Plan a scene (default: the built-in Fig. 1 clutter scene) and write the plan file.
    Plan {
        /// Scene file (YAML).
        scene: Option<PathBuf>,
        /// Search time limit (s); default: the scene's planner.time_limit.
        #[arg(long)]
        time: Option<f64>,
        /// Random seed; default: the scene's planner.seed.
        #[arg(long)]
        seed: Option<u64>,
        /// Control samples per extension; default: the scene's planner.k.
        #[arg(long)]
        k: Option<u32>,
        /// pcrrt (pushes objects), static (only the goal object moves), or one of OMPL's
        /// control planners on the same problem: kpiece, est, pdst, sst.
        #[arg(long, default_value_t = PlannerKind::PcRrt)]
        planner: PlannerKind,
        /// Where to write the plan.
        #[arg(long, default_value = "plan.json")]
        out: PathBuf,
        /// Also render the plan's pictures into this folder.
        #[arg(long)]
        render: Option<PathBuf>,
        /// Shortcutting budget in seconds of work (0 turns it off).
        #[arg(long, default_value_t = 3.0)]
        shortcut: f64,
        /// Add every propagation step to the tree (OMPL RRT's intermediate_states; off by
        /// default, see BENCHMARKS.md).
        #[arg(long)]
        intermediate_states: bool,
        /// No progress output.
        #[arg(long)]
        quiet: bool,
        /// Keep a solution only if at least --robust-rate of this many re-simulations from
        /// perturbed scenes (as `check --noise`) reach the goal; search on otherwise.
        #[arg(long, default_value_t = 0)]
        robust: usize,
        /// The fraction of --robust re-simulations that must reach the goal.
        #[arg(long, default_value_t = 0.9)]
        robust_rate: f64,
    },
    /// Re-simulate a plan file and report whether every state is valid and the goal is
    /// reached; with --noise, also how often perturbed re-simulations still reach it.
    Check {
        plan: PathBuf,
        /// Re-simulate the plan this many times with perturbed object start poses and
        /// parameters (±5 mm, ±0.05 rad; mass, mu_g, mu_c, c x U(0.8, 1.2)).
        #[arg(long, default_value_t = 0)]
        noise: usize,
        /// Seed of the perturbations.
        #[arg(long, default_value_t = 1)]
        seed: u64,
    },
    /// Play a plan's trajectory open loop in a 3D rigid-body engine (rapier): the arm's
    /// links follow the trajectory, the objects slide, turn and tip freely. Reports how
    /// often the goal is reached, each object's final error and the first divergence.
    Execute {
        plan: PathBuf,
        /// Trials; the first is unperturbed, the others perturbed as `check --noise`.
        #[arg(long, default_value_t = 10)]
        trials: usize,
        /// Pace relative to the plan's trajectory (0.25: four times slower).
        #[arg(long, default_value_t = 1.0)]
        speed: f64,
        /// Seed of the perturbations.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Also write the report as JSON.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Write DIR/execution.html: the plan animated with the nominal execution's
        /// objects drawn over it.
        #[arg(long)]
        render: Option<PathBuf>,
    },
    /// Benchmark planners on scenes with OMPL's benchmark tooling: one OMPL log per scene
    /// (scenes run in parallel processes), merged into DIR/results.db by
    /// ompl_benchmark_statistics (Planner Arena's format).
    Bench {
        /// Scene files.
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
        /// Planners: pcrrt, static, darrt, kpiece, est, pdst, sst.
        #[arg(
            long,
            value_delimiter = ',',
            default_value = "pcrrt,static,kpiece,est,pdst,sst"
        )]
        planners: Vec<PlannerKind>,
        /// Runs per planner and scene.
        #[arg(long, default_value_t = 10)]
        runs: u32,
        /// Time limit per run (s).
        #[arg(long, default_value_t = 30.0)]
        time: f64,
        /// Output folder (logs and results.db).
        #[arg(long)]
        out: PathBuf,
        /// Scenes benchmarked at once (default: the number of cores).
        #[arg(long)]
        jobs: Option<usize>,
        /// Shortcutting budget measured after each solved run (s of work).
        #[arg(long, default_value_t = 3.0)]
        shortcut: f64,
        #[arg(long, default_value_t = 1)]
        seed: u64,
    },
    /// Draw the benchmark plots from the OMPL logs in DIR (written by `bench`) into DIR/plots.
    Plots { dir: PathBuf },
    /// One scene of `bench`, in its own process (used by `bench`).
    #[command(hide = true)]
    BenchScene {
        scene: PathBuf,
        #[arg(long, value_delimiter = ',')]
        planners: Vec<PlannerKind>,
        #[arg(long)]
        runs: u32,
        #[arg(long)]
        time: f64,
        #[arg(long)]
        shortcut: f64,
        #[arg(long)]
        seed: u64,
        #[arg(long)]
        log: PathBuf,
    },
    /// Scene sets.
    Scenes {
        #[command(subcommand)]
        action: ScenesCommand,
    },
    /// Draw a plan: snapshots.svg, timeline.svg and animation.html.
    Render {
        plan: PathBuf,
        /// Output folder.
        #[arg(long, default_value = "render")]
        out: PathBuf,
        /// Snapshot times in seconds, comma-separated (default: four control boundaries).
        #[arg(long, value_delimiter = ',')]
        times: Vec<f64>,
    },
    /// Install the CLI, libpushplan.a, the C++ headers, pushplan.pc and the CMake package
    /// (find_package(pushplan) -> pushplan::pushplan) into a prefix.
    Install {
        /// Installation prefix (e.g. ~/.local or /usr/local).
        #[arg(long)]
        prefix: PathBuf,
    },
}

#[derive(Subcommand)]
enum ScenesCommand {
    /// Generate the paper's benchmark dataset: HERB's table, the same goal object and goal
    /// disc in every scene, 1..7 movable objects, valid start states.
    Generate {
        #[arg(long, default_value_t = 35)]
        count: usize,
        /// Range of object counts, e.g. 1..7 (spread evenly over the scenes).
        #[arg(long, default_value = "1..7")]
        objects: String,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Output folder.
        #[arg(long)]
        out: PathBuf,
    },
}

fn main() -> ExitCode {
    // Output piped into `head` and the like: end quietly when the reader goes away, as
    // command-line tools do, instead of panicking on the failed write.
    // SAFETY: restoring a signal's default disposition at start-up, before any thread.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Plan {
            scene,
            time,
            seed,
            k,
            planner,
            out,
            render,
            shortcut,
            intermediate_states,
            quiet,
            robust,
            robust_rate,
        } => {
            let scene = scene.unwrap_or_else(|| PathBuf::from(DEFAULT_SCENE));
            let options = RunOptions {
                robust,
                robust_rate,
                time,
                seed,
                k,
                planner,
                shortcut,
                intermediate_states,
                quiet,
            };
            plan(&scene, &options, &out).and_then(|code| match render {
                Some(dir) => draw(&out, &dir, &[]).map(|_| code),
                None => Ok(code),
            })
        }
        Command::Check { plan, noise, seed } => check(&plan, noise, seed),
        Command::Execute {
            plan,
            trials,
            speed,
            seed,
            json,
            render,
        } => execute(
            &plan,
            trials,
            speed,
            seed,
            json.as_deref(),
            render.as_deref(),
        ),
        Command::Render { plan, out, times } => draw(&plan, &out, &times),
        Command::Scenes {
            action:
                ScenesCommand::Generate {
                    count,
                    objects,
                    seed,
                    out,
                },
        } => generate_scenes(count, &objects, seed, &out),
        Command::Bench {
            scenes,
            planners,
            runs,
            time,
            out,
            jobs,
            shortcut,
            seed,
        } => {
            let settings = BenchSettings {
                planners,
                runs,
                time,
                shortcut,
                seed,
            };
            bench(&scenes, &settings, &out, jobs)
        }
        Command::Plots { dir } => plots(&dir),
        Command::Install { prefix } => install(&prefix),
        Command::BenchScene {
            scene,
            planners,
            runs,
            time,
            shortcut,
            seed,
            log,
        } => {
            let options = BenchOptions {
                planners,
                runs,
                time_limit: time,
                seed,
                shortcut,
                log: log.to_string_lossy().into_owned(),
            };
            benchmark_scene(&scene, &options).map(|_| ExitCode::SUCCESS)
        }
    };
    match result {
        Ok(code) => code,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

fn install(prefix: &Path) -> Result<ExitCode, String> {
    let binary = std::env::current_exe().map_err(|e| format!("the running binary: {e}"))?;
    let written = pushplan::install::install(prefix, &binary)?;
    println!(
        "installed {} files into {}",
        written.len(),
        prefix.display()
    );
    Ok(ExitCode::SUCCESS)
}

/// The `plan` command's options.
struct RunOptions {
    robust: usize,
    robust_rate: f64,
    time: Option<f64>,
    seed: Option<u64>,
    k: Option<u32>,
    planner: PlannerKind,
    shortcut: f64,
    intermediate_states: bool,
    quiet: bool,
}

fn plan(scene_path: &Path, run: &RunOptions, out: &Path) -> Result<ExitCode, String> {
    let scene = Scene::load(scene_path).map_err(|e| e.to_string())?;
    let p = scene.planner.clone();
    let (planner, quiet) = (run.planner, run.quiet);
    let options = SolveOptions {
        time_limit: run.time.unwrap_or(p.time_limit),
        seed: run.seed.unwrap_or(p.seed),
        k: run.k.unwrap_or(p.k),
        goal_bias: p.goal_bias,
        planner,
        intermediate_states: run.intermediate_states,
        progress: !quiet,
        robust_trials: run.robust,
        robust_rate: run.robust_rate,
    };
    if !(0.0..=1.0).contains(&run.robust_rate) {
        return Err(format!(
            "--robust-rate must be in [0, 1], got {}",
            run.robust_rate
        ));
    }
    if !(options.time_limit.is_finite() && options.time_limit > 0.0) {
        return Err(format!(
            "--time must be positive, got {}",
            options.time_limit
        ));
    }
    if options.k == 0 {
        return Err("--k must be at least 1".into());
    }
    if !quiet {
        eprintln!(
            "planning '{}' with {} (k = {}, seed = {}, up to {} s)",
            scene.name,
            planner.name(),
            options.k,
            options.seed,
            options.time_limit
        );
    }
    if !(run.shortcut.is_finite() && run.shortcut >= 0.0) {
        return Err(format!(
            "--shortcut must be zero or positive, got {}",
            run.shortcut
        ));
    }
    let solution = solve(scene_path, &options)?;
    let variant = scene.clone().planned_by(planner);
    let mut controls =
        PathControl::from_flat(&solution.controls, &solution.steps, variant.robot.dof())?;
    let mut before = None;
    if solution.exact && run.shortcut > 0.0 {
        let settings = ShortcutSettings::from_seconds(run.shortcut, options.seed);
        let start = variant.start.clone();
        let outcome = shortcut(
            &mut Propagator::new(variant.clone()),
            &start,
            &controls,
            &settings,
        );
        if !quiet {
            eprintln!(
                "shortcutting: {} of {} attempts accepted",
                outcome.accepted, outcome.attempts
            );
        }
        // In robust planning a shortcut is kept only while it stays robust.
        let robust = run.robust == 0
            || robustness(
                &variant,
                &outcome.controls,
                &Noise::default(),
                run.robust,
                options.seed,
            )
            .success_rate
                >= run.robust_rate;
        if robust {
            controls = outcome.controls;
            before = Some(outcome.before);
        } else if !quiet {
            eprintln!("shortcutting: the shortcut path is less robust; the path as found is kept");
        }
    }
    let settings = PlanSettings {
        planner,
        seed: options.seed,
        k: options.k,
        goal_bias: options.goal_bias,
        time_limit: options.time_limit,
        shortcut: run.shortcut,
    };
    let reference = scene_path.to_string_lossy().into_owned();
    let mut file = PlanFile::build(&reference, scene, &settings, &controls, before)?;
    if run.robust > 0 && solution.exact {
        let report = robustness(
            &variant,
            &controls,
            &Noise::default(),
            run.robust,
            options.seed,
        );
        file.robustness = Some(RobustnessRecord {
            trials: run.robust,
            required_rate: run.robust_rate,
            success_rate: report.success_rate,
        });
    }
    std::fs::write(out, file.to_json())
        .map_err(|e| format!("{}: cannot write: {e}", out.display()))?;

    let status = if solution.exact {
        "solved"
    } else if solution.approximate {
        "not solved (approximate path written)"
    } else {
        "not solved"
    };
    println!(
        "{status} in {:.2} s: tree of {} states, {} propagation steps ({:.0} steps/s)",
        solution.planning_time,
        solution.tree_size,
        solution.propagation_steps,
        solution.propagation_steps as f64 / solution.planning_time.max(1e-9)
    );
    if let Some(r) = &file.robustness {
        println!(
            "robust: {:.0} % of {} perturbed re-simulations reach the goal (at least {:.0} % required)",
            100.0 * r.success_rate,
            r.trials,
            100.0 * r.required_rate
        );
    }
    let moved: Vec<&str> = file
        .objects
        .iter()
        .zip(
            file.start.objects.iter().zip(
                &file
                    .controls
                    .last()
                    .map_or(&file.start, |c| &c.state)
                    .objects,
            ),
        )
        .filter(|(_, (a, b))| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt() > 1e-3)
        .map(|(name, _)| name.as_str())
        .collect();
    let (b, a) = (&file.metrics.before_shortcut, &file.metrics.after_shortcut);
    println!(
        "path: {} controls, {:.2} s; objects moved: {}",
        file.controls.len(),
        a.duration,
        if moved.is_empty() {
            "none".to_string()
        } else {
            moved.join(", ")
        }
    );
    println!(
        "manipulator path: {:.2} rad / {:.2} m of end-effector travel (before shortcutting {:.2} rad / {:.2} m); \
         object displacement {:.3} m (before {:.3} m); {} made contact",
        a.joint_length,
        a.ee_length,
        b.joint_length,
        b.ee_length,
        a.object_displacement,
        b.object_displacement,
        match a.links_in_contact {
            1 => "1 link".to_string(),
            n => format!("{n} links"),
        }
    );
    println!("plan written to {}", out.display());
    Ok(if solution.exact {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn check(path: &Path, noise: usize, seed: u64) -> Result<ExitCode, String> {
    let plan = PlanFile::read(path)?;
    let report = plan.check(path)?;
    if noise > 0 {
        let scene = Scene::load(plan.scene_path(path))
            .map_err(|e| e.to_string())?
            .planned_by(plan.planner);
        let r = robustness(
            &scene,
            &plan.path_controls(),
            &Noise::default(),
            noise,
            seed,
        );
        println!(
            "perturbed re-simulations: {} of {noise} reach the goal ({:.0} %); goal object's final centre {:.1} mm from the planned one on average (largest {:.1} mm), spread x {:.1} mm, y {:.1} mm, yaw {:.3} rad",
            r.trials.iter().filter(|t| t.reached).count(),
            100.0 * r.success_rate,
            1e3 * r.mean_deviation,
            1e3 * r.max_deviation,
            1e3 * r.std_xy_yaw[0],
            1e3 * r.std_xy_yaw[1],
            r.std_xy_yaw[2],
        );
        for (i, t) in r.trials.iter().enumerate().filter(|(_, t)| !t.reached) {
            match &t.failure {
                Some(why) => println!("  trial {i}: {why}"),
                None => println!(
                    "  trial {i}: the goal object ends {:.1} mm outside the disc",
                    1e3 * t.goal_distance
                ),
            }
        }
    }
    println!(
        "{}: {} controls; every state valid: {}; states reproduced: {}; goal reached: {}",
        path.display(),
        plan.controls.len(),
        yes(report.all_valid),
        yes(report.states_match),
        yes(report.goal_reached)
    );
    for problem in &report.problems {
        println!("  {problem}");
    }
    println!(
        "{}",
        if report.passed() {
            "plan OK"
        } else {
            "plan FAILED"
        }
    );
    Ok(if report.passed() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn draw(plan_path: &Path, dir: &Path, times: &[f64]) -> Result<ExitCode, String> {
    let plan = PlanFile::read(plan_path)?;
    let files = pushplan::render::render(&plan, plan_path, dir, times)?;
    for file in [&files.snapshots, &files.timeline, &files.animation] {
        println!("wrote {}", file.display());
    }
    Ok(ExitCode::SUCCESS)
}

/// What every scene of a benchmark runs.
struct BenchSettings {
    planners: Vec<PlannerKind>,
    runs: u32,
    time: f64,
    shortcut: f64,
    seed: u64,
}

fn planner_list(planners: &[PlannerKind]) -> String {
    planners
        .iter()
        .map(|p| p.name())
        .collect::<Vec<_>>()
        .join(",")
}

/// Runs one `bench-scene` process per scene, `jobs` at a time, then merges the logs.
fn bench(
    scenes: &[PathBuf],
    settings: &BenchSettings,
    out: &Path,
    jobs: Option<usize>,
) -> Result<ExitCode, String> {
    if !(settings.time.is_finite() && settings.time > 0.0) || settings.runs == 0 {
        return Err("--time must be positive and --runs at least 1".into());
    }
    for scene in scenes {
        Scene::load(scene).map_err(|e| e.to_string())?; // bad scenes fail before anything runs
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let jobs = jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .max(1);
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let logs: Vec<PathBuf> = scenes
        .iter()
        .enumerate()
        .map(|(i, s)| {
            out.join(format!(
                "{i:03}_{}.log",
                s.file_stem().unwrap_or_default().to_string_lossy()
            ))
        })
        .collect();
    eprintln!(
        "benchmarking {} scenes x {} planners x {} runs, up to {} s each, {jobs} at a time",
        scenes.len(),
        settings.planners.len(),
        settings.runs,
        settings.time
    );
    let started = std::time::Instant::now();
    let mut pending: Vec<usize> = (0..scenes.len()).rev().collect();
    let mut running: Vec<(usize, std::process::Child, std::time::Instant)> = Vec::new();
    let (mut done, mut failed) = (0, Vec::new());
    while !pending.is_empty() || !running.is_empty() {
        while running.len() < jobs {
            let Some(i) = pending.pop() else { break };
            // The child's messages go to a file next to its log: a pipe nobody reads
            // until the child ends would block a child that writes much.
            let messages = std::fs::File::create(logs[i].with_extension("err"))
                .map_err(|e| format!("{}: {e}", logs[i].with_extension("err").display()))?;
            let child = std::process::Command::new(&exe)
                .arg("bench-scene")
                .arg(&scenes[i])
                .args(["--planners", &planner_list(&settings.planners)])
                .args([
                    "--runs",
                    &settings.runs.to_string(),
                    "--time",
                    &settings.time.to_string(),
                ])
                .args([
                    "--shortcut",
                    &settings.shortcut.to_string(),
                    "--seed",
                    &settings.seed.to_string(),
                ])
                .arg("--log")
                .arg(&logs[i])
                .stdout(std::process::Stdio::null())
                .stderr(messages)
                .spawn()
                .map_err(|e| format!("cannot start a benchmark process: {e}"))?;
            running.push((i, child, std::time::Instant::now()));
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
        let mut k = 0;
        while k < running.len() {
            if let Some(status) = running[k].1.try_wait().map_err(|e| e.to_string())? {
                let (i, _, since) = running.remove(k);
                done += 1;
                let stderr =
                    std::fs::read_to_string(logs[i].with_extension("err")).unwrap_or_default();
                let verdict = if status.success() {
                    "done".to_string()
                } else {
                    format!("FAILED: {}", stderr.trim())
                };
                eprintln!(
                    "[{done}/{}] {} {verdict} ({:.0} s, {:.0} s in all)",
                    scenes.len(),
                    scenes[i].display(),
                    since.elapsed().as_secs_f64(),
                    started.elapsed().as_secs_f64()
                );
                if !status.success() {
                    failed.push(i);
                }
            } else {
                k += 1;
            }
        }
    }
    let merged: Vec<&PathBuf> = logs
        .iter()
        .enumerate()
        .filter(|(i, l)| !failed.contains(i) && l.is_file())
        .map(|(_, l)| l)
        .collect();
    let db = out.join("results.db");
    let _ = std::fs::remove_file(&db);
    let status = std::process::Command::new("ompl_benchmark_statistics")
        .args(&merged)
        .arg("-d")
        .arg(&db)
        .stdout(std::process::Stdio::null())
        .status()
        .map_err(|e| format!("cannot run ompl_benchmark_statistics ({e}): install ompl-demos (bash .ci/install-packages)"))?;
    if !status.success() {
        return Err("ompl_benchmark_statistics failed".into());
    }
    println!("{} logs merged into {}", merged.len(), db.display());
    plots(out)?;
    Ok(if failed.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn plots(dir: &Path) -> Result<ExitCode, String> {
    let mut logs: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "log"))
        .collect();
    logs.sort();
    if logs.is_empty() {
        return Err(format!("{}: no OMPL benchmark logs (*.log)", dir.display()));
    }
    let logs = logs
        .iter()
        .map(|p| pushplan::benchmark::read_log(p))
        .collect::<Result<Vec<_>, _>>()?;
    for file in pushplan::benchmark::plots::write_plots(&logs, &dir.join("plots"))? {
        println!("wrote {}", file.display());
    }
    Ok(ExitCode::SUCCESS)
}

fn generate_scenes(count: usize, objects: &str, seed: u64, out: &Path) -> Result<ExitCode, String> {
    let range = objects
        .split_once("..")
        .and_then(|(a, b)| Some((a.trim().parse().ok()?, b.trim().parse().ok()?)))
        .ok_or_else(|| format!("--objects must look like 1..7, got '{objects}'"))?;
    let files = pushplan::scene::generate::generate(count, range, seed, out)?;
    println!("wrote {} scenes to {}", files.len(), out.display());
    Ok(ExitCode::SUCCESS)
}

fn yes(b: bool) -> &'static str {
    if b {
        "yes"
    } else {
        "no"
    }
}

fn execute(
    path: &Path,
    trials: usize,
    speed: f64,
    seed: u64,
    json: Option<&Path>,
    render: Option<&Path>,
) -> Result<ExitCode, String> {
    if !(speed.is_finite() && speed > 0.0) {
        return Err(format!("--speed: must be positive and finite, got {speed}"));
    }
    if trials == 0 {
        return Err("--trials: must be at least 1".into());
    }
    let plan = PlanFile::read(path)?;
    let scene = Scene::load(plan.scene_path(path)).map_err(|e| e.to_string())?;
    let settings = ExecuteSettings {
        trials,
        speed,
        seed,
        record: render.is_some(),
        ..ExecuteSettings::default()
    };
    let report = pushplan::execute::execute(&scene, &plan, &settings)?;
    print_execution(path, &scene, &report);
    if let Some(dir) = render {
        let page = pushplan::render::render_execution(&plan, path, &report.trials[0].frames, dir)?;
        println!("animation written to {}", page.display());
    }
    if let Some(json) = json {
        let text = serde_json::to_string_pretty(&report).expect("reports serialise") + "\n";
        std::fs::write(json, text).map_err(|e| format!("{}: {e}", json.display()))?;
    }
    Ok(if report.success_rate > 0.0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn print_execution(path: &Path, scene: &Scene, report: &ExecutionReport) {
    let n = report.trials.len();
    println!(
        "{}: executed {n} times in 3D (rapier) at {}x speed: {} reach the goal ({:.0} %); {} tip an object; {} bring two objects into contact",
        path.display(),
        report.speed,
        report.trials.iter().filter(|t| t.reached).count(),
        100.0 * report.success_rate,
        report.tipped_trials,
        report.object_contact_trials,
    );
    for (i, t) in report.trials.iter().enumerate() {
        let errors: Vec<String> = scene
            .objects
            .iter()
            .zip(&t.final_errors)
            .map(|(o, e)| format!("{} {:.0} mm", o.name, 1e3 * e))
            .collect();
        let divergence = match &t.first_divergence {
            None => "none".to_string(),
            Some(pushplan::execute::Divergence::Tipped { object, time }) => {
                format!("{object} tips at {time:.2} s")
            }
            Some(pushplan::execute::Divergence::ObjectContact {
                object_a,
                object_b,
                time,
            }) => format!("{object_a} touches {object_b} at {time:.2} s"),
            Some(pushplan::execute::Divergence::Drift {
                object,
                time,
                error,
            }) => format!(
                "{object} {:.0} mm off its predicted path at {time:.2} s",
                1e3 * error
            ),
        };
        println!(
            "  trial {i}{}: {}, goal object {:.0} mm {} the disc's edge; final errors: {}; first divergence: {divergence}",
            if i == 0 && n > 1 { " (nominal)" } else { "" },
            if t.reached { "reached" } else { "missed" },
            1e3 * t.goal_distance.abs(),
            if t.goal_distance <= 0.0 { "inside" } else { "outside" },
            errors.join(", "),
        );
    }
}
