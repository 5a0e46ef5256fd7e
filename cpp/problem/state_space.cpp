#include "pushplan/cpp/problem/state_space.h"

#include "pushplan/cpp/problem/sampling.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <algorithm>
#include <new>

namespace ob = ompl::base;

namespace pushplan::detail
{
    namespace
    {
        /// `n` bytes rounded up to the strictest fundamental alignment.
        std::size_t alignedSize(std::size_t n)
        {
            constexpr std::size_t a = alignof(std::max_align_t);
            return (n + a - 1) / a * a;
        }
    }  // namespace

    PushStateSpace::PushStateSpace(const ModelHandle &model)
      : view_(model.view()), metric_(bridge::Metric::make(model.problem())), layout_(view_->layout())
    {
        const auto &info = view_->info();
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
            table.setLow(0, info.table[0]);
            table.setHigh(0, info.table[1]);
            table.setLow(1, info.table[2]);
            table.setHigh(1, info.table[3]);
            object->setBounds(table);
            object->setName(std::string(info.object_names[i]));
            addSubspace(object, 1.0);
        }
        lock();
    }

    StateLayout stateLayout(std::size_t dof, std::size_t objects, std::size_t particle_values)
    {
        // One block per state:
        //   [top | top components | joints | per object: SE2, its 2 components, xy header |
        //    joint values | x, y of every object | SO2 (yaw) of every object | particles].
        StateLayout layout{};
        layout.components = alignedSize(sizeof(ob::CompoundState));
        layout.joints = layout.components + alignedSize(sizeof(ob::State *) * (1 + objects));
        layout.objects = layout.joints + alignedSize(sizeof(ob::RealVectorStateSpace::StateType));
        layout.object_headers = alignedSize(sizeof(ob::SE2StateSpace::StateType)) + alignedSize(2 * sizeof(ob::State *)) +
                                alignedSize(sizeof(ob::RealVectorStateSpace::StateType));
        layout.joint_values = layout.objects + layout.object_headers * objects;
        layout.xy_values = layout.joint_values + sizeof(double) * dof;
        layout.yaws = alignedSize(layout.xy_values + 2 * sizeof(double) * objects);
        layout.particles = alignedSize(layout.yaws + sizeof(ob::SO2StateSpace::StateType) * objects);
        layout.size = layout.particles + sizeof(double) * particle_values;
        return layout;
    }

    double PushStateSpace::getMaximumExtent() const
    {
        return metric_->max_extent();
    }

    ob::State *PushStateSpace::allocState() const
    {
        auto *block = static_cast<char *>(::operator new(layout_.size, std::align_val_t(alignof(std::max_align_t))));
        std::fill(block + layout_.particles, block + layout_.size, char(0));
        auto *top = new (block) ob::CompoundState();
        top->components = reinterpret_cast<ob::State **>(block + layout_.components);
        auto *joints = new (block + layout_.joints) ob::RealVectorStateSpace::StateType();
        joints->values = reinterpret_cast<double *>(block + layout_.joint_values);
        top->components[0] = joints;
        for (std::size_t i = 0; i + 1 < componentCount_; ++i)
        {
            char *at = block + layout_.objects + i * layout_.object_headers;
            auto *se2 = new (at) ob::SE2StateSpace::StateType();
            at += alignedSize(sizeof(ob::SE2StateSpace::StateType));
            se2->components = reinterpret_cast<ob::State **>(at);
            at += alignedSize(2 * sizeof(ob::State *));
            auto *xy = new (at) ob::RealVectorStateSpace::StateType();
            xy->values = reinterpret_cast<double *>(block + layout_.xy_values) + 2 * i;
            auto *yaw = new (block + layout_.yaws + i * sizeof(ob::SO2StateSpace::StateType))
                ob::SO2StateSpace::StateType();
            se2->components[0] = xy;
            se2->components[1] = yaw;
            top->components[1 + i] = se2;
        }
        return top;
    }

    // The parts hold no resources of their own: releasing the block ends them all.
    void PushStateSpace::freeState(ob::State *state) const
    {
        ::operator delete(static_cast<void *>(state), std::align_val_t(alignof(std::max_align_t)));
    }

    // The components as OMPL copies them, then the perturbed worlds' poses.
    void PushStateSpace::copyState(ob::State *destination, const ob::State *source) const
    {
        ob::CompoundStateSpace::copyState(destination, source);
        std::copy(reinterpret_cast<const char *>(source) + layout_.particles,
                  reinterpret_cast<const char *>(source) + layout_.size,
                  reinterpret_cast<char *>(destination) + layout_.particles);
    }

    double PushStateSpace::distance(const ob::State *a, const ob::State *b) const
    {
        // Hot: every distance in a nearest-neighbour query reads two states.
        view_->read(a, a_);
        view_->read(b, b_);
        return metric_->distance(slice(a_), slice(b_));
    }

    PushStateSampler::PushStateSampler(const PushStateSpace *space, std::uint_fast32_t seed)
      : ob::StateSampler(space), view_(space->view())
    {
        rng_.setLocalSeed(seed);
    }

    void PushStateSampler::sampleRaw(const bridge::SceneInfo &info, ompl::RNG &rng, std::vector<double> &out)
    {
        out.resize(info.dof);
        sampleJoints(info, rng, out.data());
        for (std::size_t i = 0; i < info.objects; ++i)
        {
            const auto [x, y] = sampleOnTable(info, rng);
            out.insert(out.end(), {x, y, sampleYaw(rng)});
        }
    }

    void PushStateSampler::sampleUniform(ob::State *state)
    {
        // Uniform over the space, valid or not, as the paper's RRT draws its targets: a
        // target only attracts the tree, the propagation keeps every state valid. (Drawing
        // until valid cost 97 % of the time with 20 objects: see BENCHMARKS.md.)
        sampleRaw(view_->info(), rng_, buffer_);
        view_->pinClutter(buffer_);
        view_->write(buffer_, state);
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
