//! The `pushplan` command line: its syntax (clap) and the dispatch to
//! [`cli`].

mod cli;
mod install;

use clap::{Parser, Subcommand};
use cli::within;
use cli::{
    allowed_collisions_of, bench, bench_merge, bench_scene, check, draw, execute, export,
    generate_scenes, generate_shipped_scenes, install, pick_place, plan, plots, replan, robot,
    ExecuteOptions, PickPlaceOptions, PlanOptions, ReplanOptions, RobotQuery, SearchFlags,
};
use pushplan::benchmark::grid::{Cell, Grid, Shard};
use pushplan::bridge::OmplSearch;
use pushplan::limits;
use pushplan::planner::closed_loop::{defaults, ClosedLoopOptions};
use pushplan::planning::execute::EngineKind;
use pushplan::planning::PlannerKind;
use pushplan::scene::builtin;
use pushplan::scene::generate::{Arm, Design};
use std::path::PathBuf;
use std::process::ExitCode;

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
        #[command(flatten)]
        search: SearchFlags,
        /// Where to write the plan.
        #[arg(long, default_value = "plan.json")]
        out: PathBuf,
        /// Also render the plan's pictures into this folder.
        #[arg(long)]
        render: Option<PathBuf>,
        /// No progress output.
        #[arg(long)]
        quiet: bool,
        /// The goal instead of the scene's: `grasp:OBJECT` reaches a grasp of OBJECT (its
        /// scene `grasps`) with IK-BiRRT, every object a static obstacle, no pushing.
        #[arg(long, value_name = "grasp:OBJECT")]
        goal: Option<String>,
        /// Push, then grasp: after the pushing plan reaches the goal, reach a grasp of the
        /// goal object where it now is with IK-BiRRT (the plan file holds both).
        #[arg(long)]
        grasp: bool,
        /// IK-BiRRT's P_sample: the probability that an iteration adds inverse-kinematics
        /// solutions of the grasp regions to the goal tree.
        #[arg(long, default_value_t = 0.1)]
        sample_probability: f64,
    },
    /// The rest of a plan from a state observed while it ran (a JSON file of joint values
    /// and object poses by name, docs/commands.md): the plan's remaining controls if they
    /// still reach the goal from there, else a new search from it.
    Replan {
        /// Plan file (JSON, written by `plan` or `replan`).
        plan: PathBuf,
        /// The observed state (JSON, format pushplan-observed/1).
        #[arg(long)]
        observed: PathBuf,
        /// The control at whose start the state was observed; default: the one after the
        /// plan's recorded state nearest the observation.
        #[arg(long, value_name = "CONTROL")]
        at: Option<usize>,
        /// Where to write the new plan.
        #[arg(long, default_value = "replanned.json")]
        out: PathBuf,
        /// No progress output.
        #[arg(long)]
        quiet: bool,
        #[command(flatten)]
        search: SearchFlags,
    },
    /// Re-simulate a plan file and report whether every state is valid and the goal is
    /// reached, then make it again from its scene, settings and seed and compare ("plan OK"
    /// when both agree with the file); with --noise, also how often perturbed
    /// re-simulations still reach the goal. Given a scene file, check the scene: what
    /// cannot work or will be slow, with the numbers.
    Check {
        /// Plan file (JSON, written by `plan`), or a scene file (.yaml, .yml): the scene is
        /// loaded and checked for what cannot work or will be slow (an object the tool tips
        /// at the plane's height, a goal out of reach or over the table's edge, objects on
        /// the goal disc), with the numbers; exit 1 with warnings
        plan: PathBuf,
        /// Re-simulate the plan this many times with perturbed object start poses and
        /// parameters (±5 mm, ±0.05 rad; mass, mu_g, c x U(0.8, 1.2); mu_c x U(0.5, 1.2);
        /// centres of friction ±2 cm), objects pushing one another.
        #[arg(long, default_value_t = 0, value_parser = within::count::<usize>(&limits::NOISE))]
        noise: usize,
        /// Seed of the perturbations.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Check the path only: re-simulate it, but do not make the plan again from its
        /// settings and seed (how it was made stays unconfirmed: "path OK", not "plan OK").
        #[arg(long)]
        path_only: bool,
    },
    /// Play a plan's trajectory open loop in a 3D rigid-body engine (rapier or MuJoCo): the arm's
    /// links follow the trajectory, the objects slide, turn and tip freely. Reports how
    /// often the goal is reached, each object's final error and the first divergence. Exit
    /// status: 0 when some trial reaches the goal, 1 when none does, 2 for bad input.
    Execute {
        /// Plan file (JSON, written by `plan`).
        plan: PathBuf,
        /// Trials; the first is unperturbed, the others perturbed as `check --noise`.
        #[arg(long, default_value_t = 10, value_parser = within::count::<usize>(&limits::TRIALS))]
        trials: usize,
        /// Pace relative to the plan's trajectory (0.25: four times slower).
        #[arg(long, default_value_t = 1.0, value_parser = within::real(&limits::SPEED))]
        speed: f64,
        /// Seed of the perturbations.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// The 3D engine: rapier (rigid contacts, objects on evenly spread feet) or
        /// mujoco (soft contacts, objects on their own faces and rims).
        #[arg(long, default_value_t = EngineKind::Rapier)]
        engine: EngineKind,
        /// Also write the report as JSON.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Write DIR/execution.html: the plan animated with the nominal execution's
        /// objects drawn over it.
        #[arg(long)]
        render: Option<PathBuf>,
        /// Closed loop: after each control (or when an object leaves its predicted pose
        /// by 2 cm), read the world's object poses and joints; re-simulate the rest of the
        /// plan from there, and re-plan from there when it no longer reaches the goal.
        #[arg(long)]
        closed_loop: bool,
        /// With --closed-loop: each re-planning search's time limit (s).
        #[arg(long, default_value_t = defaults::REPLAN_TIME, value_name = "SECONDS", value_parser = within::real(&limits::REPLAN_TIME))]
        replan_time: f64,
        /// With --closed-loop: threads of each re-planning search (default: one per core,
        /// as `plan --threads`: the arm waits on a re-plan, and two threads find one in
        /// about half the time).
        #[arg(long, value_name = "N", value_parser = within::count::<u32>(&limits::REPLAN_THREADS))]
        replan_threads: Option<u32>,
        /// With --closed-loop: shortcutting of each re-planned path before its first control
        /// is played (s of work; by default none: the polish below shortens it while the arm
        /// plays, and the median re-plan takes 0.03 s instead of 0.16 s, BENCHMARKS.md).
        #[arg(long, default_value_t = defaults::REPLAN_SHORTCUT, value_name = "SECONDS", value_parser = within::real(&limits::REPLAN_SHORTCUT))]
        replan_shortcut: f64,
        /// With --closed-loop: shortcutting of each re-planned path while the arm plays it
        /// (s of work, as much per control as the control lasts, until this is spent; it
        /// does not delay the arm).
        #[arg(long, default_value_t = defaults::REPLAN_POLISH, value_name = "SECONDS", value_parser = within::real(&limits::REPLAN_POLISH))]
        replan_polish: f64,
        /// With --closed-loop: where the rest of the plan no longer reaches the goal, edits
        /// of it where it fails (a detour round the control that stops being valid, a push
        /// held longer or shorter) are tried first, with this much work (s of work and as
        /// many on the clock; by default 0: none); one that is valid and reaches the goal
        /// is played on with no search. Not the default: side by side on five hard dense
        /// scenes in MuJoCo, in two runs, 16 of 24 trials reached the goal with mends and
        /// without (docs/notes/plans-in-the-world.md).
        #[arg(long, default_value_t = defaults::REPLAN_MEND, value_name = "SECONDS", value_parser = within::real(&limits::REPLAN_MEND))]
        replan_mend: f64,
        /// With --closed-loop: searches per trial at most (found or not; repairs and legs count);
        /// a trial that needs more stops with a report. The search budget bounds the time;
        /// dense trials that reach the goal search up to 157 times (BENCHMARKS.md).
        #[arg(long, default_value_t = defaults::MAX_REPLANS, value_name = "N", value_parser = within::count::<usize>(&limits::MAX_REPLANS))]
        max_replans: usize,
        /// With --closed-loop: search time per trial at most, found or not (s); each search
        /// gets no more than what is left, and a trial that needs more stops with a report
        /// (benchmark 22's trials that reach the goal search up to 240 s in all; BENCHMARKS.md)
        #[arg(long, default_value_t = defaults::REPLAN_BUDGET, value_name = "SECONDS", value_parser = within::real(&limits::REPLAN_BUDGET))]
        replan_budget: f64,
        /// With --closed-loop: where no search finds a way to the goal, a leg is searched
        /// instead: the goal object to within half this distance of the point this far
        /// ahead on its way in the last plan that reached the goal (m; 0: no legs). Where
        /// that point lies off the goal disc, the leg is searched first and the goal only
        /// if no leg is found.
        #[arg(long, default_value_t = defaults::REPLAN_LEG, value_name = "METRES", value_parser = within::real(&limits::REPLAN_LEG))]
        replan_leg: f64,
        /// With --closed-loop: search a repair on a thread of its own while the arm plays
        /// the part of the rest still valid, instead of holding the arm while it searches
        /// (not where that part ends more than a leg from the goal: there the searches run
        /// at once). On the dense scenes: as many trials reach the goal, and the arm
        /// waits a third less (BENCHMARKS.md, "Repairs searched ahead").
        #[arg(long, default_value_t = defaults::REPAIR_AHEAD, value_name = "BOOL", action = clap::ArgAction::Set)]
        repair_ahead: bool,
    },
    /// Benchmark planners on scenes with OMPL's benchmark tooling: every (scene, planner,
    /// run) in a process of its own, the logs merged into DIR/results.db (Planner Arena's
    /// format) with plots in DIR/plots. With --shard K/N, only every N-th run from the K-th
    /// on, to merge later with `bench merge`.
    #[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
    Bench {
        #[command(subcommand)]
        action: Option<BenchCommand>,
        /// Scene files.
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
        /// Planners: push_kpiece, pcrrt, static, darrt, kpiece, est, pdst, sst, darrt_pick (DARRT
        /// with PickPlace).
        #[arg(
            long,
            value_delimiter = ',',
            default_value = "push_kpiece,pcrrt,static,kpiece,est,pdst,sst"
        )]
        planners: Vec<PlannerKind>,
        /// Runs per planner and scene.
        #[arg(long, default_value_t = 10, value_parser = within::count::<u32>(&limits::RUNS))]
        runs: u32,
        /// Time limit per run (s).
        #[arg(long, default_value_t = 30.0, value_parser = within::real(&limits::TIME_LIMIT))]
        time: f64,
        /// Output folder (logs and results.db).
        #[arg(long, required = true)]
        out: Option<PathBuf>,
        /// Runs at once (default: the number of cores over --threads).
        #[arg(long, value_parser = within::count::<usize>(&limits::JOBS))]
        jobs: Option<usize>,
        /// Threads of each run of push_kpiece and kpiece, whose threads share one search
        /// (as `plan --threads`); the other planners run on one thread.
        #[arg(long, default_value_t = 1, value_parser = within::count::<u32>(&limits::THREADS))]
        threads: u32,
        /// Shortcutting budget measured after each solved run (s of work).
        #[arg(long, default_value_t = 3.0, value_parser = within::real(&limits::SHORTCUT))]
        shortcut: f64,
        /// Every run's seeds derive from this seed and the run's index.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Run only shard K of N (1 <= K <= N) of the runs, e.g. a Slurm array task's.
        #[arg(long, default_value = "1/1")]
        shard: Shard,
        /// Every planner's first restart budget in propagation steps (0: never), instead
        /// of its own (as `plan --restart`).
        #[arg(long, value_name = "STEPS")]
        restart: Option<u64>,
        /// push_kpiece's patience before it falls back to PC RRT (as `plan --fallback`),
        /// instead of its own; the other planners never fall back.
        #[arg(long, value_name = "STEPS")]
        fallback: Option<u64>,
        /// Go on with an interrupted benchmark in --out (the same grid and shard): runs
        /// whose log is there are kept, the others run.
        #[arg(long)]
        resume: bool,
    },
    /// Draw the benchmark plots from the OMPL logs in DIR (written by `bench`) into DIR/plots.
    Plots {
        /// A `bench` output folder (its OMPL logs, *.log).
        dir: PathBuf,
    },
    /// One run of one planner on one scene, in its own process (used by `bench`).
    #[command(hide = true)]
    BenchScene {
        /// The benchmark folder: its manifest holds the grid.
        out: PathBuf,
        /// The cell: indices into the grid's scenes and planners, and the run.
        #[arg(long)]
        scene: usize,
        #[arg(long)]
        planner: usize,
        #[arg(long)]
        run: u32,
        #[arg(long)]
        log: PathBuf,
    },
    /// Scene sets.
    Scenes {
        #[command(subcommand)]
        action: ScenesCommand,
    },
    /// Show a scene's robot for writing `start_joints`: its joints and limits, the tool
    /// pose of a configuration (forward kinematics; default: the scene's start) and, with
    /// --reach, configurations that put the tool on a point of the pushing plane (inverse
    /// kinematics), printed as `start_joints:` lines. A start the scene refuses is shown
    /// with the reason, not refused here.
    Robot {
        /// Scene file (YAML); default: the built-in Fig. 1 scene.
        scene: Option<PathBuf>,
        /// A configuration to show instead of the start: joint values (rad, or m for
        /// prismatic joints), comma-separated.
        #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
        joints: Option<Vec<f64>>,
        /// Find configurations with the tool at X,Y[,YAW] on the pushing plane (world
        /// frame: m, m, rad; the plane's tilt is kept).
        #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
        reach: Option<Vec<f64>>,
        /// Inverse kinematics attempts for --reach: from the shown configuration, then from
        /// random ones within the limits.
        #[arg(long, default_value_t = 50, value_parser = within::count::<usize>(&limits::IK_TRIES))]
        tries: usize,
        /// Seed of the random attempts (and of --allowed-collisions' configurations).
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Instead, compute the link pairs to leave out of self-collision checks as MoveIt's
        /// Setup Assistant does (adjacent links are never checked; of the others, pairs in
        /// collision at the zero configuration, in at least 95 % of --samples random
        /// configurations, or in none) and print them as the scene's allowed_collisions.
        #[arg(long)]
        allowed_collisions: bool,
        /// Random configurations for --allowed-collisions.
        #[arg(long, default_value_t = 10_000, value_parser = within::count::<usize>(&limits::COLLISION_SAMPLES))]
        samples: usize,
    },
    /// Pick and place one object with the arm's hand: the lecture's manipulation graph
    /// (placements x grasps x inverse kinematics; transfer and transit edges) searched by
    /// a two-level Fuzzy PRM; the path is checked and written as JSON.
    PickPlace {
        /// Scene file (YAML); default: the built-in Fig. 1 scene.
        scene: Option<PathBuf>,
        /// The object to move (it needs `grasps` in the scene).
        #[arg(long)]
        object: String,
        /// Where to put it: X,Y[,YAW] (m, m, rad); default: the scene's goal disc centre,
        /// the object's start yaw.
        #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
        to: Option<Vec<f64>>,
        /// Grasps drawn from each of the object's grasp regions.
        #[arg(long, default_value_t = 16, value_parser = within::count::<usize>(&limits::GRASPS))]
        grasps: usize,
        /// Seed of the grasps and the Fuzzy PRMs' samples.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Validity checks the search may spend.
        #[arg(long, default_value_t = 200_000, value_parser = within::count::<usize>(&limits::CHECK_BUDGET))]
        budget: usize,
        /// Where to write the path.
        #[arg(long, default_value = "pick_place.json")]
        out: PathBuf,
        /// Also draw the path (snapshots, timeline, animation) into this folder.
        #[arg(long)]
        render: Option<PathBuf>,
    },
    /// Draw a plan: snapshots.svg, timeline.svg and animation.html.
    Render {
        /// Plan file (JSON, written by `plan`).
        plan: PathBuf,
        /// Output folder.
        #[arg(long, default_value = "render")]
        out: PathBuf,
        /// Snapshot times in seconds, comma-separated (default: four control boundaries).
        #[arg(long, value_delimiter = ',')]
        times: Vec<f64>,
    },
    /// Write a plan's executable trajectory for other programs: a ROS
    /// trajectory_msgs/JointTrajectory (YAML, as `ros2 topic pub` takes it) or CSV. The
    /// trajectory is checked against the plan's controls in its scene first.
    Export {
        /// Plan file (JSON, written by `plan` or `replan`).
        plan: PathBuf,
        /// joint-trajectory: joint names, and per sample positions, velocities,
        /// accelerations and time from start; csv: a header row, then per sample the time,
        /// each joint's position, velocity and acceleration, and each object's predicted
        /// pose.
        #[arg(long)]
        format: pushplan::planning::export::ExportFormat,
        /// Where to write it (default: standard output).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Install the CLI, libpushplan.so and libpushplan.a, the C++ headers, pushplan.pc, the
    /// CMake package (find_package(pushplan) -> pushplan::pushplan, built with CMake, which
    /// must be on the PATH) and share/pushplan (scenes, robots, C++ examples, the plan
    /// files' JSON Schema) into a prefix.
    Install {
        /// Installation prefix (e.g. ~/.local or /usr/local).
        #[arg(long)]
        prefix: PathBuf,
    },
}

