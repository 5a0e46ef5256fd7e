#include "pushplan/cpp/problem/problem.h"

#include "pushplan/cpp/problem/control.h"
#include "pushplan/cpp/planners/darrt/darrt.h"
#include "pushplan/cpp/search/fallback.h"
#include "pushplan/cpp/problem/goal.h"
#include "pushplan/cpp/problem/nearest.h"
#include "pushplan/cpp/search/parallel_kpiece.h"
#include "pushplan/cpp/search/portfolio.h"
#include "pushplan/cpp/problem/propagator.h"
#include "pushplan/cpp/search/restarts.h"
#include "pushplan/cpp/problem/validity.h"

#include "pushplan/pushplan.h"

#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/control/SimpleDirectedControlSampler.h>
#include <ompl/control/planners/est/EST.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/planners/pdst/PDST.h>
#include <ompl/control/planners/sst/SST.h>

#include <cmath>

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace pushplan::detail
{
    std::uint_fast32_t subSeed(std::uint64_t seed, std::uint64_t stream)
    {
        std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (stream + 1);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return static_cast<std::uint_fast32_t>((z ^ (z >> 31)) & 0xFFFFFFFFULL);
    }

    SeededRRT::SeededRRT(const oc::SpaceInformationPtr &si, const ModelHandle &model, std::uint_fast32_t seed,
                         const std::string &name)
      : Seeded<oc::RRT>(si, seed)
    {
        setName(name);
        nn_ = std::make_shared<ModelNearestNeighbors<Motion>>(model);
    }

    PushProjection::PushProjection(const ob::StateSpace *space, const ModelHandle &model)
      : ob::ProjectionEvaluator(space), view_(model.view()), projection_(bridge::Projection::make(model.problem()))
    {
    }

    unsigned int PushProjection::getDimension() const
    {
        return 5;
    }

    std::vector<double> PushProjection::pushKpieceCellSizes(std::uint64_t attempt)
    {
        const double goal_object = attempt <= 1 ? 0.025 : 0.0125;
        return {0.05, 0.05, goal_object, goal_object, 0.05};
    }

    void PushProjection::defaultCellSizes()
    {
        // 5 cm in every coordinate; for the blockage, 5 cm was better on the 35 scenes
        // than 10 or 20 (BENCHMARKS.md, "The blockage").
        cellSizes_.assign(5, 0.05);
    }

    void PushProjection::project(const ob::State *state, Eigen::Ref<Eigen::VectorXd> projection) const
    {
        view_->read(state, buffer_);
        const rust::Vec<double> p = projection_->project(slice(buffer_));
        for (int i = 0; i < 5; ++i)
            projection[i] = p[i];
    }

    /// PC RRT's controls: uniform, each sampler with its own stream, from `first_stream` on.
    static void useUniformControls(const oc::ControlSpacePtr &controls, std::uint64_t seed, std::uint64_t first_stream)
    {
        auto count = std::make_shared<std::uint64_t>(0);
        controls->setControlSamplerAllocator([seed, first_stream, count](const oc::ControlSpace *c) {
            return std::make_shared<EeControlSampler>(c, subSeed(seed, first_stream + (*count)++));
        });
    }

    /// What every space information of a problem shares: the model's propagation and
    /// validity, the control durations, and Alg. 1's best of k sampled controls.
    static void configure(const oc::SpaceInformationPtr &si, const ModelHandlePtr &model, unsigned k)
    {
        const bridge::SceneInfo &info = model->info();
        si->setStateValidityChecker(std::make_shared<PushValidityChecker>(si, *model));
        si->setStatePropagator(std::make_shared<PushStatePropagator>(si, model));
        si->setPropagationStepSize(info.planner.step);
        const auto min_steps = static_cast<unsigned>(std::max(1.0, std::round(info.planner.min_duration / info.planner.step)));
        const auto max_steps = std::max(min_steps, static_cast<unsigned>(std::round(info.planner.max_duration / info.planner.step)));
        si->setMinMaxControlDuration(min_steps, max_steps);
        // Alg. 1 lines 5-8: the best of k sampled actions, by the model's distance.
        si->setDirectedControlSamplerAllocator(
            [k](const oc::SpaceInformation *s) { return std::make_shared<oc::SimpleDirectedControlSampler>(s, k); });
    }

    /// The state space X = C_R x SE(2)^M of `model`'s problem: its state samplers seeded
    /// from `seed`, its default projection on `model`.
    static std::shared_ptr<PushStateSpace> makeSpace(const ModelHandlePtr &model, std::uint64_t seed)
    {
        auto space = std::make_shared<PushStateSpace>(*model);
        auto sampler_count = std::make_shared<std::uint64_t>(0);
        space->setStateSamplerAllocator([seed, sampler_count](const ob::StateSpace *s) {
            return std::make_shared<PushStateSampler>(s->as<PushStateSpace>(), subSeed(seed, 10 + (*sampler_count)++));
        });
        space->registerDefaultProjection(std::make_shared<PushProjection>(space.get(), *model));
        return space;
    }

    /// The problem of `model` on `space` (its own, or a lane's search's): actions (vx, vy,
    /// omega_z, null-space sample), propagation, validity, start and goal.
    static Problem makeProblemOn(std::shared_ptr<PushStateSpace> space, ModelHandlePtr model, std::uint64_t seed,
                                 unsigned k)
    {
        const bridge::SceneInfo &info = model->info();
        auto controls = makeControlSpace(space, info);
        useUniformControls(controls, seed, 1000);

        auto setup = std::make_shared<oc::SimpleSetup>(controls);
        const oc::SpaceInformationPtr &si = setup->getSpaceInformation();
        configure(si, model, k);

        ob::ScopedState<> start(space);
        model->writeStart(start.get());
        setup->setStartState(start);
        setup->setGoal(std::make_shared<PushGoal>(si, model, subSeed(seed, 2)));
        // Path length in the model's metric: what SST (and any optimizing planner) minimizes.
        setup->setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si));
        return Problem{std::move(model), std::move(space), std::move(setup), k};
    }

    Problem makeProblem(ModelHandlePtr model, std::uint64_t seed, unsigned k)
    {
        std::shared_ptr<PushStateSpace> space = makeSpace(model, seed);
        return makeProblemOn(std::move(space), std::move(model), seed, k);
    }

    /// The problem's space information again, on the same state space and model, with
    /// control space and samplers of its own (uniform, PC RRT's): for a search that
    /// follows one whose controls push (Fallback).
    static oc::SpaceInformationPtr withUniformControls(const Problem &problem, std::uint64_t seed)
    {
        auto controls = makeControlSpace(problem.space, problem.model->info());
        useUniformControls(controls, seed, 3000);
        auto si = std::make_shared<oc::SpaceInformation>(problem.space, controls);
        configure(si, problem.model, problem.k);
        si->setup();
        return si;
    }

    /// Push KPIECE's controls: most along push headings, each sampler with its own stream.
    static void usePushControls(const oc::SpaceInformationPtr &si, std::uint64_t seed, const ModelHandlePtr &model)
    {
        auto count = std::make_shared<std::uint64_t>(0);
        si->getControlSpace()->setControlSamplerAllocator([seed, count, model](const oc::ControlSpace *c) {
            return std::make_shared<PushControlSampler>(c, subSeed(seed, 2000 + (*count)++), *model, PushMix{});
        });
    }

    /// What each attempt of a search of `kind` starts with (Restarting's `before_attempt`;
    /// makePlanner sets up the first, restarted or not): for Push KPIECE, the attempt's
    /// grid cells, on the search's projection and each lane's (lanes project the states
    /// they reach); else nothing.
    static Restarting::BeforeAttempt beforeAttempt(PlannerKind kind, const oc::SpaceInformationPtr &si,
                                                   const std::vector<Lane> &lanes)
    {
        if (kind != PlannerKind::PushKpiece)
            return {};
        std::vector<ob::ProjectionEvaluatorPtr> grids{si->getStateSpace()->getDefaultProjection()};
        for (const Lane &lane : lanes)
            grids.push_back(lane.projection);
        return [grids](std::uint64_t attempt) {
            for (const ob::ProjectionEvaluatorPtr &grid : grids)
                grid->setCellSizes(PushProjection::pushKpieceCellSizes(attempt));
        };
    }

    Lane makeLane(const Problem &search, ModelHandlePtr model, std::uint64_t search_seed, std::size_t index)
    {
        // Lane 0 draws the search's own streams: one lane is the search exactly.
        const std::uint64_t seed = index == 0 ? search_seed : subSeed(search_seed, 9500 + index);
        const Problem problem = makeProblemOn(search.space, model, seed, search.k);
        const oc::SpaceInformationPtr &si = problem.setup->getSpaceInformation();
        si->setup();
        auto projection = std::make_shared<PushProjection>(search.space.get(), *model);
        projection->setup();
        return Lane{si, std::move(model), std::move(projection), problem.setup->getProblemDefinition()->getGoal(),
                    seed};
    }

    /// Lane `lane`'s problem with a state space of its own, as its search's is made
    /// (makeSpace, the lane's seed): for a search that runs on the lane's thread beside
    /// others with trees of their own (the fallback's PC RRTs draw states from their
    /// spaces' samplers and measure distances with their spaces' buffers).
    static Problem laneProblem(const Lane &lane, unsigned k)
    {
        return Problem{lane.model, makeSpace(lane.model, lane.seed), nullptr, k};
    }

    /// Fallback's PC RRT on `problem`'s model and state space, seeded with `seed`, with
    /// uniform controls and a problem definition of its own (the goal `goal`; the start
    /// the Fallback's, given as it hands over), never restarted.
    static Search pcRrtFallback(const Problem &problem, const ob::GoalPtr &goal, std::uint64_t seed,
                                double goal_bias, bool intermediate_states)
    {
        const oc::SpaceInformationPtr si = withUniformControls(problem, seed);
        auto pc_rrt = std::make_shared<SeededRRT>(si, *problem.model, subSeed(seed, 4), "PCRRT");
        pc_rrt->setGoalBias(goal_bias);
        pc_rrt->setIntermediateStates(intermediate_states);
        auto setup = std::make_shared<oc::SimpleSetup>(si);
        setup->setGoal(goal);
        setup->setPlanner(pc_rrt);
        return Search{Problem{problem.model, problem.space, std::move(setup), problem.k}, std::move(pc_rrt)};
    }

    /// `planner` after setGoalBias: every planner kind takes the scene's (or the call's) goal
    /// bias, not only the RRTs (OMPL's own default, 0.05, is also the scene's default).
    template <class Planner>
    static ob::PlannerPtr withGoalBias(std::shared_ptr<Planner> planner, double goal_bias)
    {
        planner->setGoalBias(goal_bias);
        return planner;
    }

    /// OMPL's KPIECE1, or with lanes the same search with its propagations on their threads.
    static ob::PlannerPtr kpiece(const oc::SpaceInformationPtr &si, std::uint_fast32_t seed, const ModelHandlePtr &model,
                                 double goal_bias, std::vector<Lane> lanes, unsigned threads)
    {
        if (lanes.empty())
            return withGoalBias(std::make_shared<SeededKPIECE>(si, seed), goal_bias);
        return withGoalBias(std::make_shared<ParallelKPIECE>(si, seed, model, std::move(lanes), threads), goal_bias);
    }

    /// The planner of one kind, without restarts.
    static ob::PlannerPtr makeSearch(PlannerKind kind, const Problem &problem, std::uint64_t seed, double goal_bias,
                                     bool intermediate_states, std::vector<Lane> lanes, unsigned threads)
    {
        const oc::SpaceInformationPtr &si = problem.setup->getSpaceInformation();
        // The planner's own random numbers (the samplers have streams of their own).
        const std::uint_fast32_t planner_seed = subSeed(seed, 3);
        switch (kind)
        {
            case PlannerKind::PcRrt:
            case PlannerKind::StaticRrt:
            {
                auto rrt = std::make_shared<SeededRRT>(si, *problem.model, planner_seed,
                                                       kind == PlannerKind::StaticRrt ? "StaticRRT" : "PCRRT");
                rrt->setGoalBias(goal_bias);
                rrt->setIntermediateStates(intermediate_states);
                return rrt;
            }
            case PlannerKind::Darrt:
            case PlannerKind::DarrtPickPlace:
            {
                auto darrt = std::make_shared<Darrt>(si, problem.model, planner_seed);
                darrt->setGoalBias(goal_bias);
                if (kind == PlannerKind::DarrtPickPlace)
                {
                    darrt->setName("DARRTPickPlace");
                    // Half the object extensions try PickPlace first (objects with grasps).
                    darrt->setPickPlace(0.5);
                }
                return darrt;
            }
            case PlannerKind::Kpiece:
                return kpiece(si, planner_seed, problem.model, goal_bias, std::move(lanes), threads);
            case PlannerKind::PushKpiece:
            {
                usePushControls(si, seed, problem.model);
                for (const Lane &lane : lanes)
                    usePushControls(lane.si, lane.seed, lane.model);
                ob::PlannerPtr push_kpiece =
                    kpiece(si, planner_seed, problem.model, goal_bias, std::move(lanes), threads);
                push_kpiece->setName("PushKPIECE");
                return push_kpiece;
            }
            case PlannerKind::Est:
                return withGoalBias(std::make_shared<Seeded<oc::EST>>(si, planner_seed), goal_bias);
            case PlannerKind::Pdst:
                return withGoalBias(std::make_shared<Seeded<oc::PDST>>(si, planner_seed), goal_bias);
            case PlannerKind::Sst:
                return withGoalBias(std::make_shared<Seeded<oc::SST>>(si, planner_seed), goal_bias);
        }
        throw Error("unknown planner kind " + std::to_string(static_cast<int>(kind)));
    }

    ob::PlannerPtr makePlanner(PlannerKind kind, const Problem &problem, std::uint64_t seed, double goal_bias,
                               bool intermediate_states, std::uint64_t restart_steps, std::uint64_t fallback_steps,
                               std::vector<Lane> lanes, unsigned threads)
    {
        if (!lanes.empty() && !bridge::planner_shares_one_search(kind))
            throw Error(plannerName(kind) + " runs one search per thread, not one search on several");
        if (fallback_steps > 0 && kind != PlannerKind::PushKpiece)
            throw Error("fallback_steps: only push_kpiece falls back (to pcrrt), not " + plannerName(kind));
        Restarting::BeforeAttempt before_attempt =
            beforeAttempt(kind, problem.setup->getSpaceInformation(), lanes);
        if (before_attempt)
            before_attempt(1);
        // The fallback's searches run on the lanes once the first search has left them.
        const std::vector<Lane> lanes_of_search = lanes;
        ob::PlannerPtr search =
            makeSearch(kind, problem, seed, goal_bias, intermediate_states, std::move(lanes), threads);
        if (restart_steps > 0)
            search = std::make_shared<Restarting>(std::move(search), problem.model, restart_steps,
                                                  std::move(before_attempt));
        if (fallback_steps == 0)
            return search;
        // PC RRT on the same problem, one search per thread of the first (a search on T
        // threads has lanesFor(T) lanes), counted from the lanes (threadsFor) so that the
        // searches depend on them, not on the threads: the first on the search's model
        // with the search's seed, the others on lanes 1, 2, ... with theirs (lane 0 draws
        // the search's own streams).
        std::vector<Search> fallbacks{
            pcRrtFallback(problem, problem.setup->getProblemDefinition()->getGoal(), seed, goal_bias,
                          intermediate_states)};
        const std::size_t fallback_count = lanes_of_search.empty() ? 1 : threadsFor(lanes_of_search.size());
        for (std::size_t l = 1; l < fallback_count; ++l)
        {
            const Lane &lane = lanes_of_search[l];
            fallbacks.push_back(
                pcRrtFallback(laneProblem(lane, problem.k), lane.goal, lane.seed, goal_bias, intermediate_states));
        }
        return std::make_shared<Fallback>(std::move(search), std::move(fallbacks), problem.model, fallback_steps);
    }
}  // namespace pushplan::detail
