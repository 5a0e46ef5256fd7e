// A thread started on another core than the thread starting it.
//
// Linux queues a new thread on its parent's core; when the parent goes on computing (a
// search starting its helpers), an idle core takes the new thread over only at the next
// scheduler tick. On the 2-core machine of BENCHMARKS.md ("Helpers started on the other
// core") that is 3.85 ms at the median against 0.11 ms for a thread placed on the other
// core at once: a tenth of a typical search's time.
#pragma once

#include <exception>
#include <functional>
#include <pthread.h>

namespace pushplan::detail
{
    class HelperThread
    {
    public:
        /// Starts `body` on a new thread, first placed on any core but the calling
        /// thread's (if the process may run on another); once running it may move to any
        /// core the calling thread may use.
        explicit HelperThread(std::function<void()> body);
        HelperThread(const HelperThread &) = delete;
        HelperThread &operator=(const HelperThread &) = delete;
        /// Joins the thread if nobody did.
        ~HelperThread();

        /// Waits for the body to end; rethrows what it threw.
        void join();

    private:
        struct Start;
        static void *run(void *start);

        pthread_t thread_{};
        bool joinable_ = false;
        std::exception_ptr failure_;
    };
}  // namespace pushplan::detail
