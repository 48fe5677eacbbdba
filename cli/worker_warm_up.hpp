// cli/worker_warm_up.hpp — start oneTBB's worker threads in the background,
// so that the first parallel loop finds them running.
#pragma once

#include <thread>

namespace polyvol::cli {

// oneTBB initialises itself (its allocator library, its thread pool) and
// creates its workers at the first parallel loop, on the thread that runs
// it. On the machine of docs/benchmarks.md (a virtual machine, two cores)
// the first worker then often joined that loop 1.5-5 ms after it had begun,
// which cost a whole-process `polyvol volume` of an 8M-triangle binary STL
// about a tenth of its time. A helper thread that runs an empty parallel
// loop as soon as the arguments are parsed takes both off the critical path:
// they overlap probing, mapping and parsing the files. (Started before the
// parse, it gained nothing more there and cost --help a thread.)
//
// The library does not do this itself: how and when a program starts its
// threads is the program's choice.
class WorkerWarmUp {
public:
    WorkerWarmUp();   // starts the helper (nothing, if no thread can be started)
    ~WorkerWarmUp();  // joins it: oneTBB is never still starting up at exit
    WorkerWarmUp(const WorkerWarmUp&) = delete;
    WorkerWarmUp& operator=(const WorkerWarmUp&) = delete;

private:
    std::thread helper_;
};

}  // namespace polyvol::cli
