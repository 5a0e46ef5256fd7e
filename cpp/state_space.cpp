#include "state_space.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <boost/math/constants/constants.hpp>

namespace ob = ompl::base;

namespace pushplan::detail
{
    PushStateSpace::PushStateSpace(ModelHandlePtr model) : model_(std::move(model))
    {
        const auto &info = model_->info();
        setName("PushStateSpace");
        auto joints = std::make_shared<ob::RealVectorStateSpace>(info.dof);
        ob::RealVectorBounds joint_bounds(info.dof);
        for (std::size_t i = 0; i < info.dof; ++i)
        {
            joint_bounds.setLow(i, info.joint_lower[i]);
            joint_bounds.setHigh(i, info.joint_upper[i]);
            joints->setDimensionName(i, std::string(info.joint_names[i]));
        }
        joints->setBounds(joint_bounds);
        addSubspace(joints, 1.0);
        for (std::size_t i = 0; i < info.objects; ++i)
        {
            auto object = std::make_shared<ob::SE2StateSpace>();
            ob::RealVectorBounds table(2);
            table.setLow(0, info.table_min_x);
            table.setHigh(0, info.table_max_x);
            table.setLow(1, info.table_min_y);
            table.setHigh(1, info.table_max_y);
            object->setBounds(table);
            object->setName(std::string(info.object_names[i]));
            addSubspace(object, 1.0);
        }
        lock();
    }

    double PushStateSpace::distance(const ob::State *a, const ob::State *b) const
    {
        return model_->distance(a, b);
    }

    PushStateSampler::PushStateSampler(const PushStateSpace *space, std::uint_fast32_t seed)
      : ob::StateSampler(space), model_(space->model())
    {
        rng_.setLocalSeed(seed);
    }

    void PushStateSampler::sampleRaw(const bridge::SceneInfo &info, ompl::RNG &rng, std::vector<double> &out)
    {
        out.clear();
        for (std::size_t i = 0; i < info.dof; ++i)
            out.push_back(rng.uniformReal(info.joint_lower[i], info.joint_upper[i]));
        const double pi = boost::math::constants::pi<double>();
        for (std::size_t i = 0; i < info.objects; ++i)
        {
            out.push_back(rng.uniformReal(info.table_min_x, info.table_max_x));
            out.push_back(rng.uniformReal(info.table_min_y, info.table_max_y));
            out.push_back(rng.uniformReal(-pi, pi));
        }
    }

    void PushStateSampler::sampleUniform(ob::State *state)
    {
        for (int attempt = 0; attempt < kRejectionTries; ++attempt)
        {
            sampleRaw(model_->info(), rng_, buffer_);
            model_->write(buffer_, state);
            if (model_->isValid(state))
                return;
        }
    }

    void PushStateSampler::sampleUniformNear(ob::State *state, const ob::State *, double)
    {
        sampleUniform(state);
    }

    void PushStateSampler::sampleGaussian(ob::State *state, const ob::State *, double)
    {
        sampleUniform(state);
    }
}  // namespace pushplan::detail