#[derive(Subcommand)]
enum BenchCommand {
    /// Merge the folders of a benchmark's shards (`bench --shard K/N`) into one database
    /// and one set of plots.
    Merge {
        /// The shards' output folders.
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// Output folder.
        #[arg(long)]
        out: PathBuf,
    },
}

#[derive(Subcommand)]
enum ScenesCommand {
    /// Generate a benchmark scene set for an arm (the WAM on HERB's table by default): the
    /// same goal object and goal disc in every scene, valid start states. Designs: `paper`
    /// (the whole-arm paper's: objects anywhere in reach, up to 12), `dense` (up to 20
    /// objects placed one by one, in turn scattered, covering part of the goal disc, and
    /// walling off the straight route), `occupied_goal` (1-4 objects on the goal disc, at the
    /// table's far edge in every other scene), `mixed_heights` (tall narrow and flat objects
    /// among the clutter) and `walls` (two static walls across the way, a narrow passage).
    Generate {
        /// paper, dense, occupied_goal, mixed_heights or walls (see above).
        #[arg(long, default_value = "paper")]
        design: Design,
        /// The arm: wam (on HERB's table), panda, ur5e or iiwa14 (on a table before them).
        #[arg(long, default_value = "wam")]
        robot: Arm,
        /// Number of scenes.
        #[arg(long, default_value_t = 35, value_parser = within::count::<usize>(&limits::SCENES))]
        count: usize,
        /// Range of object counts, e.g. 1..7 (spread evenly over the scenes).
        #[arg(long, default_value = "1..7")]
        objects: String,
        /// Seed of the random layouts.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Output folder.
        #[arg(long)]
        out: PathBuf,
        /// Instead, write every shipped set of every arm and design into OUT/ARM/DESIGN
        /// (the repository's `scenes/`: `--shipped --out scenes` regenerates them).
        #[arg(long, conflicts_with_all = ["design", "robot", "count", "objects", "seed"])]
        shipped: bool,
    },
}

