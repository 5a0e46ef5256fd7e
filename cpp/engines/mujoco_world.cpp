#include "pushplan/cpp/engines/mujoco_world.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

namespace pushplan::mujoco
{
    namespace
    {
        /// MuJoCo 2.2 reads MJCF from files only: the text goes into a virtual file system
        /// (two megabytes of fixed tables, hence on the heap).
        struct VirtualFiles
        {
            mjVFS *vfs = static_cast<mjVFS *>(std::malloc(sizeof(mjVFS)));
            VirtualFiles() { mj_defaultVFS(vfs); }
            ~VirtualFiles()
            {
                mj_deleteVFS(vfs);
                std::free(vfs);
            }
        };
    }  // namespace

    MujocoWorld::MujocoWorld(mjModel_ *model, mjData_ *data) : model_(model), data_(data) {}

    MujocoWorld::~MujocoWorld()
    {
        mj_deleteData(data_);
        mj_deleteModel(model_);
    }

    int MujocoWorld::body(rust::Str name) const
    {
        return mj_name2id(model_, mjOBJ_BODY, std::string(name).c_str());
    }

    int MujocoWorld::freeJointAddress(int body, bool velocity) const
    {
        if (body < 0 || body >= model_->nbody || model_->body_jntnum[body] != 1)
            throw std::out_of_range("body " + std::to_string(body) + " has no free joint");
        int joint = model_->body_jntadr[body];
        if (model_->jnt_type[joint] != mjJNT_FREE)
            throw std::out_of_range("body " + std::to_string(body) + " has no free joint");
        return velocity ? model_->jnt_dofadr[joint] : model_->jnt_qposadr[joint];
    }

    void MujocoWorld::setFreeJoint(int body, rust::Slice<const double> pose,
                                   rust::Slice<const double> velocity)
    {
        if (pose.size() != 7 || velocity.size() != 6)
            throw std::invalid_argument("a free joint has 7 coordinates and 6 velocities");
        std::memcpy(data_->qpos + freeJointAddress(body, false), pose.data(), 7 * sizeof(double));
        std::memcpy(data_->qvel + freeJointAddress(body, true), velocity.data(),
                    6 * sizeof(double));
    }

    void MujocoWorld::freeJointPose(int body, rust::Slice<double> pose) const
    {
        if (pose.size() != 7)
            throw std::invalid_argument("a free joint has 7 coordinates");
        std::memcpy(pose.data(), data_->qpos + freeJointAddress(body, false), 7 * sizeof(double));
    }

    void MujocoWorld::freeJointVelocity(int body, rust::Slice<double> velocity) const
    {
        if (velocity.size() != 6)
            throw std::invalid_argument("a free joint has 6 velocities");
        std::memcpy(velocity.data(), data_->qvel + freeJointAddress(body, true),
                    6 * sizeof(double));
    }

    void MujocoWorld::setForce(int body, rust::Slice<const double> force)
    {
        if (body < 0 || body >= model_->nbody || force.size() != 3)
            throw std::out_of_range("no such body, or a force of other than 3 components");
        std::memcpy(data_->xfrc_applied + 6 * body, force.data(), 3 * sizeof(double));
    }

    void MujocoWorld::step() { mj_step(model_, data_); }

    bool MujocoWorld::touching(rust::Slice<const std::int32_t> bodies,
                               rust::Slice<std::int32_t> pair) const
    {
        if (pair.size() != 2)
            throw std::invalid_argument("a pair has two bodies");
        auto listed = [&](int body) {
            return std::find(bodies.begin(), bodies.end(), body) != bodies.end();
        };
        for (int i = 0; i < data_->ncon; ++i)
        {
            const mjContact &c = data_->contact[i];
            const int a = model_->geom_bodyid[c.geom1], b = model_->geom_bodyid[c.geom2];
            if (c.dist < 0.0 && listed(a) && listed(b))
            {
                pair[0] = a;
                pair[1] = b;
                return true;
            }
        }
        return false;
    }

    std::unique_ptr<MujocoWorld> load(rust::Str mjcf)
    {
        VirtualFiles files;
        if (!files.vfs)
            throw std::bad_alloc();
        const char *name = "pushplan.xml";
        if (mj_makeEmptyFileVFS(files.vfs, name, static_cast<int>(mjcf.size())) != 0)
            throw std::runtime_error("MuJoCo's virtual file system refused the model");
        int file = mj_findFileVFS(files.vfs, name);
        std::memcpy(files.vfs->filedata[file], mjcf.data(), mjcf.size());
        char error[1000] = "";
        mjModel *model = mj_loadXML(name, files.vfs, error, sizeof error);
        if (!model)
            throw std::runtime_error(std::string("MuJoCo does not compile the model: ") + error);
        mjData *data = mj_makeData(model);
        if (!data)
        {
            mj_deleteModel(model);
            throw std::bad_alloc();
        }
        return std::make_unique<MujocoWorld>(model, data);
    }

    int version() { return mj_version(); }
}  // namespace pushplan::mujoco
