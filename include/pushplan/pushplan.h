// pushplan: whole-arm rearrangement planning by quasistatic pushing.
//
// The C++ API. Load a scene (a YAML file, or YAML text built in code), choose planner
// options, solve, and read the plan as Eigen types. Errors are thrown as
// pushplan::Error with a message naming the file and field at fault.
//
//   pushplan::Planner planner("scenes/herb_fig1_clutter.yaml");
//   pushplan::Options options;
//   options.time_limit = 10.0;
//   pushplan::Plan plan = planner.solve(options);
//   if (plan.solved) { /* plan.joint_trajectory, plan.object_poses, plan.controls ... */ }
//
// Link with libpushplan.a and -lompl; `pkg-config --cflags --libs pushplan` gives the
// flags (see the README). Units: m, rad, s, N. A Planner is not thread-safe; use one per
// thread.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace ompl::control
{
    class SimpleSetup;
}

namespace pushplan
{
    /// Any failure: bad scene, bad option, internal error. what() says which and why.
    class Error : public std::runtime_error
    {
    public:
        using std::runtime_error::runtime_error;
    };

    /// The planners pushplan runs: the paper's planner, its baselines and OMPL's control
    /// planners on pushplan's problem. The same list, with the same names, is the CLI's
    /// `--planner` / `--planners` and the plan file's `planner` (plannerName()).
    enum class PlannerKind : std::uint8_t
    {
        /// Physics-constrained RRT: objects are pushed (the paper's PC RRT). "pcrrt"
        PcRrt,
        /// The same RRT where only the goal object can move; the other objects are static
        /// obstacles (the paper's Static RRT baseline). "static"
        StaticRrt,
        /// DARRT's primitives (transit, push) searched by RRT (the paper's baseline; its
        /// paths are primitive sequences, measured by `pushplan bench`). "darrt"
        Darrt,
        /// OMPL's KPIECE1 with pushplan's projection (end-effector and goal-object xy, the
        /// blockage of the goal object's way). "kpiece"
        Kpiece,
        /// OMPL's EST. "est"
        Est,
        /// OMPL's PDST. "pdst"
        Pdst,
        /// OMPL's SST (asymptotically near-optimal: searches the whole time limit). "sst"
        Sst,
        /// DARRT with a fourth primitive, PickPlace: the hand grasps an object (its scene
        /// `grasps`), carries it and sets it down (the paper's suggestion). "darrt_pick"
        DarrtPickPlace,
        /// OMPL's KPIECE1 whose controls mostly follow push headings: the tool walks round
        /// the goal object and pushes it toward the goal, or pushes what stands in its way
        /// aside (pushplan's own planner; the default). "push_kpiece"
        PushKpiece,
    };

    /// The planner's name ("pcrrt", "static", ...).
    std::string plannerName(PlannerKind kind);
    /// The planner of a name; throws pushplan::Error listing the names for another.
    PlannerKind plannerKind(const std::string &name);

    /// How far a search is: reported once a second to Options::on_progress.
    struct Progress
    {
        double seconds = 0.0;                   ///< since the search started
        std::uint64_t propagation_steps = 0;    ///< in all searches
        double steps_per_second = 0.0;          ///< since the last report
        double propagating = 0.0;               ///< share of that time spent in the physics
        std::optional<std::size_t> tree_states; ///< in all trees (RRT- and KPIECE-based planners)
        unsigned searches = 1;                  ///< running in parallel
        /// The smallest distance to the goal of a state reached so far (m for a goal disc,
        /// rad for a goal configuration; zero or negative: inside).
        double closest_goal_distance = 0.0;
        /// An event instead of a periodic report (a solution dropped as not robust, say).
        std::string note;
    };

