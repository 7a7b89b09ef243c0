// Edit commands for points, weights, partitions, trim points, material, lights and camera.
#include "ui/edit/commands.h"

#include "model/document/validation.h"
#include "ui/edit/commandsupport.h"

#include <QLoggingCategory>
#include <QUndoStack>
#include <cmath>
#include <map>
#include <set>

Q_LOGGING_CATEGORY(lcEdit, "knotwork.edit")

namespace kw {

using namespace edit_detail;

DocumentCommand::DocumentCommand(Document* document, const QString& text)
    : QUndoCommand(text), m_doc(document) {}

void DocumentCommand::check(const Status& done, const char* what) {
    if (done)
        return;
    qCWarning(lcEdit) << "document refused" << what << "of" << text() << "(" << done.message()
                      << ") - the document changed outside the undo stack; dropping the command";
    setObsolete(true);
}

bool pushCommand(QUndoStack* stack, std::unique_ptr<QUndoCommand> command) {
    if (!stack || !command)
        return false;
    stack->push(command.release());
    return true;
}

// ---- MoveControlPoints

Expected<std::unique_ptr<MoveControlPoints>>
MoveControlPoints::create(Document* document, SurfaceId surface, std::vector<int> indices,
                          std::vector<glm::dvec3> from, std::vector<glm::dvec3> to, MoveKind kind) {
    if (!document)
        return Error(noDocument());
    if (indices.empty() || indices.size() != from.size() || indices.size() != to.size())
        return Error(QStringLiteral("need one old and one new position per point"));
    // The document's own rule, for both ends: undo writes `from` as redo writes `to`.
    for (const auto* positions : {&from, &to})
        if (Status step = document->checkControlPoints(surface, indices, *positions); !step)
            return step.error();
    const QString text = indices.size() == 1
                             ? QStringLiteral("Move control point")
                             : QStringLiteral("Move %1 control points").arg(indices.size());
    std::unique_ptr<MoveControlPoints> c(new MoveControlPoints(document, text));
    c->m_surface = surface;
    c->m_indices = std::move(indices);
    c->m_from = std::move(from);
    c->m_to = std::move(to);
    c->m_kind = kind;
    c->m_link = document->seamLink();
    return c;
}

void MoveControlPoints::redo() {
    check(document()->setControlPoints(m_surface, m_indices, m_to, m_link), "redo");
}

void MoveControlPoints::undo() {
    check(document()->setControlPoints(m_surface, m_indices, m_from, m_link), "undo");
}

bool MoveControlPoints::mergeWith(const QUndoCommand* other) {
    const auto* o = static_cast<const MoveControlPoints*>(other);
    if (o->m_kind != MoveKind::Nudge || o->m_surface != m_surface || o->m_indices != m_indices)
        return false;
    m_to = o->m_to;
    setObsolete(m_to == m_from);
    return true;
}

// ---- SetWeight

Expected<std::unique_ptr<SetWeight>> SetWeight::create(Document* document, SurfaceId surface,
                                                       int index, double weight) {
    if (!document)
        return Error(noDocument());
    if (Status step = document->checkWeight(surface, index, weight); !step)
        return step.error();
    const Surface* s = document->surface(surface);
    std::unique_ptr<SetWeight> c(
        new SetWeight(document, QStringLiteral("Set weight to %1").arg(weight)));
    c->m_surface = surface;
    c->m_index = index;
    c->m_from = s->geometry.weights[size_t(index)];
    c->m_to = weight;
    return c;
}

void SetWeight::redo() {
    check(document()->setWeight(m_surface, m_index, m_to), "redo");
}
void SetWeight::undo() {
    check(document()->setWeight(m_surface, m_index, m_from), "undo");
}

bool SetWeight::mergeWith(const QUndoCommand* other) {
    const auto* o = static_cast<const SetWeight*>(other);
    if (o->m_surface != m_surface || o->m_index != m_index)
        return false;
    m_to = o->m_to;
    setText(o->text());
    setObsolete(m_to == m_from);
    return true;
}

// ---- SetPartitions

Expected<std::unique_ptr<SetPartitions>> SetPartitions::create(Document* document,
                                                               SurfaceId surface, int nu, int nv) {
    const Surface* s = surfaceIn(document, surface);
    if (!s)
        return Error(noSurface(document, surface));
    if (Status valid = checkPartitions(nu, nv); !valid)
        return std::move(valid).error();
    std::unique_ptr<SetPartitions> c(
        new SetPartitions(document, QStringLiteral("Set partitions to %1 × %2").arg(nu).arg(nv)));
    c->m_surface = surface;
    c->m_fromU = s->partitionsU;
    c->m_fromV = s->partitionsV;
    c->m_toU = nu;
    c->m_toV = nv;
    return c;
}

void SetPartitions::redo() {
    check(document()->setPartitions(m_surface, m_toU, m_toV), "redo");
}
void SetPartitions::undo() {
    check(document()->setPartitions(m_surface, m_fromU, m_fromV), "undo");
}

bool SetPartitions::mergeWith(const QUndoCommand* other) {
    const auto* o = static_cast<const SetPartitions*>(other);
    if (o->m_surface != m_surface)
        return false;
    m_toU = o->m_toU;
    m_toV = o->m_toV;
    setText(o->text());
    setObsolete(m_toU == m_fromU && m_toV == m_fromV);
    return true;
}

// ---- MoveTrimPoints

Expected<std::unique_ptr<MoveTrimPoints>>
MoveTrimPoints::create(Document* document, std::vector<TrimPointRef> refs,
                       std::vector<glm::dvec2> from, std::vector<glm::dvec2> to, MoveKind kind) {
    if (!document)
        return Error(noDocument());
    if (refs.empty() || refs.size() != from.size() || refs.size() != to.size())
        return Error(QStringLiteral("need one old and one new position per trim point"));
    // The document's own rule, per surface and for both ends (undo writes `from`).
    std::map<SurfaceId, std::pair<std::vector<TrimPointRef>, std::vector<size_t>>> bySurface;
    for (size_t k = 0; k < refs.size(); ++k) {
        bySurface[refs[k].surface].first.push_back(refs[k]);
        bySurface[refs[k].surface].second.push_back(k);
    }
    for (const auto& [surface, group] : bySurface)
        for (const auto* positions : {&from, &to}) {
            std::vector<glm::dvec2> at;
            for (size_t k : group.second)
                at.push_back((*positions)[k]);
            if (Status step = document->checkTrimPoints(group.first, at); !step)
                return step.error();
        }
    const QString text = refs.size() == 1 ? QStringLiteral("Move trim point")
                                          : QStringLiteral("Move %1 trim points").arg(refs.size());
    std::unique_ptr<MoveTrimPoints> c(new MoveTrimPoints(document, text));
    c->m_refs = std::move(refs);
    c->m_from = std::move(from);
    c->m_to = std::move(to);
    c->m_kind = kind;
    return c;
}

// One Document call per surface, so coinciding curve ends move together and every loop stays
// closed (Document refuses a move that opens one).
void MoveTrimPoints::apply(const std::vector<glm::dvec2>& positions, const char* what) {
    std::map<SurfaceId, std::pair<std::vector<TrimPointRef>, std::vector<glm::dvec2>>> bySurface;
    for (size_t k = 0; k < m_refs.size(); ++k) {
        auto& [refs, to] = bySurface[m_refs[k].surface];
        refs.push_back(m_refs[k]);
        to.push_back(positions[k]);
    }
    Status done;
    for (const auto& [surface, moves] : bySurface)
        if (Status moved = document()->setTrimPoints(moves.first, moves.second); !moved)
            done = std::move(moved);
    check(done, what);
}

void MoveTrimPoints::redo() {
    apply(m_to, "redo");
}
void MoveTrimPoints::undo() {
    apply(m_from, "undo");
}

bool MoveTrimPoints::mergeWith(const QUndoCommand* other) {
    const auto* o = static_cast<const MoveTrimPoints*>(other);
    if (o->m_kind != MoveKind::Nudge || o->m_refs != m_refs)
        return false;
    m_to = o->m_to;
    setObsolete(m_to == m_from);
    return true;
}

// ---- SetMaterial

Expected<std::unique_ptr<SetMaterial>> SetMaterial::create(Document* document, SurfaceId surface,
                                                           const Material& material) {
    const Surface* s = surfaceIn(document, surface);
    if (!s)
        return Error(noSurface(document, surface));
    if (Status valid = checkMaterial(material); !valid)
        return std::move(valid).error();
    std::unique_ptr<SetMaterial> c(
        new SetMaterial(document, QStringLiteral("Change material of “%1”").arg(s->name)));
    c->m_surface = surface;
    c->m_from = s->material;
    c->m_to = material;
    return c;
}

void SetMaterial::redo() {
    check(document()->setMaterial(m_surface, m_to), "redo");
}
void SetMaterial::undo() {
    check(document()->setMaterial(m_surface, m_from), "undo");
}

bool SetMaterial::mergeWith(const QUndoCommand* other) {
    const auto* o = static_cast<const SetMaterial*>(other);
    if (o->m_surface != m_surface)
        return false;
    m_to = o->m_to;
    setObsolete(m_to == m_from);
    return true;
}

// ---- SetLights

Expected<std::unique_ptr<SetLights>> SetLights::make(Document* document, std::vector<Light> lights,
                                                     const QString& text, int changed) {
    if (!document)
        return Error(noDocument());
    if (Status valid = checkLights(lights); !valid)
        return std::move(valid).error();
    std::unique_ptr<SetLights> c(new SetLights(document, text));
    c->m_from = document->scene().lights;
    c->m_to = std::move(lights);
    c->m_changed = changed;
    return c;
}

Expected<std::unique_ptr<SetLights>> SetLights::create(Document* document,
                                                       std::vector<Light> lights) {
    return make(document, std::move(lights), QStringLiteral("Set lights"), -1);
}

Expected<std::unique_ptr<SetLights>> SetLights::addLight(Document* document, const Light& light) {
    if (!document)
        return Error(noDocument());
    std::vector<Light> lights = document->scene().lights;
    if (lights.size() >= size_t(kMaxLights))
        return Error(QStringLiteral("a scene has at most %1 lights").arg(kMaxLights));
    lights.push_back(light);
    return make(document, std::move(lights), QStringLiteral("Add light"), -1);
}

Expected<std::unique_ptr<SetLights>> SetLights::removeLight(Document* document, int index) {
    if (!document)
        return Error(noDocument());
    std::vector<Light> lights = document->scene().lights;
    if (index < 0 || size_t(index) >= lights.size())
        return Error(QStringLiteral("no light %1").arg(index + 1));
    if (lights.size() == 1)
        return Error(QStringLiteral("cannot remove the last light"));
    lights.erase(lights.begin() + index);
    return make(document, std::move(lights), QStringLiteral("Remove light %1").arg(index + 1), -1);
}

Expected<std::unique_ptr<SetLights>> SetLights::changeLight(Document* document, int index,
                                                            const Light& light) {
    if (!document)
        return Error(noDocument());
    std::vector<Light> lights = document->scene().lights;
    if (index < 0 || size_t(index) >= lights.size())
        return Error(QStringLiteral("no light %1").arg(index + 1));
    lights[size_t(index)] = light;
    return make(document, std::move(lights), QStringLiteral("Change light %1").arg(index + 1),
                index);
}

void SetLights::redo() {
    check(document()->setLights(m_to), "redo");
}
void SetLights::undo() {
    check(document()->setLights(m_from), "undo");
}

bool SetLights::mergeWith(const QUndoCommand* other) {
    const auto* o = static_cast<const SetLights*>(other);
    if (m_changed < 0 || o->m_changed != m_changed)
        return false;
    m_to = o->m_to;
    setObsolete(m_to == m_from);
    return true;
}

// ---- SetCamera

Expected<std::unique_ptr<SetCamera>> SetCamera::create(Document* document, const Camera& camera) {
    if (!document)
        return Error(noDocument());
    if (Status valid = checkCamera(camera); !valid)
        return std::move(valid).error();
    std::unique_ptr<SetCamera> c(new SetCamera(document, QStringLiteral("Change camera")));
    c->m_from = document->scene().camera;
    c->m_to = camera;
    return c;
}

void SetCamera::redo() {
    check(document()->setCamera(m_to), "redo");
}
void SetCamera::undo() {
    check(document()->setCamera(m_from), "undo");
}

bool SetCamera::mergeWith(const QUndoCommand* other) {
    m_to = static_cast<const SetCamera*>(other)->m_to;
    setObsolete(m_to == m_from);
    return true;
}

} // namespace kw
