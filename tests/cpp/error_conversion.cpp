// How failures leave the C++ API (run by tests/integration/cpp_api.rs, built with the library's
// internal headers): detail::asPushplanError, which wraps Planner::solve() and
// makeSetup(), turns OMPL's own exception and the model's rust::Error into
// pushplan::Error with their messages, and lets a pushplan::Error through unchanged.
// No planning input reaches an OMPL exception today (options and scenes are checked
// first), so each kind is raised here by the library that owns it.
#include "pushplan/cpp/api/planner_source.h"

#include <ompl/base/spaces/RealVectorBounds.h>
#include <ompl/util/Exception.h>

#include "expect.h"

#include <iostream>
#include <string>

namespace
{
    using test::expect;
    using test::failures;

    /// The message of the pushplan::Error `f` throws through asPushplanError, or "" if
    /// it throws nothing or anything else.
    template <typename F>
    std::string pushplanErrorOf(F &&f)
    {
        try
        {
            pushplan::detail::asPushplanError([&] {
                f();
                return 0;
            });
        }
        catch (const pushplan::Error &e)
        {
            return e.what();
        }
        catch (...)
        {
        }
        return "";
    }
}  // namespace

int main()
{
    // OMPL's own check of bounds throws ompl::Exception for a lower bound above the upper.
    const std::string ompl = pushplanErrorOf([] {
        ompl::base::RealVectorBounds bounds(1);
        bounds.setLow(1.0);
        bounds.setHigh(0.0);
        bounds.check();
    });
    std::cout << "  " << ompl << "\n";
    expect(ompl.rfind("OMPL: ", 0) == 0 && ompl.find("bound") != std::string::npos,
           "an ompl::Exception leaves as pushplan::Error, marked as OMPL's, with OMPL's message");

    // The model refuses YAML that is not a scene: a rust::Error from across the bridge.
    const std::string model = pushplanErrorOf([] { pushplan::bridge::Problem::from_yaml("[1, 2", "inline.yaml"); });
    std::cout << "  " << model << "\n";
    expect(model.find("inline.yaml") != std::string::npos && model.rfind("OMPL: ", 0) != 0,
           "the model's rust::Error leaves as pushplan::Error naming the source");

    const std::string own = pushplanErrorOf([] { throw pushplan::Error("time_limit must be positive"); });
    expect(own == "time_limit must be positive", "a pushplan::Error passes through unchanged");

    const std::string other = pushplanErrorOf([] { throw std::runtime_error("bad_alloc-like"); });
    expect(other == "OMPL: bad_alloc-like", "any other std::exception leaves as pushplan::Error too");
    return failures == 0 ? 0 : 1;
}