    /// Planner options. Unset values take the scene file's `planner:` values, or the
    /// library's defaults (the same as the CLI's: Rust's `planning::RunSettings::of_scene`).
    /// Every count, duration and rate has the CLI's limit (docs/commands.md, "Input
    /// limits"): a value outside throws pushplan::Error naming it (`Options::k: must be in
    /// [1, 10000], got 1000000000 ...`) before any search.
    struct Options
    {
        PlannerKind planner = PlannerKind::PushKpiece;
        /// Time limit of the call (s), counted from its start: loading the scene, the
        /// search and the robustness checks (shortcutting stops at it too).
        std::optional<double> time_limit;
        std::optional<std::uint64_t> seed;    ///< random seed
        std::optional<unsigned> k;            ///< control samples per extension
        std::optional<double> goal_bias;      ///< probability of sampling the goal
        /// Shortcutting budget after an exact solution, in seconds of work (counted in
        /// propagation steps, so the result is deterministic); 0 turns it off. Default 3.
        std::optional<double> shortcut;
        /// Add every propagation step to the tree (OMPL RRT's intermediate_states).
        /// Default false.
        std::optional<bool> intermediate_states;
        /// Keep a solution only if at least `robust_rate` of this many re-simulations from
        /// perturbed scenes (object start poses +-5 mm / +-0.05 rad; mass, `mu_g` and
        /// pressure x U(0.8, 1.2), the arm's friction `mu_c` x U(0.5, 1.2), the centre of
        /// friction +-2 cm) reach the goal; otherwise search on, and when the time
        /// runs out first, the most robust solution found is the plan (Plan::robustness says
        /// its rate). Default 20 in solve and solveFrom, as the CLI's `plan` (a plan is
        /// robust by default), 0 in replan's search (a re-plan is wanted fast); 0 takes the
        /// first solution as found.
        std::optional<unsigned> robust_trials;
        /// Default 0.95: one perturbed world in 20 may miss (BENCHMARKS.md).
        std::optional<double> robust_rate;
        /// Shortcutting budget (seconds of work) spent on each solution that is not robust
        /// enough, toward the path that reaches the goal in the most perturbed scenes (drawn
        /// apart from the check's), before it is dropped. Default 1.5.
        std::optional<double> robust_shortcut;
        /// Perturbed worlds (drawn as the check's) every tree state carries in robust
        /// planning: an extension is kept only if it is valid in each, and the goal is
        /// reached only when each world's goal object is in the disc. Default 0: none (the
        /// check alone). Only with robust_trials > 0, in the pushing problem (not Static RRT).
        std::optional<unsigned> robust_particles;
        /// Threads to plan on; default: one per core. The KPIECE planners run one search
        /// whose extensions run in parallel on lanes (a model each: threads plus threads²/8,
        /// at least one spare and at most two per thread) and join the tree in a fixed order; the others one search per thread, in lock-step rounds
        /// counted in propagation steps. Either way the same scene, seed and thread count
        /// give the same plan.
        std::optional<unsigned> threads;
        /// A search that finds no solution within this many propagation steps starts over
        /// with a new tree, attempt i with Luby(i) times as many (1, 1, 2, 1, 1, 2, 4, ...);
        /// 0: never. Default: the planner's (Push KPIECE restarts, the others do not).
        std::optional<std::uint64_t> restart_steps;
        /// Push KPIECE only: when this many propagation steps have not moved the goal
        /// object, the search hands over to PC RRT for the rest of the time, one independent
        /// PC RRT search per thread (its guided pushes need the hand at the goal object
        /// first; PC RRT's random targets sweep the arm's postures). 0: never. Default: the
        /// planner's (Push KPIECE 1 000 000, the others 0; another planner with a value > 0
        /// is an error).
        std::optional<std::uint64_t> fallback_steps;

        /// Print progress to stderr once a second.
        bool progress = false;
        /// Called with the progress once a second and at events instead of printing it
        /// (whatever `progress` says), on the thread that called solve().
        std::function<void(const Progress &)> on_progress;
    };

    /// A link pushing an object during one propagation step.
    struct Contact
    {
        std::size_t step;    ///< step within its control
        std::string link;
        std::string object;
        double force;        ///< normal force (N)
    };

    /// How long and how disruptive a path is.
    /// Laid out as Rust's path::PathMetrics, which the bridge passes as is: keep the order.
    struct PathMetrics
    {
        double joint_length = 0.0;         ///< joint-space path length (rad)
        double ee_length = 0.0;            ///< end-effector travel (m)
        double object_displacement = 0.0;  ///< total travel of all object centres (m)
        std::size_t objects_moved = 0;
        std::size_t links_in_contact = 0;  ///< links that pushed an object
        double duration = 0.0;             ///< s
    };

