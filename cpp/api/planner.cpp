// pushplan::Planner: the OMPL problem of Alg. 1 set up from a scene, solved with
// ompl::control::RRT, and the plan checked by re-simulation before it is returned.

#include "pushplan/pushplan.h"

#include "pushplan/cpp/problem/model_handle.h"
#include "pushplan/cpp/search/parallel_kpiece.h"
#include "pushplan/cpp/api/planner_source.h"
#include "pushplan/cpp/api/search_builder.h"
#include "pushplan/cpp/search/portfolio.h"
#include "pushplan/cpp/problem/problem.h"

#include <ompl/base/PlannerData.h>
#include <ompl/control/SimpleSetup.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <thread>
#include <utility>

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace pushplan
{
    namespace detail
    {
        /// `kind` if it is one of PlannerKind's values: an integer cast to the enum must not
        /// reach Rust, where an unknown discriminant is undefined behaviour.
        PlannerKind checkedKind(PlannerKind kind)
        {
            // PushKpiece is the enum's last value.
            if (static_cast<unsigned>(kind) > static_cast<unsigned>(PlannerKind::PushKpiece))
                throw Error("unknown planner kind " + std::to_string(static_cast<unsigned>(kind)));
            return kind;
        }

        /// One search per core (at least one).
        unsigned defaultThreads()
        {
            return std::max(1u, std::thread::hardware_concurrency());
        }

        /// The searches' statistics, summed by the model (reasons in name order).
        SearchStats searchStats(const std::vector<ModelHandlePtr> &models)
        {
            const bridge::SearchStats sum = summedSearchStats(models);
            SearchStats total{sum.propagations, sum.steps, sum.moved_goal_object, sum.moved_clutter, {}, {}};
            for (std::size_t i = 0; i < sum.stop_reasons.size(); ++i)
                total.stopped.emplace_back(std::string(sum.stop_reasons[i]), sum.stop_counts[i]);
            for (std::size_t i = 0; i < sum.self_collision_counts.size(); ++i)
                total.self_collisions.emplace_back(std::string(sum.self_collision_links[2 * i]),
                                                   std::string(sum.self_collision_links[2 * i + 1]),
                                                   sum.self_collision_counts[i]);
            return total;
        }

        /// A progress report on stderr, one line (Options::progress without on_progress).
        void printProgress(const Progress &p)
        {
            if (!p.note.empty())
            {
                std::fprintf(stderr, "  %s\n", p.note.c_str());
                return;
            }
            std::fprintf(stderr, "  searching: %5.1f s, %llu propagation steps, %.0f steps/s, %.0f %% propagating",
                         p.seconds, static_cast<unsigned long long>(p.propagation_steps), p.steps_per_second,
                         100.0 * p.propagating);
            if (p.tree_states)
                std::fprintf(stderr, ", tree of %zu states", *p.tree_states);
            if (p.searches > 1)
                std::fprintf(stderr, " in %u searches", p.searches);
            if (std::isfinite(p.closest_goal_distance))
                std::fprintf(stderr, ", closest to the goal %.3f", p.closest_goal_distance);
            std::fputc('\n', stderr);
        }
    }  // namespace detail

    Planner::Planner(const std::string &scene_file)
        : Planner(std::make_unique<Source>(Source{detail::asPushplanError(
              [&] { return bridge::Problem::load(detail::utf8(scene_file, "the scene file's path")); })}))
    {
    }

    Planner Planner::fromYaml(const std::string &yaml, const std::string &source)
    {
        return Planner(std::make_unique<Source>(Source{detail::asPushplanError([&] {
            return bridge::Problem::from_yaml(detail::utf8(yaml, "the scene's YAML text"),
                                              detail::utf8(source, "the scene's source label"));
        })}));
    }

    Planner::Planner(std::unique_ptr<Source> source) : source_(std::move(source))
    {
    }

    Planner::~Planner() = default;
    Planner::Planner(Planner &&) noexcept = default;
    Planner &Planner::operator=(Planner &&) noexcept = default;

    std::string Planner::sceneName() const
    {
        return std::string(source().problem->info().name);
    }

    std::vector<std::string> Planner::sceneWarnings() const
    {
        std::vector<std::string> warnings;
        for (const auto &w : source().problem->scene_warnings())
            warnings.emplace_back(w);
        return warnings;
    }

    const Planner::Source &Planner::source() const
    {
        if (!source_)
            throw Error("this pushplan::Planner was moved from: it has no scene");
        return *source_;
    }

    std::string plannerName(PlannerKind kind)
    {
        return std::string(bridge::planner_name(detail::checkedKind(kind)));
    }

    PlannerKind plannerKind(const std::string &name)
    {
        try
        {
            return bridge::planner_kind(detail::utf8(name, "the planner kind's name"));
        }
        catch (const rust::Error &e)
        {
            throw Error(e.what());
        }
    }

    double Plan::duration() const
    {
        double total = 0.0;
        for (const auto &c : controls)
            total += c.duration;
        return total;
    }

    namespace detail
    {
        /// `to` = `from`: an option given, or one that is always given (the planner).
        template <class T, class U>
        void given(T &to, const std::optional<U> &from)
        {
            if (from)
                to = static_cast<T>(*from);
        }
        template <class T>
        void given(T &to, const T &from)
        {
            to = from;
        }

        RunSettings resolve(const Options &options, const bridge::SceneInfo &info)
        {
            // The settings no option changes (Rust's, as the CLI's), on every core, a plan
            // robust; then each option given. Options has a field of each name RunSettings has.
            RunSettings run = bridge::run_settings_of_scene(checkedKind(options.planner), info.planner);
            run.threads = defaultThreads();
            run.robust_trials = bridge::plan_robust_trials();
#define PUSHPLAN_GIVEN(field) given(run.field, options.field);
            PUSHPLAN_RUN_SETTINGS_FIELDS(PUSHPLAN_GIVEN)
#undef PUSHPLAN_GIVEN
            return run;
        }

        /// Throws, naming the option, for a value out of range (a pushplan::Error once
        /// through asPushplanError, as in solve).
        static void check(const RunSettings &run)
        {
            checkedKind(run.planner);
            if (!bridge::planner_yields_controls(run.planner))
                throw Error("DARRT's paths are sequences of primitives, not controls: a plan holds controls "
                            "(measure DARRT with `pushplan bench`)");
            // The limits table's (Rust's RunSettings::check, as the CLI's), each value
            // named as Options names it.
            bridge::check_run_settings(run);
        }
    }  // namespace detail

    namespace detail
    {
        /// Where `options` send progress reports: on_progress, or stderr with `progress`.
        std::function<void(const Progress &)> reportsOf(const Options &options)
        {
            if (!options.on_progress && options.progress)
                return printProgress;
            return options.on_progress;
        }

        /// The plan's propagation step and the names of its joints and objects, the scene's.
        void nameParts(Plan &plan, const bridge::SceneInfo &info)
        {
            plan.step = info.planner.step;
            for (const auto &n : info.joint_names)
                plan.joint_names.emplace_back(n);
            for (const auto &n : info.object_names)
                plan.object_names.emplace_back(n);
        }

        /// `observed` in the flat layout, its sizes checked against the scene's.
        std::vector<double> flatObservation(const Observation &observed, const bridge::SceneInfo &info)
        {
            if (static_cast<std::size_t>(observed.q.size()) != info.dof)
                throw Error("Observation::q has " + std::to_string(observed.q.size()) + " values, the robot " +
                            std::to_string(info.dof) + " joints");
            if (observed.objects.size() != info.objects)
                throw Error("Observation::objects has " + std::to_string(observed.objects.size()) +
                            " poses, the scene " + std::to_string(info.objects) + " objects");
            std::vector<double> flat(observed.q.data(), observed.q.data() + observed.q.size());
            for (const Eigen::Vector3d &pose : observed.objects)
                flat.insert(flat.end(), pose.data(), pose.data() + 3);
            return flat;
        }

        /// `problem` starting at `observed` (checked as a scene's start is).
        rust::Box<bridge::Problem> startingAt(rust::Box<bridge::Problem> problem, const Observation &observed)
        {
            problem->set_start(slice(flatObservation(observed, problem->info())));
            return problem;
        }
    }  // namespace detail

    Plan Planner::solve(const Options &options) const
    {
        const Source &source = this->source();
        return detail::solve([&] { return source.load(); },
                             [&](const bridge::SceneInfo &info) { return detail::resolve(options, info); },
                             detail::reportsOf(options));
    }

    Plan Planner::solveFrom(const Observation &start, const Options &options) const
    {
        const Source &source = this->source();
        return detail::solve([&] { return detail::startingAt(source.load(), start); }, [&](const bridge::SceneInfo &info) { return detail::resolve(options, info); },
                             detail::reportsOf(options));
    }

    namespace detail
    {
        /// `plan`'s controls from `first` to `last` (exclusive), flat, appended to `path`.
        void appendControls(FlatPath &path, const Plan &plan, std::size_t first, std::size_t last)
        {
            for (std::size_t i = first; i < last; ++i)
            {
                const Control &c = plan.controls[i];
                path.controls.insert(path.controls.end(), c.ee_velocity.data(), c.ee_velocity.data() + 3);
                path.controls.insert(path.controls.end(), c.nullspace.data(), c.nullspace.data() + c.nullspace.size());
                path.steps.push_back(c.steps);
            }
        }

        /// The state `k` of the flat `states` (of the scene `info` describes) as an observation.
        Observation observationAt(const rust::Vec<double> &states, std::size_t k, const bridge::SceneInfo &info)
        {
            const std::size_t size = info.dof + 3 * info.objects;
            const double *state = states.data() + k * size;
            Observation out;
            out.q = Eigen::Map<const Eigen::VectorXd>(state, static_cast<Eigen::Index>(info.dof));
            for (std::size_t i = 0; i < info.objects; ++i)
                out.objects.emplace_back(Eigen::Map<const Eigen::Vector3d>(state + info.dof + 3 * i));
            return out;
        }

        /// The plan of `path` from the problem's start, which re-simulated it into `states`:
        /// checked and described as every plan is, not shortcut (it is an old plan's rest,
        /// or part of it).
        Plan described(const bridge::Finisher &finisher, const bridge::SceneInfo &info, FlatPath path,
                       const rust::Vec<double> &states)
        {
            path.states.assign(states.begin(), states.end());
            const bridge::FinishedPath finished = finish(
                finisher, path, true,
                bridge::FinishSettings{0.0, 0, 0, 0.0, false, 0, -1.0, 0, std::numeric_limits<double>::infinity(), 1});
            Plan out;
            out.solved = true;
            nameParts(out, info);
            describe(out, finisher, info, finished);
            return out;
        }
    }  // namespace detail

    Plan Planner::replan(const Plan &plan, std::size_t at, const Observation &observed, const Options &options) const
    {
        const Source &source = this->source();
        return detail::asPushplanError([&]() -> Plan {
            if (at > plan.controls.size())
                throw Error("replan: at = " + std::to_string(at) + ", but the plan has " +
                            std::to_string(plan.controls.size()) + " controls");
            const auto started = std::chrono::steady_clock::now();
            const auto seconds = [&] {
                return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
            };
            const rust::Box<bridge::Problem> problem = detail::startingAt(source.load(), observed);
            const bridge::SceneInfo info = problem->info();
            // The rest of the plan, re-simulated from the observed state and judged as every
            // front that closes the loop judges it (Rust's planning::rest).
            detail::FlatPath rest;
            detail::appendControls(rest, plan, at, plan.controls.size());
            const rust::Box<bridge::Finisher> finisher = bridge::Finisher::make(*problem);
            const bridge::RestFrom verdict = finisher->rest_from(detail::slice(rest.controls), detail::slice(rest.steps));
            if (verdict.reaches)
            {
                Plan kept = detail::described(*finisher, info, rest, verdict.states);
                kept.planning_time = seconds();
                kept.replanned = Replanned{at, true, std::nullopt};
                return kept;
            }
            // A re-plan is wanted fast: the first solution unless robustness is asked for.
            Options fast = options;
            fast.robust_trials = options.robust_trials.value_or(0u);
            if (verdict.valid > 0)
            {
                // A repair: the rest kept as far as it is valid (to its end if it ends short)
                // and an ending searched from there, with a share of the search time.
                Options repair = fast;
                repair.time_limit = bridge::repair_share() * detail::resolve(fast, info).time_limit;
                const Plan ending = solveFrom(detail::observationAt(verdict.states, verdict.valid, info), repair);
                detail::FlatPath whole;
                detail::appendControls(whole, plan, at, at + verdict.valid);
                detail::appendControls(whole, ending, 0, ending.controls.size());
                const bridge::RestFrom joined =
                    ending.solved ? finisher->rest_from(detail::slice(whole.controls), detail::slice(whole.steps))
                                  : bridge::RestFrom{};
                if (joined.reaches)
                {
                    Plan repaired = detail::described(*finisher, info, whole, joined.states);
                    repaired.planning_time = seconds();
                    repaired.tree_size = ending.tree_size;
                    repaired.propagation_steps = ending.propagation_steps;
                    repaired.search = ending.search;
                    repaired.threads = ending.threads;
                    repaired.restarts = ending.restarts;
                    repaired.fallbacks = ending.fallbacks;
                    repaired.handed_back = ending.handed_back;
                    repaired.replanned = Replanned{at, false, verdict.valid};
                    return repaired;
                }
            }
            Plan searched = solveFrom(observed, fast);
            searched.replanned = Replanned{at, false, std::nullopt};
            return searched;
        });
    }

    Plan detail::solve(const std::function<rust::Box<bridge::Problem>()> &load,
                       const std::function<RunSettings(const bridge::SceneInfo &)> &settings_of,
                       const std::function<void(const Progress &)> &application_tell, Finishing finishing)
    {
        // An exception from the application's progress callback stops the search and
        // reaches the caller as it was thrown; every other failure inside, the model's or
        // OMPL's, leaves as pushplan::Error.
        std::exception_ptr callback_failure;
        std::function<void(const Progress &)> tell;
        if (application_tell)
            tell = [&](const Progress &p) {
                try
                {
                    application_tell(p);
                }
                catch (...)
                {
                    callback_failure = std::current_exception();
                    throw;
                }
            };
        try
        {
            return solveScene(load, settings_of, tell, finishing);
        }
        catch (...)
        {
            if (callback_failure)
                std::rethrow_exception(callback_failure);
            throw;
        }
    }

    Plan detail::solveScene(const std::function<rust::Box<bridge::Problem>()> &load,
                              const std::function<RunSettings(const bridge::SceneInfo &)> &settings_of,
                              const std::function<void(const Progress &)> &tell, Finishing finishing)
    {
        // Every failure inside, the model's or OMPL's, leaves as pushplan::Error.
        return detail::asPushplanError([&]() -> Plan {
            using detail::checked;
            // The time limit counts from here: loading the scene and setting up the
            // searches are part of the time a plan takes.
            const auto started = std::chrono::steady_clock::now();
            detail::SearchBuilder builder(load);
            const bridge::SceneInfo &info = builder.info();
            const RunSettings run = settings_of(info);
            check(run);
            // The KPIECE planners run one search whose propagations use every thread
            // (detail::ParallelKPIECE); the others one search per thread (detail::Portfolio).
            // Each search and each propagation lane has a model of its own.
            const unsigned threads = run.threads;
            const bool lanes_per_search = threads > 1 && bridge::planner_shares_one_search(run.planner);
            const unsigned search_count = lanes_per_search ? 1 : threads;
            const unsigned lane_count = lanes_per_search ? detail::lanesFor(threads) : 0;
            const double time_limit = run.time_limit;
            const std::uint64_t seed = run.seed;
            const std::uint64_t fallback_steps = run.fallback_steps;

            // OMPL's log level is process-wide: quiet below warnings while planning, then put
            // back as the application had it.
            const struct LogLevelGuard
            {
                ompl::msg::LogLevel saved = ompl::msg::getLogLevel();
                LogLevelGuard() { ompl::msg::setLogLevel(std::max(saved, ompl::msg::LOG_WARN)); }
                ~LogLevelGuard() { ompl::msg::setLogLevel(saved); }
            } log_level;
            // Set up on this thread, in order: OMPL's planners draw their seeds as they are made.
            std::vector<detail::Search> searches;
            // Search i's own model, and every model (each search's, then its lanes').
            std::vector<detail::ModelHandlePtr> models, every_model;
            for (unsigned i = 0; i < search_count; ++i)
            {
                detail::BuiltSearch built = builder.search(run, detail::searchSeed(seed, i), lane_count);
                built.problem.setup->setPlanner(built.planner);
                built.problem.setup->setup();
                models.push_back(built.models[0]);
                every_model.insert(every_model.end(), built.models.begin(), built.models.end());
                searches.push_back(detail::Search{std::move(built.problem), std::move(built.planner)});
            }
            detail::Portfolio portfolio(std::move(searches), !bridge::planner_cut_at_time_limit(run.planner));

            // Search until an exact solution or the time limit; progress once a second.
            const auto elapsed = [&] {
                return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
            };
            // When searching stops: the time limit, less, once a solution is set aside in
            // robust planning, what measuring the plan once more takes (the finishing
            // measures it in worlds no solution was chosen in: `unseen_trials`).
            double search_limit = time_limit;
            // Whether the time runs out within `within` seconds (the searches ask it ahead
            // of an iteration they cannot cut: Portfolio), and whether it has.
            const std::function<bool(double)> out_of_time_within = [&](double within) {
                return elapsed() + within >= search_limit;
            };
            const std::function<bool()> out_of_time = [&] { return out_of_time_within(0.0); };
            // The models refuse to propagate past the limit: an extension of k long controls
            // (OMPL checks the limit only between extensions) ends on time. Not PDST's: it
            // stops before an iteration as long as its longest so far would overrun.
            if (bridge::planner_cut_at_time_limit(run.planner))
                for (const detail::ModelHandlePtr &m : every_model)
                    m->propagator().set_time_limit(time_limit - elapsed());
            // Each report: totals, then the rate since the last one and the share of that
            // time spent propagating (the rest is the planner: nearest neighbours, sampling).
            double next_report = 1.0, last_t = 0.0, last_propagating = 0.0;
            std::uint64_t last_steps = 0, told_fallbacks = 0, told_handed_back = 0;
            // An event rather than a periodic report: the totals so far and what happened.
            const auto tell_event = [&](std::string what) {
                if (!tell)
                    return;
                Progress p;
                p.seconds = elapsed();
                p.propagation_steps = portfolio.propagationSteps();
                p.searches = search_count;
                p.closest_goal_distance = portfolio.closestGoalDistance();
                p.note = std::move(what);
                tell(p);
            };
            const std::function<bool()> report_due = [&] {
                return tell && elapsed() >= next_report;
            };
            const std::function<void()> report = [&] {
                const double t = elapsed();
                if (const std::uint64_t fallbacks = portfolio.fallbacks(); fallbacks > told_fallbacks)
                {
                    // As many PC RRT searches as the search had threads (Fallback).
                    tell_event("the goal object has not moved in " + std::to_string(fallback_steps) +
                               " propagation steps: PC RRT searches on" +
                               (threads > 1 ? ", " + std::to_string(threads) + " independent searches" : ""));
                    told_fallbacks = fallbacks;
                }
                if (const std::uint64_t handed_back = portfolio.handedBack(); handed_back > told_handed_back)
                {
                    tell_event("PC RRT has moved the goal object nearer the goal: Push KPIECE searches on from there");
                    told_handed_back = handed_back;
                }
                Progress p;
                p.seconds = t;
                p.propagation_steps = portfolio.propagationSteps();
                const double propagating = portfolio.propagationSeconds() / threads;
                p.steps_per_second = static_cast<double>(p.propagation_steps - last_steps) / (t - last_t);
                p.propagating = (propagating - last_propagating) / (t - last_t);
                p.tree_states = portfolio.treeStates();
                p.searches = search_count;
                p.closest_goal_distance = portfolio.closestGoalDistance();
                tell(p);
                last_t = t, last_steps = p.propagation_steps, last_propagating = propagating;
                next_report = std::floor(t) + 1.0;
            };
            const auto search = [&] {
                try
                {
                    return portfolio.solve(out_of_time_within, report_due, report);
                }
                catch (const rust::Error &e)
                {
                    throw Error(std::string("planning failed: ") + e.what());
                }
            };

            // The path as found: controls with their step counts, and the states OMPL reached.
            detail::FlatPath found;
            std::optional<std::size_t> winner = search();
            const auto read_path = [&] {
                found = {};
                if (const std::optional<std::size_t> best = winner ? winner : portfolio.best())
                {
                    const oc::SimpleSetup &setup = *portfolio[*best].problem.setup;
                    found = portfolio[*best].problem.model->view()->readPath(setup.getSolutionPath());
                }
            };

            Plan plan;
            read_path();
            // Robust planning: a solution that too few perturbed re-simulations carry to the
            // goal is first shortcut toward the most robust path (`planner::finish`); if it is
            // still not robust enough it is set aside, and its search starts over with a new
            // tree (the old tree's next solutions would mostly extend it, past its goal node).
            // When the time runs out before a solution reaches the rate, the most robust one
            // set aside is the plan, its rate recorded: a plan in time, never a worse one.
            struct SetAside
            {
                std::size_t search;
                detail::FlatPath path;
                double robustness;
                std::size_t trials;
            };
            std::optional<SetAside> most_robust;
            while (winner && run.robust_trials > 0)
            {
                // Measured as found first: a solution robust as it is goes to the final
                // shortcutting without the work toward robustness.
                const rust::Box<bridge::Finisher> finisher = bridge::Finisher::make(models[*winner]->problem());
                // The rate as found is passed on: the shortcutting toward robustness compares
                // with it and need not measure it again.
                // Checks cut short by the time limit are over the trials they ran. Such a
                // check does not make a solution robust (one lucky trial is not 95 %), and
                // solutions set aside are ranked as if the trials not run had failed.
                const auto robust = [&](const bridge::FinishedPath &p) {
                    return p.robustness_trials == run.robust_trials && p.robustness >= run.robust_rate;
                };
                const auto surely = [&](double rate, std::size_t trials) {
                    return rate * static_cast<double>(trials) / run.robust_trials;
                };
                // Shortcutting toward robustness spends the whole budget on it (only toward
                // robustness: true), not shortening first.
                const auto finished = [&](double shortcut, double found_rate, std::size_t found_trials) {
                    return detail::finish(*finisher, found, true,
                                          bridge::FinishSettings{shortcut, seed, run.robust_trials, run.robust_rate,
                                                                 true, 0, found_rate, found_trials,
                                                                 search_limit - elapsed(), threads});
                };
                const double check_started = elapsed();
                const bridge::FinishedPath as_found = finished(0.0, -1.0, 0);
                const double check_seconds = elapsed() - check_started;
                const bridge::FinishedPath made_robust =
                    robust(as_found) || out_of_time()
                        ? as_found
                        : finished(run.robust_shortcut, as_found.robustness, as_found.robustness_trials);
                plan.robustness = made_robust.robustness;
                plan.robustness_trials = made_robust.robustness_trials;
                detail::FlatPath as_made_robust{
                    std::vector<double>(made_robust.controls.begin(), made_robust.controls.end()),
                    std::vector<std::size_t>(made_robust.steps.begin(), made_robust.steps.end()),
                    std::vector<double>(made_robust.states.begin(), made_robust.states.end())};
                if (robust(made_robust))
                {
                    found = std::move(as_made_robust);
                    break;
                }
                if (!most_robust || surely(plan.robustness, plan.robustness_trials) >
                                        surely(most_robust->robustness, most_robust->trials))
                {
                    most_robust = SetAside{*winner, std::move(as_made_robust), plan.robustness, plan.robustness_trials};
                    // Time kept to measure it once more, as long as its check took with half
                    // again to spare (its finished path is no longer).
                    search_limit = time_limit - 1.5 * check_seconds;
                }
                {
                    char note[320];
                    std::snprintf(note, sizeof note,
                                  "a solution reaches the goal in %.0f %% of %zu perturbed re-simulations "
                                  "(%.0f %% as found; %zu of %zu controls kept shortcutting toward robustness): "
                                  "searching on",
                                  100.0 * plan.robustness, plan.robustness_trials, 100.0 * as_found.robustness,
                                  made_robust.steps.size(), found.steps.size());
                    tell_event(note);
                }
                if (out_of_time())
                {
                    winner.reset();  // the most robust path set aside is taken below
                    break;
                }
                portfolio.restart(*winner);
                winner = search();
                read_path();
            }
            if (!winner && most_robust)
            {
                winner = most_robust->search;
                found = std::move(most_robust->path);
                plan.robustness = most_robust->robustness;
                plan.robustness_trials = most_robust->trials;
                char note[256];
                std::snprintf(note, sizeof note,
                              "no solution reached %.0f %% in time: the most robust found, %.0f %% of %zu "
                              "perturbed re-simulations, is the plan",
                              100.0 * run.robust_rate, 100.0 * plan.robustness, plan.robustness_trials);
                tell_event(note);
            }
            const bool solved = winner.has_value();
            const detail::ModelHandlePtr &model = models[winner.value_or(portfolio.best().value_or(0))];

            plan.planning_time = elapsed();
            plan.propagation_steps = portfolio.propagationSteps();
            plan.search = detail::searchStats(every_model);
            plan.threads = threads;
            plan.lanes = lane_count;
            plan.restarts = portfolio.restarts();
            plan.fallbacks = portfolio.fallbacks();
            plan.handed_back = portfolio.handedBack();
            detail::nameParts(plan, info);
            for (std::size_t i = 0; i < portfolio.size(); ++i)
            {
                const detail::Search &s = portfolio[i];
                ob::PlannerData data(s.problem.setup->getSpaceInformation());
                s.planner->getPlannerData(data);
                plan.tree_size += data.numVertices();
            }
            plan.solved = solved;
            if (found.states.empty())
                return plan;
            if (finishing == Finishing::AsFound)
            {
                describePath(plan, info, slice(found.states), slice(found.controls), slice(found.steps));
                return plan;
            }

            // Every plan is checked (re-simulating it reproduces its states) and finished
            // (shortcut, kept robust) by the model, the same way as the CLI's and bench's.
            // A robust solution was measured in the perturbed worlds as it was kept: without
            // shortcutting the path stays that one, and its robustness stands.
            const bool measured = solved && run.robust_trials > 0 && run.shortcut == 0.0;
            const rust::Box<bridge::Finisher> finisher = bridge::Finisher::make(model->problem());
            const bridge::FinishedPath path = detail::finish(
                *finisher, found, solved,
                bridge::FinishSettings{run.shortcut, seed, measured ? 0u : run.robust_trials, run.robust_rate, false,
                                       run.robust_trials,
                                       solved && run.robust_trials > 0 ? plan.robustness : -1.0,
                                       plan.robustness_trials, time_limit - elapsed(), threads});
            describe(plan, *finisher, info, path);
            return plan;
            });
    }

    void detail::describe(Plan &plan, const bridge::Finisher &finisher, const bridge::SceneInfo &info,
                          const bridge::FinishedPath &path)
    {
        plan.before_shortcut = path.before;
        plan.after_shortcut = path.after;
        if (path.robustness >= 0.0)
        {
            plan.robustness = path.robustness;
            plan.robustness_trials = path.robustness_trials;
        }
        if (path.unseen_rate >= 0.0)
        {
            plan.unseen_robustness = path.unseen_rate;
            plan.unseen_trials = path.unseen_trials;
        }
        const rust::Slice<const double> controls(path.controls.data(), path.controls.size());
        const rust::Slice<const std::size_t> steps(path.steps.data(), path.steps.size());
        describePath(plan, info, rust::Slice<const double>(path.states.data(), path.states.size()), controls, steps);
        plan.trajectory = trajectoryOf(finisher.trajectory(controls, steps), info);
        plan.contacts.resize(path.steps.size());
        for (const auto &c : path.contacts)
            plan.contacts[c.control].push_back(
                Contact{c.step, std::string(info.link_names[c.link]), std::string(info.object_names[c.object]), c.force});
    }

    void detail::describePath(Plan &plan, const bridge::SceneInfo &info, rust::Slice<const double> states,
                              rust::Slice<const double> controls, rust::Slice<const std::size_t> steps)
    {
        const detail::FlatLayout flat{info.dof, info.objects};
        for (std::size_t s = 0; s * flat.size() < states.size(); ++s)
        {
            const double *x = states.data() + s * flat.size();
            plan.joint_trajectory.emplace_back(Eigen::Map<const Eigen::VectorXd>(x, info.dof));
            std::vector<Eigen::Vector3d> poses;
            for (std::size_t o = 0; o < info.objects; ++o)
                poses.emplace_back(x[flat.object(o)], x[flat.object(o) + 1], x[flat.object(o) + 2]);
            plan.object_poses.push_back(std::move(poses));
        }
        const std::size_t cwidth = 3 + info.dof;
        for (std::size_t i = 0; i < steps.size(); ++i)
            plan.controls.push_back(controlAt(controls.data() + i * cwidth, steps[i], info));
    }

    Control detail::controlAt(const double *c, std::size_t steps, const bridge::SceneInfo &info)
    {
        return Control{Eigen::Vector3d(c[0], c[1], c[2]), Eigen::Map<const Eigen::VectorXd>(c + 3, info.dof),
                       static_cast<double>(steps) * info.planner.step, steps};
    }

    Trajectory detail::trajectoryOf(const bridge::Trajectory &trajectory, const bridge::SceneInfo &info)
    {
        Trajectory out;
        out.rate = trajectory.rate;
        for (std::size_t k = 0; k < trajectory.times.size(); ++k)
        {
            out.times.push_back(trajectory.times[k]);
            out.q.emplace_back(Eigen::Map<const Eigen::VectorXd>(trajectory.q.data() + k * info.dof, info.dof));
            std::vector<Eigen::Vector3d> poses;
            for (std::size_t o = 0; o < info.objects; ++o)
            {
                const double *p = trajectory.objects.data() + (k * info.objects + o) * 3;
                poses.emplace_back(p[0], p[1], p[2]);
            }
            out.objects.push_back(std::move(poses));
        }
        return out;
    }
}  // namespace pushplan
