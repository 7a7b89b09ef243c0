// SceneChanges: the document's changes pulled at frame time, and the scene's control bounds
// kept per surface.
#include "render/scene_changes.h"

namespace kw {

void SceneChanges::pull(const Document& doc) {
    const Document::Changes changes = doc.changesSince(m_document == &doc ? m_since : 0);
    m_document = &doc;
    m_since = changes.through;
    if (changes.structural) {
        m_structure = true;
        return;
    }
    for (const SurfaceChange& c : changes.surfaces)
        if (m_changedSet.insert(c.id.value).second)
            m_changed.push_back(c.id);
}

void SceneChanges::forget() {
    m_document = nullptr;
    m_since = 0;
    m_structure = true;
    m_boundsValid = false;
    m_changed.clear();
    m_changedSet.clear();
}

void SceneChanges::clear() {
    m_structure = false;
    m_changed.clear();
    m_changedSet.clear();
}

SceneChanges::Box SceneChanges::boxOf(const Surface& s) const {
    Box b;
    if (!s.geometry.points.empty()) {
        surfaceControlBounds(s.geometry, b.lo, b.hi);
        b.any = true;
    }
    return b;
}

void SceneChanges::updateBounds(const Document& doc) {
    const std::vector<Surface>& surfaces = doc.scene().surfaces;
    bool changed = false;
    if (m_structure || !m_boundsValid || m_boxes.size() != surfaces.size()) {
        m_boxes.resize(surfaces.size());
        m_index.clear();
        m_index.reserve(surfaces.size());
        for (size_t i = 0; i < surfaces.size(); ++i) {
            m_boxes[i] = boxOf(surfaces[i]);
            m_index[surfaces[i].id.value] = int(i);
        }
        m_boundsValid = true;
        changed = true;
    } else {
        for (const SurfaceId id : m_changed) {
            const int i = indexOf(id);
            if (i < 0 || surfaces[size_t(i)].id != id)
                continue; // removed: a structural change came with it
            const Box b = boxOf(surfaces[size_t(i)]);
            Box& old = m_boxes[size_t(i)];
            if (b.any != old.any || b.lo != old.lo || b.hi != old.hi) {
                old = b;
                changed = true;
            }
        }
    }
    if (!changed)
        return;
    // The union of the boxes: a pass over one box per surface, not over their points. The
    // same min and max as kw::sceneBounds, so the camera planes are bit-identical.
    Box u;
    for (const Box& b : m_boxes) {
        if (!b.any)
            continue;
        u.lo = u.any ? glm::min(u.lo, b.lo) : b.lo;
        u.hi = u.any ? glm::max(u.hi, b.hi) : b.hi;
        u.any = true;
    }
    m_union = u;
}

bool SceneChanges::bounds(glm::dvec3& lo, glm::dvec3& hi) const {
    if (!m_union.any)
        return false;
    lo = m_union.lo;
    hi = m_union.hi;
    return true;
}

int SceneChanges::indexOf(SurfaceId id) const {
    const auto it = m_index.find(id.value);
    return it == m_index.end() ? -1 : it->second;
}

} // namespace kw