    /// The end-effector action of one control.
    struct Control
    {
        Eigen::Vector3d ee_velocity;  ///< (vx, vy) m/s and omega_z rad/s, world frame
        Eigen::VectorXd nullspace;    ///< null-space sample (rad/s per joint)
        double duration;              ///< s
        std::size_t steps;            ///< propagation steps (duration / step)
    };

    /// The executable trajectory, as plan files hold it: every propagation step timed so
    /// that no joint exceeds its URDF velocity limit or the scene's acceleration limit and
    /// no pushed object moves faster than the scene allows (at rest at each control's
    /// end), sampled at `rate` Hz, with the object poses the model predicts.
    struct Trajectory
    {
        double rate = 0.0;                                   ///< samples per second
        std::vector<double> times;                           ///< s
        std::vector<Eigen::VectorXd> q;                      ///< joint values per sample
        std::vector<std::vector<Eigen::Vector3d>> objects;   ///< (x, y, yaw) per object
    };

    /// What a search's propagations did: diagnostics, not part of the plan.
    struct SearchStats
    {
        std::uint64_t propagations = 0;       ///< runs of steps from a tree state
        std::uint64_t steps = 0;              ///< propagation steps in all
        std::uint64_t moved_goal_object = 0;  ///< propagations that moved the goal object
        std::uint64_t moved_clutter = 0;      ///< ... that moved another object
        /// Propagations stopped early, by the rule a step broke ("objects too close",
        /// "jammed", "joint limit", ...).
        std::vector<std::pair<std::string, std::uint64_t>> stopped;
        /// Of the self-collision stops, by link pair (names in order): a pair a robot's
        /// searches keep stopping on usually belongs in the scene's allowed_collisions.
        std::vector<std::tuple<std::string, std::string, std::uint64_t>> self_collisions;
    };

    /// A state observed while a plan runs, as a robot's joint encoders and perception
    /// report it: in the scene's orders (Plan::joint_names, Plan::object_names).
    struct Observation
    {
        Eigen::VectorXd q;                     ///< joint values (rad, or m)
        std::vector<Eigen::Vector3d> objects;  ///< (x, y, yaw) per object: m, m, rad; world frame
    };

    /// Where a re-planned plan (Planner::replan) comes from.
    struct Replanned
    {
        std::size_t at = 0;  ///< the control of the old plan at whose start the world was observed
        /// The old plan's remaining controls still reached the goal from the observed state
        /// and are this plan's (no search); false: this plan was repaired or searched anew.
        bool kept = false;
        /// A repair: this many of the old plan's controls from `at` were valid from the
        /// observed state and begin this plan, and an ending searched from where they end
        /// follows. Unset: kept whole, or searched anew from the observed state.
        std::optional<std::size_t> repaired;
    };

    struct Plan
    {
        bool solved = false;          ///< an exact solution: the goal is reached
        double planning_time = 0.0;   ///< s
        std::size_t tree_size = 0;    ///< tree nodes, all searches
        std::uint64_t propagation_steps = 0;
        SearchStats search;           ///< summed over the searches
        unsigned threads = 1;         ///< threads planned on (Options::threads)
        /// Lanes the one search's extensions ran on: more than the threads, so that a
        /// thread rarely waits for another's extension (0: one thread, or a planner that
        /// runs one search per thread).
        unsigned lanes = 0;
        /// Attempts that found no solution within their budget and started over
        /// (Options::restart_steps), all searches.
        std::uint64_t restarts = 0;
        /// Searches that handed over to PC RRT (Options::fallback_steps).
        std::uint64_t fallbacks = 0;
        /// Times such a search handed the problem back to Push KPIECE, from a state where
        /// PC RRT had moved the goal object nearer the goal.
        std::uint64_t handed_back = 0;
        double step = 0.0;            ///< propagation step (s)
        std::vector<std::string> joint_names;
        std::vector<std::string> object_names;
        /// States: joint values and object poses (x, y, yaw) at the start and after each
        /// control: controls.size() + 1 entries.
        std::vector<Eigen::VectorXd> joint_trajectory;
        std::vector<std::vector<Eigen::Vector3d>> object_poses;
        std::vector<Control> controls;
        /// Per control, the pushes during its steps.
        std::vector<std::vector<Contact>> contacts;
        /// The path as found and after shortcutting (equal when not shortcut).
        PathMetrics before_shortcut;
        PathMetrics after_shortcut;
        /// What a controller plays (empty without a path).
        Trajectory trajectory;
        /// Fraction of the perturbed re-simulations that reached the goal (-1: not checked,
        /// Options::robust_trials was 0). Below Options::robust_rate when no solution reached
        /// it within the time limit: the plan is then the most robust solution found.
        double robustness = -1.0;
        /// The perturbed re-simulations `robustness` is over: Options::robust_trials, or fewer
        /// where the time limit cut the check short (the first of them: the same seed and this
        /// many trials measure it again). 0 when not checked.
        std::size_t robustness_trials = 0;
        /// The plan's rate in as many perturbed worlds as the check has, drawn apart from
        /// the check's (-1: not measured: not robust planning, or the time limit came
        /// first). Every solution is judged in the check's worlds and the plan is the first
        /// to pass there or the best set aside, so `robustness` is the luckiest of the run;
        /// this one was not chosen on.
        double unseen_robustness = -1.0;
        /// The perturbed re-simulations `unseen_robustness` is over.
        std::size_t unseen_trials = 0;
        /// Set by Planner::replan: the plan starts at the observed state, not the scene's start.
        std::optional<Replanned> replanned;
        /// Total duration of the controls (s).
        double duration() const;
    };

