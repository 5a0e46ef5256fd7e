#include "pushplan/cpp/search/helper_thread.h"

#include <memory>
#include <sched.h>
#include <system_error>

namespace pushplan::detail
{
    /// What the new thread needs: its body, where its failure goes, and the cores it may
    /// use once running (the starting thread's).
    struct HelperThread::Start
    {
        std::function<void()> body;
        std::exception_ptr *failure = nullptr;
        cpu_set_t allowed{};
        bool placed_elsewhere = false;
    };

    void *HelperThread::run(void *argument)
    {
        const std::unique_ptr<Start> start(static_cast<Start *>(argument));
        if (start->placed_elsewhere)
            pthread_setaffinity_np(pthread_self(), sizeof start->allowed, &start->allowed);
        try
        {
            start->body();
        }
        catch (...)
        {
            *start->failure = std::current_exception();
        }
        return nullptr;
    }

    HelperThread::HelperThread(std::function<void()> body)
    {
        auto start = std::make_unique<Start>();
        start->body = std::move(body);
        start->failure = &failure_;
        pthread_attr_t attributes;
        pthread_attr_init(&attributes);
        const int here = sched_getcpu();
        if (here >= 0 && sched_getaffinity(0, sizeof start->allowed, &start->allowed) == 0)
        {
            cpu_set_t elsewhere = start->allowed;
            CPU_CLR(here, &elsewhere);
            start->placed_elsewhere = CPU_COUNT(&elsewhere) > 0 &&
                                      pthread_attr_setaffinity_np(&attributes, sizeof elsewhere, &elsewhere) == 0;
        }
        const int error = pthread_create(&thread_, &attributes, run, start.get());
        pthread_attr_destroy(&attributes);
        if (error != 0)
            throw std::system_error(error, std::generic_category(), "cannot start a helper thread");
        start.release();  // the thread owns it now
        joinable_ = true;
    }

    HelperThread::~HelperThread()
    {
        if (joinable_)
            pthread_join(thread_, nullptr);
    }

    void HelperThread::join()
    {
        if (joinable_)
        {
            pthread_join(thread_, nullptr);
            joinable_ = false;
        }
        if (failure_)
            std::rethrow_exception(failure_);
    }
}  // namespace pushplan::detail
