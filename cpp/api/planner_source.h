// Where a Planner's scene comes from (a file or YAML text), and how failures leave the
// C++ API, shared by its sources.
#pragma once

#include "pushplan/pushplan.h"
#include "pushplan/cpp/problem/bridge_types.h"
#include "pushplan/cpp/problem/model_handle.h"
#include "pushplan/src/bridge.rs.h"
#include "rust/cxx.h"  // rust::Error

#include <functional>
#include <stdexcept>
#include <string>

namespace pushplan
{
    namespace detail
    {
        /// `value` if `ok`, else an error naming the option.
        template <typename T>
        T checked(const char *name, T value, bool ok)
        {
            if (!ok)
                throw Error(std::string("option ") + name + " is out of range: " + std::to_string(value));
            return value;
        }

        /// Runs `f`; an error of the model (rust::Error) or of OMPL (std::exception)
        /// leaves as pushplan::Error, the one exception type the API promises.
        template <typename F>
        auto asPushplanError(F &&f) -> decltype(f())
        {
            try
            {
                return f();
            }
            catch (const Error &)
            {
                throw;
            }
            catch (const rust::Error &e)
            {
                throw Error(e.what());
            }
            catch (const std::exception &e)
            {
                throw Error(std::string("OMPL: ") + e.what());
            }
        }

        /// Finishes a found path the one way the model does (re-simulated, shortcut, kept
        /// robust: planning::finish).
        inline bridge::FinishedPath finish(const bridge::Finisher &finisher, const FlatPath &found, bool solved,
                                           const bridge::FinishSettings &settings)
        {
            return finisher.finish(slice(found.controls), slice(found.steps), slice(found.states), solved, settings);
        }

        /// `plan` given the finished `path` (`finisher`'s, in the scene `info` describes):
        /// its states, controls, metrics, robustness, trajectory and contacts.
        void describe(Plan &plan, const bridge::Finisher &finisher, const bridge::SceneInfo &info,
                      const bridge::FinishedPath &path);

        /// `text` for Rust, which takes UTF-8 only; else a pushplan::Error naming `what`.
        inline rust::Str utf8(const std::string &text, const std::string &what)
        {
            try
            {
                return rust::Str(text);
            }
            catch (const std::invalid_argument &)
            {
                throw Error(what + " is not UTF-8 text");
            }
        }

        /// Options with every unset value taken from the scene (`info`).
        RunSettings resolve(const Options &options, const bridge::SceneInfo &info);

        /// What solve does with the path it found.
        enum class Finishing
        {
            /// Finishes it (re-simulated, shortcut, with its trajectory and contacts):
            /// Planner::solve.
            Whole,
            /// Hands back its controls and the states after each, its robustness if
            /// measured: the CLI finishes the path itself (planning::finish), and would
            /// otherwise pay for re-simulating it twice after the time limit.
            AsFound,
        };

        /// Plans the scene `load` reads as the settings `settings_of` gives for it (checked
        /// here, every value named), telling `tell` (if set) how far the search is: what
        /// Planner::solve and the CLI's search do. Throws pushplan::Error, or what `tell`
        /// threw (the search stopped there).
        Plan solve(const std::function<rust::Box<bridge::Problem>()> &load,
                   const std::function<RunSettings(const bridge::SceneInfo &)> &settings_of,
                   const std::function<void(const Progress &)> &tell, Finishing finishing = Finishing::Whole);

        /// solve's work, every failure as pushplan::Error (an exception of `tell` too).
        Plan solveScene(const std::function<rust::Box<bridge::Problem>()> &load,
                        const std::function<RunSettings(const bridge::SceneInfo &)> &settings_of,
                        const std::function<void(const Progress &)> &tell, Finishing finishing);

        /// `plan`'s states (the start and after each control) and controls from the flat
        /// `states`, `controls` and `steps` of the scene `info` describes.
        void describePath(Plan &plan, const bridge::SceneInfo &info, rust::Slice<const double> states,
                          rust::Slice<const double> controls, rust::Slice<const std::size_t> steps);

        /// `kind` if it is one of PlannerKind's values; else pushplan::Error.
        PlannerKind checkedKind(PlannerKind kind);

        /// One search per core (at least one).
        unsigned defaultThreads();

        /// `observed` in the flat layout, its sizes checked against the scene's.
        std::vector<double> flatObservation(const Observation &observed, const bridge::SceneInfo &info);

        /// `problem` starting at `observed` (checked as a scene's start is).
        rust::Box<bridge::Problem> startingAt(rust::Box<bridge::Problem> problem, const Observation &observed);

        /// `plan`'s controls from `first` to `last` (exclusive), flat, appended to `path`.
        void appendControls(FlatPath &path, const Plan &plan, std::size_t first, std::size_t last);

        /// The state `k` of the flat `states` (of the scene `info` describes) as an observation.
        Observation observationAt(const rust::Vec<double> &states, std::size_t k, const bridge::SceneInfo &info);

        /// The flat control at `c` (3 + dof values), held for `steps` steps, of the scene
        /// `info` describes.
        Control controlAt(const double *c, std::size_t steps, const bridge::SceneInfo &info);

        /// The model's trajectory as the API's (of the scene `info` describes).
        Trajectory trajectoryOf(const bridge::Trajectory &trajectory, const bridge::SceneInfo &info);

        /// Reaches a grasp of `object` in the scene `load` reads as the settings
        /// `settings_of` gives for it (checked here), from the flat state `start_of` gives
        /// for it: what Planner::reach and the CLI's reach do. Throws pushplan::Error.
        Reach reach(const std::function<rust::Box<bridge::Problem>()> &load, const std::string &object,
                    const std::function<ReachSettings(const bridge::SceneInfo &)> &settings_of,
                    const std::function<std::vector<double>(const bridge::SceneInfo &)> &start_of);
    }  // namespace detail

    /// A Planner's scene, read and prepared once, when the Planner is made (from a file or
    /// YAML text): every search and re-plan works on duplicates of it (preparing a dense
    /// scene's objects takes 40-80 ms, a share of a re-plan's latency).
    struct Planner::Source
    {
        rust::Box<bridge::Problem> problem;

        /// The scene as a problem of its own (from its start, the pushing problem).
        rust::Box<bridge::Problem> load() const { return problem->duplicate(); }
    };
}  // namespace pushplan