    /// Options of reaching a grasp (Planner::reach). Unset values take the scene file's
    /// `planner:` values.
    struct ReachOptions
    {
        std::optional<double> time_limit;   ///< search time (s)
        std::optional<std::uint64_t> seed;  ///< random seed
        /// IK-BiRRT's P_sample: the probability that an iteration adds inverse-kinematics
        /// solutions of the grasp regions to the goal tree instead of growing the trees.
        double sample_probability = 0.1;
    };

    /// A reach of a grasp (Planner::reach): joint-space waypoints, joined by straight
    /// lines, from the arm's configuration to one inside a grasp region of the object
    /// (its scene `grasps`), every object a static obstacle where it is.
    struct Reach
    {
        bool solved = false;
        double planning_time = 0.0;  ///< s
        std::string object;
        /// The first is where the arm starts; the last is in a grasp region. Empty when
        /// not solved.
        std::vector<Eigen::VectorXd> waypoints;
        std::size_t goal_samples = 0;  ///< IK solutions the goal tree was rooted at
        std::size_t tree_size = 0;     ///< states in both trees
    };

    /// Options of the OMPL problem of a scene (pushplan/ompl.h). Unset values take the
    /// scene file's `planner:` values.
    struct SetupOptions
    {
        std::optional<std::uint64_t> seed;  ///< seeds every random source of the problem
        std::optional<unsigned> k;          ///< control samples per extension (best of k)
        /// Static RRT's problem: every object but the goal object is a static obstacle.
        bool static_clutter = false;
    };

    class Planner;
    /// pushplan's problem of a scene as OMPL objects (declared in pushplan/ompl.h).
    std::shared_ptr<ompl::control::SimpleSetup> makeSetup(const Planner &planner,
                                                          const SetupOptions &options);

    class Planner
    {
    public:
        /// Loads and validates a scene file. It is read once, here: every solve and re-plan
        /// plans the scene as it was then (a re-plan does not pay for reading it again).
        explicit Planner(const std::string &scene_file);
        /// A scene from YAML text; relative paths resolve against `source`'s folder.
        static Planner fromYaml(const std::string &yaml, const std::string &source);
        ~Planner();
        /// A moved-from planner has no scene: solve() and sceneName() throw pushplan::Error.
        Planner(Planner &&) noexcept;
        Planner &operator=(Planner &&) noexcept;

        /// Plans. Throws pushplan::Error on bad options or internal failure; a search that
        /// finds no exact solution returns a Plan with solved == false (and the closest
        /// path found, if any).
        Plan solve(const Options &options = Options()) const;

        /// Plans from `start` (a state observed while a plan runs) instead of the scene's
        /// start. The state is checked as a scene's start is: an arm's tool is brought onto
        /// its pushing plane, then joint limits and every validity rule; pushplan::Error if
        /// it fails (an object deep inside the arm, two objects pressed more than 2 cm into
        /// each other; shallower, they are moved out to touch).
        Plan solveFrom(const Observation &start, const Options &options = Options()) const;

