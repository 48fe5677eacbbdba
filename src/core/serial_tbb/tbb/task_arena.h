// core/serial_tbb/tbb/task_arena.h — see blocked_range.h.
#pragma once

namespace tbb::this_task_arena {

inline int max_concurrency() { return 1; }

template <typename F>
auto isolate(const F& f) {
    return f();
}

}  // namespace tbb::this_task_arena
