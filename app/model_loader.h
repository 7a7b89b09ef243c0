// Reading the model file on a second thread while the renderer's OpenGL context starts:
// `knotwork render part.step` overlaps the CAD reader's child process (and the camera fit)
// with Qt's GUI and OpenGL start-up (docs/PERFORMANCE.md ## Start-up).
#pragma once

#include "model/cad/cadimport.h"
#include "model/error.h"

#include <QString>
#include <atomic>
#include <optional>
#include <thread>

namespace kw::cli {

/// A model read by ModelLoader, with the camera its first image uses.
struct LoadedModel {
    ImportResult import;
    /// The file's own camera when it has one (Camera::authored), else fitCamera at the aspect
    /// given to start().
    Camera camera;
};

class ModelLoader {
public:
    ModelLoader() = default;
    ModelLoader(const ModelLoader&) = delete;
    ModelLoader& operator=(const ModelLoader&) = delete;
    /// Cancels a read still running (a CAD child is killed at once) and waits for the thread.
    ~ModelLoader();

    /// Starts reading `path` with openModelFile (cadimport.h) on its own thread; then, for a
    /// model without an authored camera, fits one (fitCamera) at `aspect` there too. Needs the
    /// Q*Application to exist (the CAD reader is found next to the executable).
    void start(const QString& path, double aspect);
    /// Waits for the read; the error names the file when it failed.
    Expected<LoadedModel> wait();

private:
    std::thread m_thread;
    std::atomic<bool> m_cancel{false};
    std::optional<LoadedModel> m_result;
    QString m_error;
};

} // namespace kw::cli
