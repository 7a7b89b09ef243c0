// Edit commands that add, remove and rename surfaces and add or remove trim loops.
#include "model/document/validation.h"
#include "ui/edit/commands.h"
#include "ui/edit/commandsupport.h"

#include <set>

namespace kw {

using namespace edit_detail;

namespace {

bool loopIdUsed(const Scene& scene, TrimLoopId id) {
    for (const Surface& s : scene.surfaces)
        if (findLoop(&s, id))
            return true;
    return false;
}

QString curves(size_t n) {
    return n == 1 ? QStringLiteral("1 curve") : QStringLiteral("%1 curves").arg(n);
}

} // namespace

// ---- AddSurface

Expected<std::unique_ptr<AddSurface>> AddSurface::create(Document* document, Surface surface,
                                                         int index) {
    if (!document)
        return Error(noDocument());
    const auto& surfaces = document->scene().surfaces;
    if (index == -1)
        index = int(surfaces.size());
    if (index < 0 || size_t(index) > surfaces.size())
        return Error(QStringLiteral("surface index %1 out of range").arg(index));
    if (surface.id.isValid() && document->surface(surface.id))
        return Error(QStringLiteral("surface id %1 already used").arg(surface.id.value));
    std::set<TrimLoopId> ids;
    for (const TrimLoop& l : surface.trims)
        if (l.id.isValid() && (loopIdUsed(document->scene(), l.id) || !ids.insert(l.id).second))
            return Error(QStringLiteral("trim loop id %1 already used").arg(l.id.value));
    // Check everything but the ids before allocating any, so a rejected edit uses up none.
    Surface probe = surface;
    probe.id = SurfaceId{1};
    std::uint32_t next = 1;
    for (TrimLoop& l : probe.trims)
        l.id = TrimLoopId{next++};
    if (Status valid = checkSurface(probe); !valid)
        return std::move(valid).error();
    if (!surface.id.isValid())
        surface.id = document->allocateSurfaceId();
    for (TrimLoop& l : surface.trims)
        if (!l.id.isValid())
            l.id = document->allocateTrimLoopId();
    if (!surface.id.isValid())
        return Error(QStringLiteral("no ids left"));
    const QString text = QStringLiteral("Add surface “%1”").arg(surface.name);
    std::unique_ptr<AddSurface> c(new AddSurface(document, text));
    c->m_surface = std::move(surface);
    c->m_index = index;
    return c;
}

void AddSurface::redo() {
    check(document()->insertSurface(m_index, m_surface), "redo");
}
void AddSurface::undo() {
    check(document()->removeSurface(m_surface.id), "undo");
}

// ---- RemoveSurface

Expected<std::unique_ptr<RemoveSurface>> RemoveSurface::create(Document* document,
                                                               SurfaceId surface) {
    const Surface* s = surfaceIn(document, surface);
    if (!s)
        return Error(noSurface(document, surface));
    std::unique_ptr<RemoveSurface> c(
        new RemoveSurface(document, QStringLiteral("Remove surface “%1”").arg(s->name)));
    c->m_surface = *s;
    c->m_index = document->indexOf(surface);
    return c;
}

void RemoveSurface::redo() {
    check(document()->removeSurface(m_surface.id), "redo");
}
void RemoveSurface::undo() {
    check(document()->insertSurface(m_index, m_surface), "undo");
}

// ---- RenameSurface

Expected<std::unique_ptr<RenameSurface>>
RenameSurface::create(Document* document, SurfaceId surface, const QString& name) {
    const Surface* s = surfaceIn(document, surface);
    if (!s)
        return Error(noSurface(document, surface));
    if (name.trimmed().isEmpty())
        return Error(QStringLiteral("a surface name needs a visible character"));
    if (name == s->name)
        return Error(QStringLiteral("surface is already named “%1”").arg(name));
    std::unique_ptr<RenameSurface> c(
        new RenameSurface(document, QStringLiteral("Rename “%1” to “%2”").arg(s->name, name)));
    c->m_surface = surface;
    c->m_from = s->name;
    c->m_to = name;
    return c;
}

void RenameSurface::redo() {
    check(document()->setName(m_surface, m_to), "redo");
}
void RenameSurface::undo() {
    check(document()->setName(m_surface, m_from), "undo");
}

// ---- AddTrimLoop

Expected<std::unique_ptr<AddTrimLoop>> AddTrimLoop::create(Document* document, SurfaceId surface,
                                                           TrimLoop loop, int index) {
    const Surface* s = surfaceIn(document, surface);
    if (!s)
        return Error(noSurface(document, surface));
    if (index == -1)
        index = int(s->trims.size());
    if (index < 0 || size_t(index) > s->trims.size())
        return Error(QStringLiteral("trim loop index %1 out of range").arg(index));
    if (loop.id.isValid() && loopIdUsed(document->scene(), loop.id))
        return Error(QStringLiteral("trim loop id %1 already used").arg(loop.id.value));
    TrimLoop probe = loop;
    probe.id = TrimLoopId{1};
    if (Status valid = checkTrimLoop(probe); !valid)
        return std::move(valid).error();
    if (!loop.id.isValid())
        loop.id = document->allocateTrimLoopId();
    if (!loop.id.isValid())
        return Error(QStringLiteral("no ids left"));
    const QString text =
        QStringLiteral("Add trim loop (%1) to “%2”").arg(curves(loop.curves.size()), s->name);
    std::unique_ptr<AddTrimLoop> c(new AddTrimLoop(document, text));
    c->m_surface = surface;
    c->m_loop = std::move(loop);
    c->m_index = index;
    return c;
}

void AddTrimLoop::redo() {
    check(document()->insertTrimLoop(m_surface, m_index, m_loop), "redo");
}
void AddTrimLoop::undo() {
    check(document()->removeTrimLoop(m_surface, m_loop.id), "undo");
}

// ---- RemoveTrimLoop

Expected<std::unique_ptr<RemoveTrimLoop>>
RemoveTrimLoop::create(Document* document, SurfaceId surface, TrimLoopId loop) {
    const Surface* s = surfaceIn(document, surface);
    if (!s)
        return Error(noSurface(document, surface));
    const TrimLoop* l = findLoop(s, loop);
    if (!l)
        return Error(
            QStringLiteral("surface %1 has no trim loop %2").arg(surface.value).arg(loop.value));
    const int index = int(l - s->trims.data());
    std::unique_ptr<RemoveTrimLoop> c(new RemoveTrimLoop(
        document, QStringLiteral("Remove trim loop %1 from “%2”").arg(loop.value).arg(s->name)));
    c->m_surface = surface;
    c->m_loop = *l;
    c->m_index = index;
    return c;
}

void RemoveTrimLoop::redo() {
    check(document()->removeTrimLoop(m_surface, m_loop.id), "redo");
}
void RemoveTrimLoop::undo() {
    check(document()->insertTrimLoop(m_surface, m_index, m_loop), "undo");
}

} // namespace kw