        /// Closing the loop: the rest of `plan` (of this planner) from a state observed at
        /// the start of its control `at`. The remaining controls are re-simulated from the
        /// observed state first and returned as they are if they still reach the goal
        /// (Plan::replanned->kept). If they are valid for a while and then stop being valid,
        /// or end short of the goal, they are kept to there and an ending is searched from
        /// where they end, with a quarter of the search time (a repair:
        /// Plan::replanned->repaired). Otherwise, or if the repair finds nothing, the scene
        /// is searched anew from the observed state as `options` say (solveFrom). The CLI's
        /// `replan` and `execute --closed-loop` do the same.
        Plan replan(const Plan &plan, std::size_t at, const Observation &observed,
                    const Options &options = Options()) const;

        /// Reaches a grasp of `object` with IK-BiRRT (the manipulation-planning lecture):
        /// from the scene's start, or from the end of `after` (a plan of this planner:
        /// push, then grasp). The reach is checked by the model before it is returned.
        /// Throws pushplan::Error if the object has no grasps or an option is out of range.
        Reach reach(const std::string &object, const ReachOptions &options = ReachOptions(),
                    const Plan *after = nullptr) const;

        /// The scene's name.
        std::string sceneName() const;

        /// The scene check (the CLI's `check SCENE.yaml`): what will not work or will be
        /// slow in a scene that loads, with the numbers (an object the tool tips at the
        /// pushing plane's height, the goal out of the tool's reach or over the table's
        /// edge, objects on the goal disc); empty when nothing is found.
        std::vector<std::string> sceneWarnings() const;

    private:
        friend std::shared_ptr<ompl::control::SimpleSetup> makeSetup(const Planner &planner,
                                                                     const SetupOptions &options);
        struct Source;
        explicit Planner(std::unique_ptr<Source> source);
        /// The scene's source; throws pushplan::Error for a moved-from planner.
        const Source &source() const;
        std::unique_ptr<Source> source_;
        friend class Executor;
    };

    /// Options of closed-loop execution (Executor): the CLI's `execute --closed-loop`
    /// options of the same names, with their defaults and limits (docs/commands.md). A
    /// value outside its limit throws pushplan::Error naming it
    /// (`ExecutorOptions::replan_time: must be in (0, 86400], ...`).
    struct ExecutorOptions
    {
        /// The planner of every re-plan (one that yields controls).
        PlannerKind planner = PlannerKind::PushKpiece;
        /// Seed of the first re-plan; the next ones count up from it. Default: the scene's.
        std::optional<std::uint64_t> seed;
        /// Each re-planning search's time limit (s); a search that finds nothing is tried
        /// again with twice the time, up to 8 times. Default 2.
        std::optional<double> replan_time;
        /// Threads of each re-planning search. Default: one per core.
        std::optional<unsigned> replan_threads;
        /// Shortcutting of a re-planned path before its first control is played (s of
        /// work). Default 0: the polish shortens it while the arm plays.
        std::optional<double> replan_shortcut;
        /// Shortcutting of a re-planned path while the arm plays it (s of work, as much per
        /// control as the control lasts at `speed`, until this is spent). Default 2.
        std::optional<double> replan_polish;
        /// Where the rest no longer reaches the goal, edits of it where it fails (a detour
        /// round the control that stops being valid, a push held longer or shorter) tried
        /// before any search (s of work; 0: none); one that is valid and reaches the goal
        /// is played on. Default 0 (none; why: `execute --help`).
        std::optional<double> replan_mend;
        /// Searches at most, found or not (repairs and legs count); then step() stops.
        /// Default 400.
        std::optional<std::size_t> max_replans;
        /// Search time in all, found or not (s); then step() stops. Default 300.
        std::optional<double> replan_budget;
        /// Where no search finds a way to the goal, a leg is searched: the goal object to
        /// within half this distance of the point this far ahead on its way in the last
        /// plan that reached the goal (m; 0: no legs); where that point lies off the goal
        /// disc, the leg is searched first and the goal only if none is found. Default 0.1.
        std::optional<double> replan_leg;
        /// Search a repair on a thread of its own while the arm plays the part of the rest
        /// still valid, instead of holding the arm while it searches (step() returns the
        /// next control at once; the repair is taken up at a later step, once it is done
        /// and the controls played since have lasted as long at `speed`); not where that
        /// part ends more than a leg from the goal. Default true (BENCHMARKS.md, "Repairs
        /// searched ahead").
        std::optional<bool> repair_ahead;
        /// The pace the application plays controls at, against the plan's (the polish's
        /// budget per control). Default 1.
        std::optional<double> speed;
    };

