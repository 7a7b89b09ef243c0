// The calling thread's CPU time: what a frame costs the thread that issues it, without the
// time it waits while other processes (or llvmpipe's rasteriser threads) run.
#pragma once

#include <ctime>

namespace kw {

/// CLOCK_THREAD_CPUTIME_ID in milliseconds.
inline double threadCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

} // namespace kw
