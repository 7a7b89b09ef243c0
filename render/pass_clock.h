// PassClock: a frame's passes timed one by one for Renderer::setPassProfiling, each ended by
// glFinish so that its GPU work (on llvmpipe, the rasteriser threads' work) counts to it.
#pragma once

#include "render/frame_report.h"

#include <QOpenGLFunctions_4_5_Core>
#include <ctime>

namespace kw {

/// CLOCK_PROCESS_CPUTIME_ID in milliseconds: every thread of the process, llvmpipe's
/// rasteriser threads included (render/thread_clock.h has the calling thread's alone).
inline double processCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

inline double wallMs() {
    timespec t{};
    clock_gettime(CLOCK_MONOTONIC, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

/// Off (the default) it does nothing: no glFinish, no clock read. On, start() begins a frame
/// and each mark(pass) finishes the GL work issued since the previous mark and adds its wall
/// and process CPU time to `pass` (a pass may be marked more than once: accumulated samples).
class PassClock {
public:
    void setEnabled(bool on) { m_on = on; }
    bool enabled() const { return m_on; }
    void start(QOpenGLFunctions_4_5_Core* gl, PassTimes* times) {
        m_gl = gl;
        m_times = m_on ? times : nullptr;
        if (!m_times)
            return;
        *m_times = PassTimes{};
        m_times->measured = true;
        m_gl->glFinish(); // what earlier calls left queued is not this frame's
        m_wall = wallMs();
        m_cpu = processCpuMs();
    }
    void mark(PassTimes::Pass pass) {
        if (!m_times)
            return;
        m_gl->glFinish();
        const double wall = wallMs(), cpu = processCpuMs();
        m_times->wallMs[pass] += wall - m_wall;
        m_times->cpuMs[pass] += cpu - m_cpu;
        m_wall = wall;
        m_cpu = cpu;
    }
    void stop() { m_times = nullptr; }

private:
    bool m_on = false;
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    PassTimes* m_times = nullptr;
    double m_wall = 0.0, m_cpu = 0.0;
};

} // namespace kw
