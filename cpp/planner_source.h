// Where a Planner's scene comes from (a file or YAML text), shared by the C++ API's
// sources.
#pragma once

#include "pushplan/pushplan.h"
#include "pushplan/src/ffi.rs.h"

#include <string>

namespace pushplan
{
    struct Planner::Source
    {
        std::string path;  // the scene file, or the label of YAML text
        std::string yaml;
        bool from_yaml = false;
        std::string name;

        rust::Box<bridge::Model> load(bool static_clutter) const
        {
            try
            {
                return from_yaml ? bridge::model_from_yaml(yaml, path, static_clutter) :
                                   bridge::load_model(path, static_clutter);
            }
            catch (const rust::Error &e)
            {
                throw Error(e.what());
            }
        }
    };
}  // namespace pushplan
