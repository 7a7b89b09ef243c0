// RendererTestHook: render's tests' view of a Renderer's implementation.
#include "render/renderer_test_hook.h"

#include "render/renderer_impl.h"

namespace kw {

GpuScene& RendererTestHook::scene(Renderer& renderer) {
    return renderer.d->scene;
}

QOpenGLFunctions_4_5_Core* RendererTestHook::gl(Renderer& renderer) {
    return renderer.d->gl;
}

const EnvironmentMap& RendererTestHook::environment(const Renderer& renderer) {
    return renderer.d->exact.environment();
}

} // namespace kw
