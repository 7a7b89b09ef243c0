// Selection: tree rows plus picked control and trim points, pruned as the document changes.
#include "model/document/selection.h"

#include <algorithm>

namespace kw {

namespace {

template <typename T> void sortUnique(std::vector<T>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
}

} // namespace

Selection::Selection(SceneModel& model, QObject* parent)
    : QObject(parent), m_doc(model.document()), m_items(new QItemSelectionModel(&model, this)) {
    connect(m_items, &QItemSelectionModel::selectionChanged, this, [this] {
        keepPointsOfSelectedRows();
        Q_EMIT changed();
    });
    connect(m_items, &QItemSelectionModel::currentChanged, this, &Selection::changed);
    connect(m_doc, &Document::sceneReset, this, [this] {
        m_points.clear();
        m_trimPoints.clear();
        Q_EMIT changed();
    });
    connect(m_doc, &Document::surfaceAboutToBeRemoved, this,
            [this](SurfaceId id) { dropSurface(id, true, true); });
    connect(m_doc, &Document::surfaceChanged, this, [this](SurfaceId id, Aspects aspects) {
        if (aspects & Aspect::Knots)
            dropSurface(id, true, false);
        // A hidden surface's points can be neither seen nor dragged: unpick them.
        const Surface* s = m_doc->surface(id);
        if ((aspects & Aspect::Display) && s && s->hidden)
            dropSurface(id, true, true);
    });
    connect(m_doc, &Document::trimLoopAboutToBeRemoved, this, [this](SurfaceId id, int index) {
        const Surface* s = m_doc->surface(id);
        if (s && index >= 0 && size_t(index) < s->trims.size())
            dropLoop(id, s->trims[size_t(index)].id);
    });
}

SurfaceId Selection::currentSurface() const {
    const QModelIndex current = m_items->currentIndex();
    return current.isValid() ? current.data(SceneModel::SurfaceIdRole).value<SurfaceId>()
                             : SurfaceId{};
}

std::vector<SurfaceId> Selection::selectedSurfaces() const {
    std::vector<SurfaceId> picked;
    for (const QModelIndex& i : m_items->selectedIndexes())
        picked.push_back(i.data(SceneModel::SurfaceIdRole).value<SurfaceId>());
    std::vector<SurfaceId> out;
    for (const Surface& s : m_doc->scene().surfaces)
        if (std::find(picked.begin(), picked.end(), s.id) != picked.end())
            out.push_back(s.id);
    return out;
}

bool Selection::validRef(const ControlPointRef& r) const {
    const Surface* s = m_doc->surface(r.surface);
    return s && r.i >= 0 && r.i < s->geometry.countU && r.j >= 0 && r.j < s->geometry.countV;
}

bool Selection::validRef(const TrimPointRef& r) const {
    const Surface* s = m_doc->surface(r.surface);
    if (!s)
        return false;
    for (const TrimLoop& l : s->trims) {
        if (l.id != r.loop)
            continue;
        return r.curve >= 0 && size_t(r.curve) < l.curves.size() && r.index >= 0 &&
               size_t(r.index) < l.curves[size_t(r.curve)].points.size();
    }
    return false;
}

bool Selection::setControlPoints(std::vector<ControlPointRef> refs) {
    for (const ControlPointRef& r : refs)
        if (!validRef(r))
            return false;
    sortUnique(refs);
    if (refs != m_points) {
        m_points = std::move(refs);
        Q_EMIT changed();
    }
    return true;
}

bool Selection::setTrimPoints(std::vector<TrimPointRef> refs) {
    for (const TrimPointRef& r : refs)
        if (!validRef(r))
            return false;
    sortUnique(refs);
    if (refs != m_trimPoints) {
        m_trimPoints = std::move(refs);
        Q_EMIT changed();
    }
    return true;
}

void Selection::clear() {
    const bool hadPoints = !m_points.empty() || !m_trimPoints.empty();
    m_points.clear();
    m_trimPoints.clear();
    if (m_items->model()) // none once the SceneModel is gone (and nothing to clear then)
        m_items->clear(); // emits changed() through selectionChanged/currentChanged if non-empty
    if (hadPoints)
        Q_EMIT changed();
}

void Selection::dropSurface(SurfaceId id, bool points, bool trims) {
    const auto before = m_points.size() + m_trimPoints.size();
    if (points)
        std::erase_if(m_points, [id](const ControlPointRef& r) { return r.surface == id; });
    if (trims)
        std::erase_if(m_trimPoints, [id](const TrimPointRef& r) { return r.surface == id; });
    if (m_points.size() + m_trimPoints.size() != before)
        Q_EMIT changed();
}

void Selection::keepPointsOfSelectedRows() {
    const std::vector<SurfaceId> rows = selectedSurfaces();
    if (rows.empty())
        return; // no row: points of any surface (Select All with none current)
    const auto outside = [&rows](SurfaceId id) {
        return std::find(rows.begin(), rows.end(), id) == rows.end();
    };
    std::erase_if(m_points, [&](const ControlPointRef& r) { return outside(r.surface); });
    std::erase_if(m_trimPoints, [&](const TrimPointRef& r) { return outside(r.surface); });
}

void Selection::dropLoop(SurfaceId id, TrimLoopId loop) {
    const auto before = m_trimPoints.size();
    std::erase_if(m_trimPoints,
                  [&](const TrimPointRef& r) { return r.surface == id && r.loop == loop; });
    if (m_trimPoints.size() != before)
        Q_EMIT changed();
}

} // namespace kw
