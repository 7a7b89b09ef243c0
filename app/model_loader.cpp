// The model file read on a second thread (see app/model_loader.h).
#include "app/model_loader.h"

namespace kw::cli {

ModelLoader::~ModelLoader() {
    m_cancel = true;
    if (m_thread.joinable())
        m_thread.join();
}

void ModelLoader::start(const QString& path, double aspect) {
    m_thread = std::thread([this, path, aspect] {
        Expected<ImportResult> r =
            openModelFile(path, [this](int, int) { return !m_cancel.load(); });
        if (!r) {
            m_error = r.message();
            return;
        }
        const Scene& scene = r->scene;
        // fitCamera evaluates every surface (its exact trimmed bounds): worth its own core.
        const Camera camera = scene.camera.authored ? scene.camera : fitCamera(scene, aspect);
        m_result = LoadedModel{std::move(*r), camera};
    });
}

Expected<LoadedModel> ModelLoader::wait() {
    if (m_thread.joinable())
        m_thread.join();
    if (!m_result)
        return Error(m_error);
    return std::move(*m_result);
}

} // namespace kw::cli
