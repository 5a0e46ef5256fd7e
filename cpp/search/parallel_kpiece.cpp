#include "pushplan/cpp/search/parallel_kpiece.h"

#include "pushplan/cpp/search/helper_thread.h"

#include <ompl/base/Goal.h>
#include <ompl/control/PathControl.h>

#include <cmath>
#include <deque>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace pushplan::detail
{
    /// One iteration: the motion it extends (chosen on the tree), and what its lane made
    /// of it: the control, the states reached with their grid coordinates, where each
    /// new motion ends and its goal distance, and what the lane's model counted.
    struct ParallelKPIECE::Extension
    {
        Motion *from = nullptr;
        Grid::Cell *cell = nullptr;
        oc::Control *control = nullptr;
        std::vector<ob::State *> states;
        unsigned reached = 0;  // valid steps
        std::vector<Grid::Coord> coords;
        /// Motion i spans states ends[i - 1] + 1 .. ends[i] (one run of states in a cell).
        std::vector<unsigned> ends;
        std::vector<double> distances;
        std::vector<char> at_goal;
        std::uint64_t model_steps = 0;
        double model_seconds = 0.0;
    };

    ParallelKPIECE::ParallelKPIECE(const oc::SpaceInformationPtr &si, std::uint_fast32_t seed,
                                   ModelHandlePtr tree_model, std::vector<Lane> lanes, unsigned threads)
      : oc::KPIECE1(si),
        tree_model_(std::move(tree_model)),
        lanes_(std::move(lanes)),
        threads_(threads == 0 ? static_cast<unsigned>(lanes_.size()) : threads),
        samplers_(lanes_.size())
    {
        if (lanes_.empty())
            throw std::invalid_argument("ParallelKPIECE: at least one lane");
        if (threads_ > lanes_.size())
            throw std::invalid_argument("ParallelKPIECE: more threads than lanes");
        rng_.setLocalSeed(seed);
    }

    void ParallelKPIECE::clear()
    {
        oc::KPIECE1::clear();
        for (oc::ControlSamplerPtr &sampler : samplers_)
            sampler.reset();
    }

    void ParallelKPIECE::select(Extension &e, CloseSamples &close_samples)
    {
        tree_.iteration++;
        e.from = nullptr;
        e.cell = nullptr;
        // Now and then from the motions closest to the goal, else from the grid's most
        // important cell (KPIECE1's order of random draws).
        if (!(close_samples.canSample() && rng_.uniform01() < goalBias_ && close_samples.selectMotion(e.from, e.cell)))
            selectMotion(e.from, e.cell);
        if (e.from == nullptr)
            throw std::logic_error("ParallelKPIECE: the grid gave no motion to extend");
        if (update_on_select_)
        {
            // Counted as a success until it returns (then corrected if it failed).
            e.cell->data->score *= goodScoreFactor_;
            tree_.grid.update(e.cell);
        }
    }

    void ParallelKPIECE::extend(Extension &e, std::size_t lane)
    {
        const Lane &l = lanes_[lane];
        oc::ControlSampler &sampler = *samplers_[lane];
        sampler.sampleNext(e.control, e.from->control, e.from->state);
        const unsigned steps = sampler.sampleStepCount(siC_->getMinControlDuration(), siC_->getMaxControlDuration());

        const bridge::Propagator &propagator = l.model->propagator();
        const std::uint64_t steps_before = propagator.steps();
        const double seconds_before = propagator.seconds();
        e.reached = l.si->propagateWhileValid(e.from->state, e.control, static_cast<int>(steps), e.states, false);
        e.model_steps = propagator.steps() - steps_before;
        e.model_seconds = propagator.seconds() - seconds_before;

        e.ends.clear();
        e.distances.clear();
        e.at_goal.clear();
        if (e.reached < siC_->getMinControlDuration())
            return;
        const ob::ProjectionEvaluator &projection = *l.projection;
        for (unsigned i = 0; i < e.reached; ++i)
            projection.computeCoordinates(e.states[i], e.coords[i]);
        for (unsigned index = 0; index < e.reached;)
        {
            const unsigned last = findNextMotion(e.coords, index, e.reached);
            double distance = 0.0;
            e.at_goal.push_back(l.goal->isSatisfied(e.states[last], &distance));
            e.distances.push_back(distance);
            e.ends.push_back(last);
            index = last + 1;
        }
    }

    bool ParallelKPIECE::add(Extension &e, CloseSamples &close_samples)
    {
        tree_model_->credit(e.model_steps, e.model_seconds);
        if (e.reached < siC_->getMinControlDuration())
        {
            e.cell->data->score *= update_on_select_ ? badScoreFactor_ / goodScoreFactor_ : badScoreFactor_;
            tree_.grid.update(e.cell);
            return false;
        }
        // Worth adding if it reaches a new or sparsely covered cell (or, rarely, anyway).
        // The states of one motion share a cell: one look-up per motion.
        const std::size_t two_thirds_of_average_coverage = (2 * tree_.size) / (3 * tree_.grid.size());
        bool interesting = false;
        for (std::size_t m = 0; m < e.ends.size() && !interesting; ++m)
        {
            const Grid::Cell *cell = tree_.grid.getCell(e.coords[e.ends[m]]);
            interesting = cell == nullptr || cell->data->motions.size() <= two_thirds_of_average_coverage;
        }
        if (interesting || rng_.uniform01() < 0.05)
        {
            // One motion per run of states in the same cell, each the parent of the next.
            Motion *parent = e.from;
            unsigned first = 0;
            for (std::size_t m = 0; m < e.ends.size(); ++m)
            {
                auto *motion = new Motion(siC_);
                si_->copyState(motion->state, e.states[e.ends[m]]);
                siC_->copyControl(motion->control, e.control);
                motion->steps = e.ends[m] - first + 1;
                motion->parent = parent;
                const double distance = e.distances[m];
                tree_model_->creditGoalDistance(distance);
                Grid::Cell *cell = addMotionAt(motion, e.coords[e.ends[m]], distance);
                if (e.at_goal[m])
                {
                    solution_ = motion;
                    approximate_distance_ = distance;
                    return true;
                }
                if (distance < approximate_distance_)
                {
                    approximate_distance_ = distance;
                    approximate_ = motion;
                }
                close_samples.consider(cell, motion, distance);
                parent = motion;
                first = e.ends[m] + 1;
            }
        }
        if (!update_on_select_)
            e.cell->data->score *= goodScoreFactor_;
        tree_.grid.update(e.cell);
        return false;
    }

    ParallelKPIECE::Grid::Cell *ParallelKPIECE::addMotionAt(Motion *motion, const Grid::Coord &coord,
                                                            double distance)
    {
        Grid::Cell *cell = tree_.grid.getCell(coord);
        if (cell != nullptr)
        {
            cell->data->motions.push_back(motion);
            cell->data->coverage += motion->steps;
            tree_.grid.update(cell);
        }
        else
        {
            cell = tree_.grid.createCell(coord);
            cell->data = new CellData();
            cell->data->motions.push_back(motion);
            cell->data->coverage = motion->steps;
            cell->data->iteration = tree_.iteration;
            cell->data->selections = 1;
            // A new cell's importance: the later it was found and the closer to the goal,
            // the more important.
            cell->data->score =
                (1.0 + std::log(static_cast<double>(tree_.iteration))) / (kGoalDistanceOffset + distance);
            tree_.grid.add(cell);
        }
        tree_.size++;
        return cell;
    }

    ob::PlannerStatus ParallelKPIECE::solve(const ob::PlannerTerminationCondition &ptc)
    {
        checkValidity();
        while (const ob::State *start = pis_.nextStart())
        {
            auto *motion = new Motion(siC_);
            si_->copyState(motion->state, start);
            siC_->nullControl(motion->control);
            addMotion(motion, 1.0);
        }
        if (tree_.grid.size() == 0)
        {
            OMPL_ERROR("%s: There are no valid initial states!", getName().c_str());
            return ob::PlannerStatus::INVALID_START;
        }
        // Each lane samples controls with a sampler of its own problem (lane 0's draws
        // the numbers KPIECE1's own sampler would).
        for (std::size_t w = 0; w < lanes_.size(); ++w)
            if (!samplers_[w])
                samplers_[w] = lanes_[w].si->allocControlSampler();

        const std::size_t window = lanes_.size();
        update_on_select_ = window > 1;
        solution_ = approximate_ = nullptr;
        approximate_distance_ = std::numeric_limits<double>::infinity();
        CloseSamples close_samples(nCloseSamples_);

        std::vector<Extension> extensions(window);
        const std::size_t most_states = siC_->getMaxControlDuration() + 1;
        for (Extension &e : extensions)
        {
            e.control = siC_->allocControl();
            e.states.resize(most_states);
            for (ob::State *&s : e.states)
                s = si_->allocState();
            e.coords.assign(most_states, Grid::Coord(projectionEvaluator_->getDimension()));
        }

        // Lane w holds iteration j = w (mod window) of turn <= j < turn + window: selected,
        // being extended, or extended and waiting to join. Iteration `turn` joins the
        // tree next; then its lane selects iteration turn + window and the turn passes on.
        // The join that ends the search leaves its lane idle; the iterations still in
        // flight are extended all the same, so what the lanes' models counted (steps,
        // stop reasons) does not depend on which thread got there first.
        enum class Phase : unsigned char
        {
            Selected,
            Extending,
            Extended,
            Idle
        };
        std::vector<Phase> phases(window, Phase::Selected);
        std::mutex work;  // guards phases, turn, joining and stop
        std::uint64_t turn = 0;
        bool joining = false;  // a thread has the tree
        bool stop = false;
        std::vector<std::exception_ptr> failures(threads_);
        std::size_t selected = 0;
        while (selected < window && !ptc())
            select(extensions[selected++], close_samples);

        const auto run = [&](std::size_t thread) {
            try
            {
                std::unique_lock<std::mutex> lock(work);
                while (true)
                {
                    const std::size_t head = turn % window;
                    if (!stop && !joining && phases[head] == Phase::Extended)
                    {
                        joining = true;
                        lock.unlock();
                        Extension &e = extensions[head];
                        const bool done = add(e, close_samples) || ptc();
                        if (!done)
                            select(e, close_samples);
                        lock.lock();
                        joining = false;
                        phases[head] = done ? Phase::Idle : Phase::Selected;
                        ++turn;
                        stop = stop || done;
                        continue;
                    }
                    std::size_t lane = window;  // the earliest iteration not yet extended
                    for (std::size_t i = 0; i < window && lane == window; ++i)
                        if (phases[(turn + i) % window] == Phase::Selected)
                            lane = (turn + i) % window;
                    if (lane < window)
                    {
                        phases[lane] = Phase::Extending;
                        lock.unlock();
                        extend(extensions[lane], lane);
                        lock.lock();
                        phases[lane] = Phase::Extended;
                        continue;
                    }
                    if (stop)
                        return;
                    lock.unlock();
                    std::this_thread::yield();
                    lock.lock();
                }
            }
            catch (...)
            {
                const std::lock_guard<std::mutex> lock(work);
                failures[thread] = std::current_exception();
                stop = true;
            }
        };
        if (selected == window)  // else the termination condition stopped the search already
        {
            // Helpers start on other cores than this thread's, which goes on extending.
            std::deque<HelperThread> helpers;
            for (std::size_t t = 1; t < threads_; ++t)
                helpers.emplace_back([&run, t] { run(t); });
            run(0);
            for (HelperThread &h : helpers)
                h.join();
        }

        for (Extension &e : extensions)
        {
            siC_->freeControl(e.control);
            for (ob::State *s : e.states)
                si_->freeState(s);
        }
        for (const std::exception_ptr &failure : failures)
            if (failure)
                std::rethrow_exception(failure);

        const bool exact = solution_ != nullptr;
        Motion *end = exact ? solution_ : approximate_;
        if (end == nullptr)
            return {false, false};
        lastGoalMotion_ = end;
        std::vector<Motion *> motions;
        for (Motion *m = end; m != nullptr; m = m->parent)
            motions.push_back(m);
        auto path = std::make_shared<oc::PathControl>(si_);
        for (auto m = motions.rbegin(); m != motions.rend(); ++m)
        {
            if ((*m)->parent)
                path->append((*m)->state, (*m)->control, (*m)->steps * siC_->getPropagationStepSize());
            else
                path->append((*m)->state);
        }
        pdef_->addSolutionPath(path, !exact, approximate_distance_, getName());
        return {true, !exact};
    }
}  // namespace pushplan::detail
