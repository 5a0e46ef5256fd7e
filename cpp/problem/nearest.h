// OMPL's nearest-neighbour interface over the model's k-d tree (planner::NearestTree):
// flat copies of the tree's states in the model's metric, exact answers.
#pragma once

#include "pushplan/cpp/problem/model_handle.h"

#include <ompl/datastructures/NearestNeighbors.h>
#include <ompl/util/Exception.h>

#include <algorithm>
#include <vector>

namespace pushplan::detail
{
    /// For planners whose Motion holds its state in `state` (oc::RRT). The distance
    /// function a planner sets is not used: the model's metric is the state space's
    /// distance. Remove is linear in the size (the RRT never removes).
    template <typename Motion>
    class ModelNearestNeighbors : public ompl::NearestNeighbors<Motion *>
    {
    public:
        /// An empty structure in the metric of `model`'s problem.
        explicit ModelNearestNeighbors(const ModelHandle &model)
          : view_(model.view()), tree_(bridge::Metric::make(model.problem())->nearest_tree())
        {
        }

        bool reportsSortedResults() const override { return true; }

        void clear() override
        {
            tree_->clear();
            motions_.clear();
        }

        void add(Motion *const &motion) override
        {
            // The tree numbers its states 0, 1, 2, ... as they come: motions_[id] is its motion.
            motions_.push_back(motion);
            bridge::tree_add(*tree_, flat(motion));
        }

        bool remove(Motion *const &motion) override
        {
            const auto at = std::find(motions_.begin(), motions_.end(), motion);
            if (at == motions_.end())
                return false;
            *at = nullptr;
            return tree_->remove(static_cast<std::size_t>(at - motions_.begin()));
        }

        Motion *nearest(Motion *const &motion) const override
        {
            const std::int64_t id = bridge::tree_nearest(*tree_, flat(motion));
            if (id < 0)
                throw ompl::Exception("No elements found in nearest neighbors data structure");
            return motions_[static_cast<std::size_t>(id)];
        }

        void nearestK(Motion *const &motion, std::size_t k, std::vector<Motion *> &nbh) const override
        {
            toMotions(bridge::tree_nearest_k(*tree_, flat(motion), k), nbh);
        }

        void nearestR(Motion *const &motion, double radius, std::vector<Motion *> &nbh) const override
        {
            toMotions(bridge::tree_nearest_r(*tree_, flat(motion), radius), nbh);
        }

        std::size_t size() const override { return tree_->len(); }

        void list(std::vector<Motion *> &data) const override
        {
            data.clear();
            std::copy_if(motions_.begin(), motions_.end(), std::back_inserter(data),
                         [](const Motion *m) { return m != nullptr; });
        }

    private:
        rust::Slice<const double> flat(const Motion *motion) const
        {
            view_->read(motion->state, buffer_);
            return slice(buffer_);
        }

        void toMotions(const rust::Vec<std::size_t> &ids, std::vector<Motion *> &nbh) const
        {
            nbh.clear();
            for (const std::size_t id : ids)
                nbh.push_back(motions_[id]);
        }

        std::shared_ptr<const StateView> view_;
        rust::Box<bridge::NearestTree> tree_;
        std::vector<Motion *> motions_;
        mutable std::vector<double> buffer_;
    };
}  // namespace pushplan::detail
