//! The `pushplan` command: plan a scene with OMPL, check a plan by re-simulating it.

use clap::{Parser, Subcommand, ValueEnum};
use pushplan::ffi::{solve, SolveOptions};
use pushplan::path::PathControl;
use pushplan::plan::{PlanFile, PlanSettings};
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
        /// pcrrt (pushes objects) or static (only the goal object moves).
        #[arg(long, value_enum, default_value_t = PlannerChoice::Pcrrt)]
        planner: PlannerChoice,
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
    },
    /// Re-simulate a plan file and report whether every state is valid and the goal is reached.
    Check { plan: PathBuf },
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

#[derive(Clone, Copy, ValueEnum)]
enum PlannerChoice {
    Pcrrt,
    Static,
}

impl PlannerChoice {
    fn name(self) -> &'static str {
        match self {
            PlannerChoice::Pcrrt => "pcrrt",
            PlannerChoice::Static => "static",
        }
    }
}

fn main() -> ExitCode {
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
        } => {
            let scene = scene.unwrap_or_else(|| PathBuf::from(DEFAULT_SCENE));
            let options = RunOptions {
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
        Command::Check { plan } => check(&plan),
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
    };
    match result {
        Ok(code) => code,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

/// The `plan` command's options.
struct RunOptions {
    time: Option<f64>,
    seed: Option<u64>,
    k: Option<u32>,
    planner: PlannerChoice,
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
        planner: planner.name().into(),
        intermediate_states: run.intermediate_states,
        progress: !quiet,
    };
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
    let variant = if planner.name() == "static" {
        scene.with_static_clutter()
    } else {
        scene.clone()
    };
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
        controls = outcome.controls;
        before = Some(outcome.before);
    }
    let settings = PlanSettings {
        planner: planner.name().into(),
        seed: options.seed,
        k: options.k,
        goal_bias: options.goal_bias,
        time_limit: options.time_limit,
        shortcut: run.shortcut,
    };
    let reference = scene_path.to_string_lossy().into_owned();
    let file = PlanFile::build(&reference, scene, &settings, &controls, before)?;
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
         object displacement {:.3} m (before {:.3} m); {} links made contact",
        a.joint_length, a.ee_length, b.joint_length, b.ee_length, a.object_displacement, b.object_displacement, a.links_in_contact
    );
    println!("plan written to {}", out.display());
    Ok(if solution.exact {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn check(path: &Path) -> Result<ExitCode, String> {
    let plan = PlanFile::read(path)?;
    let report = plan.check(path)?;
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
