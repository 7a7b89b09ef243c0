// LiveEdit: begin -> checked steps -> one undo step, or cancel back to the press-time state.
#include "ui/edit/liveedit.h"

#include "ui/edit/commands.h"
#include "ui/edit/commandsupport.h"

#include <QUndoStack>

namespace kw {

namespace {

/// The trim point a ref names, or nullptr when its loop or curve is gone.
const glm::dvec2* trimPoint(const Document& doc, const TrimPointRef& ref) {
    const TrimLoop* loop = edit_detail::findLoop(doc.surface(ref.surface), ref.loop);
    if (!loop || ref.curve < 0 || size_t(ref.curve) >= loop->curves.size())
        return nullptr;
    const std::vector<glm::dvec2>& points = loop->curves[size_t(ref.curve)].points;
    return ref.index >= 0 && size_t(ref.index) < points.size() ? &points[size_t(ref.index)]
                                                               : nullptr;
}

} // namespace

LiveEdit::LiveEdit(Document* document, QUndoStack* stack, QObject* parent)
    : QObject(parent), m_doc(document), m_stack(stack) {
    // Open or New under a drag: the recorded points belong to the old scene.
    connect(m_doc, &Document::sceneReset, this, [this] {
        clear();
        m_active = false;
    });
}

void LiveEdit::begin() {
    if (m_active)
        cancel();
    clear();
    m_active = true;
}

Error LiveEdit::refuse(Error reason) {
    Q_EMIT refused(reason.message);
    return reason;
}

Status LiveEdit::moveControlPoints(SurfaceId surface, const std::vector<int>& indices,
                                   const std::vector<glm::dvec3>& positions) {
    if (!m_active)
        return refuse(tr("no edit running"));
    if (Status step = m_doc->checkControlPoints(surface, indices, positions); !step)
        return refuse(std::move(step).error());
    if (Status net = checkNet(surface); !net)
        return refuse(std::move(net).error());
    if (Status moved = applyPoints(surface, indices, positions); !moved)
        return refuse(std::move(moved).error());
    return ok();
}

Status LiveEdit::applyPoints(SurfaceId surface, const std::vector<int>& indices,
                             const std::vector<glm::dvec3>& positions) {
    const NurbsSurface& g = m_doc->surface(surface)->geometry;
    auto [record, fresh] = m_points.try_emplace(surface);
    if (fresh)
        record->second.knots = m_doc->revisions(surface).knots;
    std::map<int, glm::dvec3>& from = record->second.from;
    for (int index : indices)
        from.try_emplace(index, g.points[size_t(index)]);
    return m_doc->setControlPoints(surface, indices, positions);
}

Status LiveEdit::moveControlPoints(const std::vector<ControlPointRef>& refs,
                                   const std::vector<glm::dvec3>& positions) {
    if (!m_active)
        return refuse(tr("no edit running"));
    if (refs.size() != positions.size())
        return refuse(QStringLiteral("need one position per control point"));
    std::map<SurfaceId, std::pair<std::vector<int>, std::vector<glm::dvec3>>> bySurface;
    for (size_t k = 0; k < refs.size(); ++k) {
        const ControlPointRef& r = refs[k];
        const Surface* s = m_doc->surface(r.surface);
        if (!s)
            return refuse(QStringLiteral("no surface with id %1").arg(r.surface.value));
        if (r.i < 0 || r.j < 0 || r.i >= s->geometry.countU || r.j >= s->geometry.countV)
            return refuse(tr("control point (%1, %2) is no longer in the %3 × %4 net of "
                             "surface %5")
                              .arg(r.i)
                              .arg(r.j)
                              .arg(s->geometry.countU)
                              .arg(s->geometry.countV)
                              .arg(r.surface.value));
        auto& [indices, at] = bySurface[r.surface];
        indices.push_back(s->geometry.index(r.i, r.j));
        at.push_back(positions[k]);
    }
    for (const auto& [id, change] : bySurface) {
        Status step = checkNet(id);
        if (step)
            step = m_doc->checkControlPoints(id, change.first, change.second);
        if (!step)
            return refuse(std::move(step).error());
    }
    // Every surface's step passed: applied, none checked again.
    for (const auto& [id, change] : bySurface)
        if (Status moved = applyPoints(id, change.first, change.second); !moved)
            return refuse(std::move(moved).error());
    return ok();
}

Status LiveEdit::checkNet(SurfaceId surface) const {
    const auto record = m_points.find(surface);
    if (record == m_points.end() || m_doc->revisions(surface).knots == record->second.knots)
        return ok();
    return Error(tr("the net of surface %1 changed under the drag").arg(surface.value));
}

Status LiveEdit::setWeight(SurfaceId surface, int index, double weight) {
    if (!m_active)
        return refuse(tr("no edit running"));
    if (Status step = m_doc->checkWeight(surface, index, weight); !step)
        return refuse(std::move(step).error());
    m_weights.try_emplace({surface, index},
                          m_doc->surface(surface)->geometry.weights[size_t(index)]);
    if (Status set = m_doc->setWeight(surface, index, weight); !set)
        return refuse(std::move(set).error());
    return ok();
}

Status LiveEdit::moveTrimPoints(const std::vector<TrimPointRef>& refs,
                                const std::vector<glm::dvec2>& positions) {
    if (!m_active)
        return refuse(tr("no edit running"));
    if (Status step = m_doc->checkTrimPoints(refs, positions); !step)
        return refuse(std::move(step).error());
    for (const TrimPointRef& ref : refs)
        if (!m_trims.count(ref))
            m_trims.emplace(ref, *trimPoint(*m_doc, ref)); // the rule found it
    if (Status moved = m_doc->setTrimPoints(refs, positions); !moved)
        return refuse(std::move(moved).error());
    return ok();
}

int LiveEdit::movedSurfaces() const {
    int moved = 0;
    for (const auto& [id, record] : m_points) {
        const Surface* s = m_doc->surface(id);
        if (!checkNet(id))
            continue;
        for (const auto& [index, p] : record.from)
            if (s && size_t(index) < s->geometry.points.size() &&
                s->geometry.points[size_t(index)] != p) {
                ++moved;
                break;
            }
    }
    return moved;
}

bool LiveEdit::commit(const QString& text, const QString& severalText) {
    if (!m_active)
        return false;
    m_active = false;
    std::vector<std::unique_ptr<QUndoCommand>> commands;
    int points = 0;
    for (const auto& [id, record] : m_points) {
        std::vector<int> indices;
        std::vector<glm::dvec3> from, to;
        for (const auto& [index, p] : record.from) {
            indices.push_back(index);
            from.push_back(p);
        }
        // A surface removed or its net changed under the drag (an undo by key): its step is
        // dropped.
        if (!checkNet(id) || !m_doc->checkControlPoints(id, indices, from))
            continue;
        for (int index : indices)
            to.push_back(m_doc->surface(id)->geometry.points[size_t(index)]);
        if (from == to)
            continue;
        if (auto c = MoveControlPoints::create(m_doc, id, indices, from, to, MoveKind::Drag)) {
            points += int(indices.size());
            commands.push_back(std::move(*c));
        } else {
            refuse(std::move(c).error());
        }
    }
    for (const auto& [key, from] : m_weights) {
        const auto& [id, index] = key;
        if (!m_doc->checkWeight(id, index, from))
            continue;
        const double to = m_doc->surface(id)->geometry.weights[size_t(index)];
        if (to == from)
            continue;
        // SetWeight takes its old value from the document: back to the press-time weight.
        if (!m_doc->setWeight(id, index, from))
            continue;
        if (auto c = SetWeight::create(m_doc, id, index, to))
            commands.push_back(std::move(*c));
    }
    std::vector<TrimPointRef> refs;
    std::vector<glm::dvec2> trimFrom, trimTo;
    for (const auto& [ref, from] : m_trims)
        if (const glm::dvec2* now = trimPoint(*m_doc, ref)) {
            refs.push_back(ref);
            trimFrom.push_back(from);
            trimTo.push_back(*now);
        }
    if (!refs.empty() && trimFrom != trimTo) {
        if (auto c = MoveTrimPoints::create(m_doc, refs, trimFrom, trimTo, MoveKind::Drag))
            commands.push_back(std::move(*c));
        else
            refuse(std::move(c).error());
    }
    clear();
    if (commands.empty())
        return false;
    if (commands.size() == 1) {
        if (!text.isEmpty())
            commands.front()->setText(text);
        return pushCommand(m_stack, std::move(commands.front()));
    }
    const QString macro =
        severalText.isEmpty()
            ? tr("Move %1 control points").arg(points)
            : QString(severalText).replace(QStringLiteral("%1"), QString::number(commands.size()));
    m_stack->beginMacro(macro);
    for (auto& c : commands)
        pushCommand(m_stack, std::move(c));
    m_stack->endMacro();
    return true;
}

bool LiveEdit::commitWith(const std::function<std::unique_ptr<QUndoCommand>()>& make) {
    if (!m_active)
        return false;
    restore();
    clear();
    m_active = false;
    return pushCommand(m_stack, make());
}

void LiveEdit::cancel() {
    if (m_active)
        restore();
    clear();
    m_active = false;
}

void LiveEdit::restore() {
    for (const auto& [id, record] : m_points) {
        if (!checkNet(id))
            continue; // the indices name other points now
        std::vector<int> indices;
        std::vector<glm::dvec3> from;
        for (const auto& [index, p] : record.from) {
            indices.push_back(index);
            from.push_back(p);
        }
        // Refused, with nothing to restore, when the surface is gone.
        (void)m_doc->setControlPoints(id, indices, from);
    }
    for (const auto& [key, from] : m_weights)
        (void)m_doc->setWeight(key.first, key.second, from); // as above
    std::map<SurfaceId, std::pair<std::vector<TrimPointRef>, std::vector<glm::dvec2>>> bySurface;
    for (const auto& [ref, from] : m_trims) {
        bySurface[ref.surface].first.push_back(ref);
        bySurface[ref.surface].second.push_back(from);
    }
    for (const auto& [id, moves] : bySurface)
        (void)m_doc->setTrimPoints(moves.first, moves.second); // as above
}

void LiveEdit::clear() {
    m_points.clear();
    m_weights.clear();
    m_trims.clear();
}

} // namespace kw
