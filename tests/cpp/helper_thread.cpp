// HelperThread (run by tests/integration/cpp_api.rs, built with the library's internal headers): the
// body runs on a thread of its own, first on another core than the starting thread's when
// the process may use two, then free to use every core the starting thread may; what the
// body throws reaches join(). The oracle is the kernel's own account: sched_getcpu() and
// the thread's affinity mask as the body sees them.
#include "pushplan/cpp/search/helper_thread.h"

#include "expect.h"

#include <sched.h>

#include <stdexcept>
#include <string>
#include <thread>

namespace
{
    namespace pd = pushplan::detail;
    using test::expect;

    struct Seen
    {
        std::thread::id thread;
        int first_core = -1;
        cpu_set_t allowed{};
    };
}  // namespace

int main()
{
    cpu_set_t mine;
    sched_getaffinity(0, sizeof mine, &mine);
    const bool two_cores = CPU_COUNT(&mine) >= 2;

    // Start from a core and stay on it while starting, so "another core" is well defined
    // (a migration in between would make it so: the check then retries).
    Seen seen;
    int here = -1;
    for (int attempt = 0; attempt < 20; ++attempt)
    {
        here = sched_getcpu();
        pd::HelperThread helper([&] {
            seen.first_core = sched_getcpu();
            seen.thread = std::this_thread::get_id();
            sched_getaffinity(0, sizeof seen.allowed, &seen.allowed);
        });
        const bool stayed = sched_getcpu() == here;
        helper.join();
        if (stayed)
            break;
    }
    expect(seen.thread != std::thread::id() && seen.thread != std::this_thread::get_id(),
           "the body runs on a thread of its own");
    expect(!two_cores || seen.first_core != here,
           "with two cores or more the body starts on another core than the starting thread's (core " +
               std::to_string(seen.first_core) + " against " + std::to_string(here) + ")");
    expect(CPU_EQUAL(&seen.allowed, &mine), "once running it may use every core the starting thread may");

    pd::HelperThread failing([] { throw std::runtime_error("from the helper"); });
    std::string message;
    try
    {
        failing.join();
    }
    catch (const std::runtime_error &e)
    {
        message = e.what();
    }
    expect(message == "from the helper", "what the body throws reaches join()");
    return test::failures == 0 ? 0 : 1;
}