    /// What Executor::step asks the application to do.
    struct ExecutorStep
    {
        enum class Kind
        {
            /// Play `control` along `trajectory`, then observe again.
            Play,
            /// The plan is played to its end: judge the world (is the goal object in the
            /// goal disc?).
            Finished,
            /// The execution cannot go on; `why` says why.
            Stopped,
        };
        Kind kind = Kind::Finished;
        /// Play: the control to play next.
        Control control;
        /// Play: its trajectory from the observed state (the arm's joints with its tool
        /// brought onto the pushing plane), timed as Plan::trajectory is.
        Trajectory trajectory;
        /// Play: the state the model predicts at the control's end.
        Observation predicted;
        /// Stopped: why (the searches' budget spent, an observation no valid start, ...).
        std::string why;
    };

    /// An execution so far (Executor::report).
    struct ExecutorReport
    {
        std::size_t controls_played = 0;  ///< Play steps returned
        std::size_t kept = 0;             ///< observations after which the rest still reached the goal
        std::size_t invalid_rests = 0;    ///< observations after which the rest stopped being valid
        std::size_t replans = 0;          ///< searches that found a plan (repairs among them)
        std::size_t repairs = 0;          ///< of those, endings searched from where the rest stopped
        std::size_t failed_replans = 0;   ///< searches that found none in their time
        std::size_t legs = 0;             ///< legs found and played (after such a search, or first far from the disc)
        /// Observations with a link deeper inside an object than an observation may be
        /// off: the arm retraced the control it had just played (once; the next such
        /// observation stops).
        std::size_t backoffs = 0;
        double search_time = 0.0;         ///< s, found or not
        /// From each observation to the step returned (s); of the observations that
        /// re-planned only.
        std::vector<double> latencies, replan_latencies;
        std::string last_failure;  ///< why the last search that found nothing did not
        std::string stopped;       ///< why step() stopped, if it did
    };

    /// Closed-loop execution for an application that observes its own world (a robot's
    /// encoders and perception, or its simulator): after each control, pass the observed
    /// state to step(), and play what it asks. The rest of the plan is re-simulated from
    /// each observation and kept while it reaches the goal; else it is repaired, searched
    /// anew (Planner::replan's steps), or, where no search finds the goal, a leg along
    /// the goal object's way is searched; searches that find nothing are tried again
    /// with more time. An observation with a link deep inside an object (further than
    /// the executor can put down to the observation's error) is met by retracing the
    /// control just played: a Play step whose trajectory runs it backwards. What
    /// `pushplan execute --closed-loop` does in its engines.
    ///
    ///   pushplan::Executor executor(planner, plan);
    ///   for (;;) {
    ///       pushplan::ExecutorStep next = executor.step(observe());
    ///       if (next.kind != pushplan::ExecutorStep::Kind::Play) break;
    ///       play(next.trajectory);  // then let the objects come to rest
    ///   }
    class Executor
    {
    public:
        /// The executor of `plan` (a solved plan of `planner`, from its first state),
        /// re-planning in `planner`'s scene. Throws pushplan::Error for an unsolved plan or
        /// an option out of range.
        Executor(const Planner &planner, const Plan &plan, const ExecutorOptions &options = ExecutorOptions());
        ~Executor();
        Executor(Executor &&) noexcept;
        Executor &operator=(Executor &&) noexcept;

        /// What to play after the world was observed in `observed` (at rest: after a
        /// control, let the objects settle). Throws pushplan::Error for an observation of
        /// the wrong size or an internal failure; an observation that is no valid start
        /// (an object deep inside the arm) is a Stopped step.
        ExecutorStep step(const Observation &observed);

        /// The execution so far.
        ExecutorReport report() const;

    private:
        struct State;
        std::unique_ptr<State> state_;
    };
}  // namespace pushplan
