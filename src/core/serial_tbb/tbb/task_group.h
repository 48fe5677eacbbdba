// core/serial_tbb/tbb/task_group.h — see blocked_range.h. A task runs when it is
// given; wait() has nothing left to wait for.
#pragma once

namespace tbb {

class task_group {
public:
    template <typename F>
    void run(F&& f) {
        f();
    }
    void wait() {}
};

}  // namespace tbb
