// Edit commands that add, remove and rename surfaces and add or remove trim loops.
#include "model/document/edit_checks.h"
#include "ui/edit/commands.h"
#include "ui/edit/commandsupport.h"

namespace kw {

using namespace edit_detail;

namespace {

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
    // The document's rule, on the ids the surface will have: its own, else those the document
    // hands out next, in the order allocated below. Checked before any is allocated, so a
    // refused edit uses up none.
    Surface probe = surface;
    std::uint32_t next = document->scene().nextId;
    if (!probe.id.isValid())
        probe.id = SurfaceId{next++};
    for (TrimLoop& l : probe.trims)
        if (!l.id.isValid())
            l.id = TrimLoopId{next++};
    if (Status allowed = checkInsertSurface(document->scene(), index, probe); !allowed)
        return std::move(allowed).error();
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
    if (Status valid = checkSurfaceName(name); !valid)
        return std::move(valid).error();
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
    // The document's rule, on the id the loop will have: its own, else the one the document
    // hands out next (none is allocated for a refused edit).
    TrimLoop probe = loop;
    if (!probe.id.isValid())
        probe.id = TrimLoopId{document->scene().nextId};
    if (Status allowed = checkInsertTrimLoop(document->scene(), *s, index, probe); !allowed)
        return std::move(allowed).error();
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
