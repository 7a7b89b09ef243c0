// What changed in a document since the renderer's last frame, pulled from the document at frame
// time (Document::changesSince): the surfaces whose data changed, and whether the list itself
// did (insert, remove, reset). GpuScene syncs those records only, so a drag step costs what it
// changed, not the scene's size. Also the scene's control bounds (the camera's near and far
// planes), kept per surface.
#pragma once

#include "model/document/document.h"

#include <glm/glm.hpp>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace kw {

class SceneChanges {
public:
    /// Adds what `doc` changed since the last pull. Another document than the one pulled
    /// from last (or the first pull) counts as a structural change: everything is new.
    void pull(const Document& doc);
    /// Drops what was pulled; the next pull() starts from a structural change.
    void forget();

    /// True after an insert, a removal, a reset or a new document: the surfaces' order and
    /// indices may have changed, so the whole list has to be walked once.
    bool structureChanged() const { return m_structure; }
    /// Ids whose surface data changed (points, knots, trims or display), each once, in the
    /// order first reported.
    const std::vector<SurfaceId>& changed() const { return m_changed; }
    /// Called once the frame applied the changes.
    void clear();

    /// Brings the per-surface control bounds up to date (every surface after a structural
    /// change, else the changed ones) and their union; also the id-to-index map. Call after
    /// follow(), before reading bounds() or indexOf(); does not clear the changes.
    void updateBounds(const Document& doc);
    /// The union of every surface's control points (hidden ones too), as kw::sceneBounds
    /// computes it; false when no surface has points.
    bool bounds(glm::dvec3& lo, glm::dvec3& hi) const;
    /// Position of `id` in the document's surfaces as of updateBounds(), or -1.
    int indexOf(SurfaceId id) const;

private:
    struct Box {
        glm::dvec3 lo{0.0}, hi{0.0};
        bool any = false;
    };
    Box boxOf(const Surface& s) const;

    const Document* m_document = nullptr;
    std::uint64_t m_since = 0; ///< Document::changesSince's `through` at the last pull
    bool m_structure = true;
    std::vector<SurfaceId> m_changed;
    std::unordered_set<std::uint32_t> m_changedSet;
    bool m_boundsValid = false;
    std::vector<Box> m_boxes; ///< by index
    std::unordered_map<std::uint32_t, int> m_index;
    Box m_union;
};

} // namespace kw
