#include "pushplan/cpp/api/search_builder.h"

#include "pushplan/cpp/search/parallel_kpiece.h"

#include <utility>

namespace pushplan::detail
{
    SearchBuilder::SearchBuilder(Load load) : load_(std::move(load)), first_(std::make_shared<ModelHandle>(load_()))
    {
    }

    ModelHandlePtr SearchBuilder::model(bool static_clutter, unsigned particles, std::uint64_t particle_seed)
    {
        ModelHandlePtr model = first_taken_ ? std::make_shared<ModelHandle>(load_()) : first_;
        first_taken_ = true;
        // Static RRT's problem: the same states, the clutter pinned where it starts.
        model->problem().set_static_clutter(static_clutter);
        if (particles > 0)
            model->setParticles(particles, particle_seed);
        return model;
    }

    BuiltSearch SearchBuilder::search(const RunSettings &run, std::uint64_t seed, unsigned lanes)
    {
        // A lane propagates the states of its search: the same perturbed worlds.
        const bool static_clutter = run.planner == PlannerKind::StaticRrt;
        std::vector<ModelHandlePtr> models{model(static_clutter, run.robust_particles, seed)};
        for (unsigned l = 0; l < lanes; ++l)
            models.push_back(model(static_clutter, run.robust_particles, seed));
        Problem problem = makeProblem(models[0], seed, run.k);
        std::vector<Lane> lane_list;
        for (unsigned l = 0; l < lanes; ++l)
            lane_list.push_back(makeLane(problem, models[1 + l], seed, l));
        ompl::base::PlannerPtr planner =
            makePlanner(run.planner, problem, seed, run.goal_bias, run.intermediate_states, run.restart_steps,
                        run.fallback_steps, std::move(lane_list), run.threads);
        return BuiltSearch{std::move(problem), std::move(planner), std::move(models)};
    }
}  // namespace pushplan::detail
