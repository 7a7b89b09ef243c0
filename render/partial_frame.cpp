// The partial frame's bookkeeping (partial_frame.h): the damaged rectangle from the surfaces
// and edge bands that changed since the remembered frame.
#include "render/partial_frame.h"

#include "render/edge_bands.h"
#include "render/exact_surface_pass.h"
#include "render/overlay_passes.h"

#include <algorithm>
#include <cmath>

namespace kw {

int PartialFrames::reachPixels(const RenderOptions& options) {
    double reach = options.pixelTolerance + double(ExactSurfacePass::kSkirtMarginPixels);
    if (options.controlNet)
        reach = std::max(reach, 0.5 * double(ControlNetPass{}.pointSize));
    if (options.edgeBands)
        reach = std::max(reach, 0.5 * double(options.edgeBands->widthPixels));
    return int(std::ceil(reach)) + 2;
}

std::optional<glm::ivec4> PartialFrames::windowRect(const glm::vec3& lo, const glm::vec3& hi,
                                                    const glm::mat4& viewProjection,
                                                    glm::ivec2 viewport, int pad) {
    const ExactPlanner::ScreenBox box = ExactPlanner::screenBox(lo, hi, viewProjection);
    if (box.behind)
        return std::nullopt;
    return grown(ExactPlanner::pixelRect(box, viewport), pad, viewport);
}

glm::ivec4 PartialFrames::grown(const glm::ivec4& rect, int pad, glm::ivec2 viewport) {
    const glm::ivec4 r(std::max(rect.x - pad, 0), std::max(rect.y - pad, 0),
                       std::min(rect.z + pad, viewport.x), std::min(rect.w + pad, viewport.y));
    if (r.z <= r.x || r.w <= r.y)
        return glm::ivec4(0); // wholly off the view
    return r;
}

void PartialFrames::unite(glm::ivec4& into, const glm::ivec4& r) {
    if (r.z <= r.x || r.w <= r.y)
        return;
    if (into.z <= into.x) {
        into = r;
        return;
    }
    into = glm::ivec4(std::min(into.x, r.x), std::min(into.y, r.y), std::max(into.z, r.z),
                      std::max(into.w, r.w));
}

std::optional<glm::ivec4>
PartialFrames::damage(const PartialFrameView& view, std::uint64_t prepassWrites,
                      const std::vector<SurfaceFootprint>& surfaces,
                      const glm::mat4& viewProjection, const EdgeBands* bands,
                      std::vector<DamagedSurface>* changed, bool* bandsChanged) const {
    if (changed)
        changed->clear();
    if (bandsChanged)
        *bandsChanged = false;
    if (!m_have || !(view == m_view) || prepassWrites != m_prepassWrites)
        return std::nullopt;
    const int pad = reachPixels(view.options);
    glm::ivec4 rect(0);
    bool whole = false;
    // A surface's pixels as the remembered frame drew them, or as this one will.
    const auto add = [&](const SurfaceFootprint& s, bool before, int index) {
        if (!s.drawn)
            return; // nothing of it was or will be drawn
        if (!s.bounded)
            whole = true;
        else
            unite(rect, grown(s.rect, pad, view.viewport));
        if (changed)
            changed->push_back(DamagedSurface{s, before, index});
    };
    size_t matched = 0;
    for (size_t k = 0; k < surfaces.size(); ++k) {
        const SurfaceFootprint& now = surfaces[k];
        const auto was = m_surfaces.find(now.id);
        if (was == m_surfaces.end()) {
            add(now, false, int(k)); // shown or added
            continue;
        }
        ++matched;
        if (!(was->second == now)) {
            add(was->second, true, -1);
            add(now, false, int(k));
        }
        if (whole)
            return std::nullopt;
    }
    if (matched != m_surfaces.size()) { // hidden or removed
        std::set<std::uint32_t> present;
        for (const SurfaceFootprint& now : surfaces)
            present.insert(now.id);
        for (const auto& [id, was] : m_surfaces)
            if (!present.count(id))
                add(was, true, -1);
    }
    if (bands != m_bands)
        return std::nullopt; // the options compared the pointer already; null on both sides
    if (bands && bands->revision != m_bandsRevision) {
        // Updated in place (EdgeBandCache): the ranges re-made since, at their old and new
        // places; a change in their number or length reaches any band.
        if (bands->layoutRevision != m_bandsLayout || bands->ranges.empty() ||
            bands->ranges.size() != m_bandBounds.size())
            return std::nullopt;
        for (size_t k = 0; k < bands->ranges.size() && !whole; ++k) {
            const EdgeBandRange& b = bands->ranges[k];
            if (b.revision <= m_bandsRevision)
                continue;
            if (bandsChanged)
                *bandsChanged = true;
            for (const auto& [lo, hi] : {m_bandBounds[k], std::pair(b.lo, b.hi)}) {
                const std::optional<glm::ivec4> r =
                    windowRect(lo, hi, viewProjection, view.viewport, pad);
                if (!r)
                    whole = true;
                else
                    unite(rect, *r);
            }
        }
    }
    if (whole)
        return std::nullopt;
    const double area = double(std::max(rect.z - rect.x, 0)) * double(std::max(rect.w - rect.y, 0));
    if (area > kMaxFraction * double(view.viewport.x) * double(view.viewport.y))
        return std::nullopt;
    return rect;
}

std::optional<FrameCamera> PartialFrames::keptCamera(const Camera& camera, QSize drawnSize,
                                                     QSize targetSize,
                                                     const glm::dvec3 (*bounds)[2]) const {
    if (!m_have || !bounds || !(camera == m_camera) || drawnSize != m_view.drawnSize ||
        targetSize != m_view.targetSize)
        return std::nullopt;
    const double aspect = double(targetSize.width()) / targetSize.height();
    const CameraMatrices fresh = cameraMatrices(camera, bounds, aspect);
    // The scene's extent along the view, as cameraMatrices measures it.
    const glm::dvec3 lo = (*bounds)[0], hi = (*bounds)[1];
    const double radius = std::max(0.5 * glm::length(hi - lo), 1e-6);
    const double d = glm::dot(0.5 * (lo + hi) - fresh.eye, fresh.forward);
    const double nearPlane = double(m_frame.nearPlane), farPlane = double(m_frame.farPlane);
    if (d + radius <= farPlane && nearPlane <= std::max(d - radius, fresh.nearPlane) &&
        nearPlane >= 0.5 * fresh.nearPlane)
        return m_frame;
    return std::nullopt;
}

void PartialFrames::remember(const Camera& camera, const FrameCamera& frame,
                             const PartialFrameView& view, std::uint64_t prepassWrites,
                             const std::vector<SurfaceFootprint>& surfaces, const EdgeBands* bands,
                             const std::set<int>& backCulled, bool pickable) {
    m_have = true;
    m_view = view;
    m_camera = camera;
    m_frame = frame;
    m_frame.reach = glm::ivec4(0);
    m_prepassWrites = prepassWrites;
    m_surfaces.clear();
    for (const SurfaceFootprint& s : surfaces)
        m_surfaces.emplace(s.id, s);
    m_bands = bands;
    m_bandBounds.clear();
    if (bands) {
        m_bandsRevision = bands->revision;
        m_bandsLayout = bands->layoutRevision;
        for (const EdgeBandRange& b : bands->ranges)
            m_bandBounds.emplace_back(b.lo, b.hi);
    }
    m_backCulled = backCulled;
    m_pickable = pickable;
}

} // namespace kw