fn main() -> ExitCode {
    // Output piped into `head` and the like: end quietly when the reader goes away, as
    // command-line tools do, instead of panicking on the failed write.
    // A file-size limit (`ulimit -f`) makes a write fail with an error instead of killing
    // the program, so that the file being written is removed and the old one kept
    // (`pushplan::output`).
    // SAFETY: setting signal dispositions at start-up, before any thread.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
    let cli = Cli::parse();
    cli::exit_code(move || run(cli.command))
}

/// The scene given, or the built-in default scene written out (with its robot) to the
/// cache folder (`pushplan::scene::builtin`).
fn scene_or_default(scene: Option<PathBuf>) -> Result<PathBuf, String> {
    match scene {
        Some(scene) => Ok(scene),
        None => builtin::write_default_scene(&builtin::cache_root()),
    }
}

/// Runs one command: its exit code, or the message of bad input.
fn run(command: Command) -> Result<ExitCode, String> {
    match command {
        Command::Plan {
            scene,
            search,
            out,
            render,
            quiet,
            goal,
            grasp,
            sample_probability,
        } => {
            let scene = scene_or_default(scene)?;
            let options = PlanOptions {
                search,
                quiet,
                grasp_goal: goal.map(|g| cli::grasp_goal(&g)).transpose()?,
                grasp_after: grasp,
                sample_probability,
                replanned: None,
            };
            plan(&OmplSearch, &scene, &options, &out).and_then(|code| match render {
                Some(dir) => draw(&out, &dir, &[]).map(|_| code),
                None => Ok(code),
            })
        }
        Command::Replan {
            plan,
            observed,
            at,
            out,
            quiet,
            search,
        } => replan(
            &OmplSearch,
            &plan,
            &observed,
            ReplanOptions { at, search, quiet },
            &out,
        ),
        Command::Check {
            plan,
            noise,
            seed,
            path_only,
        } => check(&OmplSearch, &plan, noise, seed, path_only),
        Command::Execute {
            plan,
            trials,
            speed,
            seed,
            engine,
            json,
            render,
            closed_loop,
            replan_time,
            replan_threads,
            replan_shortcut,
            replan_polish,
            replan_mend,
            max_replans,
            replan_budget,
            replan_leg,
            repair_ahead,
        } => execute(
            &plan,
            ExecuteOptions {
                trials,
                speed,
                seed,
                engine,
                json: json.as_deref(),
                render: render.as_deref(),
                closed_loop: closed_loop.then_some((
                    &OmplSearch as &dyn pushplan::planner::Search,
                    ClosedLoopOptions {
                        replan_time,
                        replan_threads: replan_threads.unwrap_or_else(cli::cores),
                        replan_shortcut,
                        replan_polish,
                        replan_mend,
                        max_replans,
                        replan_budget,
                        replan_leg,
                        repair_ahead,
                    },
                )),
            },
        ),
        Command::Render { plan, out, times } => draw(&plan, &out, &times),
        Command::Export { plan, format, out } => export(&plan, format, out.as_deref()),
        Command::PickPlace {
            scene,
            object,
            to,
            grasps,
            seed,
            budget,
            out,
            render,
        } => pick_place(
            &scene_or_default(scene)?,
            &PickPlaceOptions {
                object,
                to,
                grasps,
                seed,
                budget,
                render,
            },
            &out,
        ),
        Command::Robot {
            scene,
            joints,
            reach,
            tries,
            seed,
            allowed_collisions,
            samples,
        } => match allowed_collisions {
            true => allowed_collisions_of(&scene_or_default(scene)?, samples, seed),
            false => robot(
                &scene_or_default(scene)?,
                &RobotQuery {
                    joints,
                    reach,
                    tries,
                    seed,
                },
            ),
        },
        Command::Scenes {
            action:
                ScenesCommand::Generate {
                    design,
                    robot,
                    count,
                    objects,
                    seed,
                    out,
                    shipped,
                },
        } => match shipped {
            true => generate_shipped_scenes(&out),
            false => generate_scenes(design, robot, count, &objects, seed, &out),
        },
        Command::Bench {
            action: Some(BenchCommand::Merge { dirs, out }),
            ..
        } => bench_merge(&dirs, &out),
        Command::Bench {
            action: None,
            scenes,
            planners,
            runs,
            time,
            out,
            jobs,
            shortcut,
            seed,
            shard,
            restart,
            fallback,
            threads,
            resume,
        } => {
            let grid = Grid {
                scenes,
                planners,
                runs,
                time,
                shortcut,
                seed,
                restart,
                fallback,
                threads,
            };
            let out = out.expect("clap requires --out without a subcommand");
            bench(&grid, shard, &out, jobs, resume)
        }
        Command::Plots { dir } => plots(&dir),
        Command::Install { prefix } => install(&prefix),
        Command::BenchScene {
            out,
            scene,
            planner,
            run,
            log,
        } => bench_scene(
            &OmplSearch,
            &out,
            Cell {
                scene,
                planner,
                run,
            },
            &log,
        ),
    }
}
