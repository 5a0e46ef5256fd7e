#include "fcl_oracle.h"

#include "pushplan-fcl-oracle/src/lib.rs.h"

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>

#include <memory>
#include <stdexcept>

namespace pushplan::oracle
{
    namespace
    {
        // A right prism over a convex counter-clockwise polygon, from z = 0 to z = height.
        std::shared_ptr<fcl::CollisionGeometryd> prism(const rust::Vec<double> &xy, double height)
        {
            const int n = static_cast<int>(xy.size() / 2);
            auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
            for (int z = 0; z < 2; ++z)
                for (int i = 0; i < n; ++i)
                    vertices->emplace_back(xy[2 * i], xy[2 * i + 1], z * height);
            auto faces = std::make_shared<std::vector<int>>();
            faces->push_back(n);  // bottom, seen from below: clockwise in xy
            for (int i = n - 1; i >= 0; --i)
                faces->push_back(i);
            faces->push_back(n);  // top
            for (int i = 0; i < n; ++i)
                faces->push_back(n + i);
            for (int i = 0; i < n; ++i)  // sides
            {
                const int j = (i + 1) % n;
                faces->insert(faces->end(), {4, i, j, n + j, n + i});
            }
            return std::make_shared<fcl::Convexd>(vertices, n + 2, faces);
        }

        std::shared_ptr<fcl::CollisionGeometryd> geometry(const FclShape &s)
        {
            const std::string kind(s.kind);
            if (kind == "box")
                return std::make_shared<fcl::Boxd>(s.dims[0], s.dims[1], s.dims[2]);
            if (kind == "cylinder")
                return std::make_shared<fcl::Cylinderd>(s.dims[0], s.dims[1]);
            if (kind == "sphere")
                return std::make_shared<fcl::Sphered>(s.dims[0]);
            if (kind == "capsule")
                return std::make_shared<fcl::Capsuled>(s.dims[0], s.dims[1]);
            if (kind == "prism")
                return prism(s.vertices, s.dims[0]);
            throw std::runtime_error("unknown shape " + kind);
        }

        fcl::Transform3d transform(const FclShape &s)
        {
            fcl::Transform3d t = fcl::Transform3d::Identity();
            t.translation() = fcl::Vector3d(s.pose[0], s.pose[1], s.pose[2]);
            t.linear() = fcl::Quaterniond(s.pose[3], s.pose[4], s.pose[5], s.pose[6]).toRotationMatrix();
            return t;
        }
    }  // namespace

    FclResult fcl_query(const FclShape &a, const FclShape &b)
    {
        fcl::CollisionObjectd oa(geometry(a), transform(a));
        fcl::CollisionObjectd ob(geometry(b), transform(b));

        fcl::CollisionRequestd request(1, true);
        request.gjk_solver_type = fcl::GST_LIBCCD;
        fcl::CollisionResultd result;
        fcl::collide(&oa, &ob, request, result);

        FclResult out;
        out.collide = result.isCollision();
        out.depth = 0.0;
        if (out.collide && result.numContacts() > 0)
            out.depth = result.getContact(0).penetration_depth;

        fcl::DistanceRequestd drequest;
        drequest.gjk_solver_type = fcl::GST_LIBCCD;
        drequest.distance_tolerance = 1e-12;
        fcl::DistanceResultd dresult;
        fcl::distance(&oa, &ob, drequest, dresult);
        out.distance = dresult.min_distance;
        return out;
    }
}  // namespace pushplan::oracle
