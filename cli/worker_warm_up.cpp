// cli/worker_warm_up.cpp — see worker_warm_up.hpp.
#include "worker_warm_up.hpp"

#include <system_error>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace polyvol::cli {

WorkerWarmUp::WorkerWarmUp() {
    try {
        // One index per thread of the arena, so that oneTBB asks for every worker.
        helper_ = std::thread([] {
            try {
                tbb::parallel_for(0, tbb::this_task_arena::max_concurrency(), [](int) {});
            } catch (...) {
                // Out of memory or threads: the first real loop will say so, or manage without.
            }
        });
    } catch (const std::system_error&) {
        // No thread to spare: the first parallel loop starts the workers, as without this.
    }
}

WorkerWarmUp::~WorkerWarmUp() {
    if (helper_.joinable()) helper_.join();
}

}  // namespace polyvol::cli
