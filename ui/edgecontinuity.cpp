// The live Edge Continuity overlay: report, bands and the seams a drag opens.
#include "ui/edgecontinuity.h"

#include "model/document/document.h"
#include "render/render_types.h"
#include "ui/viewport.h"

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QHelpEvent>
#include <QThreadPool>
#include <QTimer>
#include <QToolTip>
#include <algorithm>

namespace kw {

EdgeContinuityOverlay::EdgeContinuityOverlay(Document* document, Viewport* viewport,
                                             QObject* parent)
    : QObject(parent), m_doc(document), m_viewport(viewport),
      m_alive(std::make_shared<EdgeContinuityOverlay*>(this)) {
    const auto whole = [this] {
        if (m_enabled)
            rebuild();
        else
            forget();
    };
    connect(m_doc, &Document::sceneReset, this, whole);
    connect(m_doc, &Document::surfaceInserted, this, whole);
    connect(m_doc, &Document::surfaceRemoved, this, whole);
    connect(m_doc, &Document::trimLoopInserted, this, whole);
    connect(m_doc, &Document::trimLoopRemoved, this, whole);
    connect(m_doc, &Document::continuityTolerancesChanged, this, whole);
    connect(m_doc, &Document::surfaceChanged, this,
            [this](SurfaceId id, Aspects aspects) { faceChanged(id, aspects); });
    m_viewport->installEventFilter(this);
    forget(); // off: the status bar's check pairs the document's edges
}

std::optional<size_t> EdgeContinuityOverlay::edgeAt(QPoint pos) const {
    const std::vector<std::vector<EdgeBandVertex>>& lines = m_lines.edgeLines();
    if (!m_enabled || lines.size() != m_report.edges.size() || m_viewport->width() <= 0 ||
        m_viewport->height() <= 0)
        return std::nullopt;
    const double w = m_viewport->width(), h = m_viewport->height();
    const CameraMatrices m =
        cameraMatrices(m_viewport->cameraController().camera(), m_doc->scene(), w / h);
    const glm::dmat4 vp = m.projection * m.view;
    const glm::dvec2 at(pos.x(), pos.y());
    std::optional<size_t> best;
    double bestDistance = 8.0;
    for (size_t k = 0; k < lines.size(); ++k)
        for (size_t v = 0; v + 1 < lines[k].size(); v += 2) {
            glm::dvec2 ends[2];
            bool visible = true;
            for (int e = 0; e < 2; ++e) {
                const glm::dvec4 c =
                    vp * glm::dvec4(glm::dvec3(lines[k][v + size_t(e)].position), 1.0);
                visible = visible && c.w > 0.0;
                ends[e] = glm::dvec2((c.x / c.w * 0.5 + 0.5) * w, (0.5 - c.y / c.w * 0.5) * h);
            }
            if (!visible)
                continue;
            const glm::dvec2 d = ends[1] - ends[0];
            const double t = glm::dot(d, d) > 0.0
                                 ? std::clamp(glm::dot(at - ends[0], d) / glm::dot(d, d), 0.0, 1.0)
                                 : 0.0;
            const double distance = glm::length(ends[0] + t * d - at);
            if (distance < bestDistance) {
                bestDistance = distance;
                best = k;
            }
        }
    return best;
}

QString EdgeContinuityOverlay::edgeText(size_t k) const {
    const EdgeContinuity& e = m_report.edges.at(k);
    return tr("%1 edge between surfaces %2 and %3\nG0 gap %4\nG1 angle %5°\nG2 curvature jump %6 %")
        .arg(continuityClassName(e.continuity))
        .arg(e.edge.sides[0].surface.value)
        .arg(e.edge.sides[1].surface.value)
        .arg(e.g0, 0, 'g', 3)
        .arg(e.g1Degrees, 0, 'g', 3)
        .arg(e.g2Percent, 0, 'g', 3);
}

bool EdgeContinuityOverlay::eventFilter(QObject* watched, QEvent* event) {
    if (watched == m_viewport && event->type() == QEvent::ToolTip && m_enabled) {
        const auto* help = static_cast<QHelpEvent*>(event);
        if (const std::optional<size_t> k = edgeAt(help->pos()))
            QToolTip::showText(help->globalPos(), edgeText(*k), m_viewport);
        else
            QToolTip::hideText();
        return true;
    }
    return QObject::eventFilter(watched, event);
}

void EdgeContinuityOverlay::setEnabled(bool on) {
    if (on == m_enabled)
        return;
    m_enabled = on;
    if (on) {
        rebuild();
    } else {
        forget();
        m_bands.reset();
        m_lines.clear();
        m_viewport->setEdgeBands(nullptr);
    }
}

void EdgeContinuityOverlay::rebuild() {
    QElapsedTimer clock;
    clock.start();
    m_report = continuityReport(m_doc->scene(), continuityTolerances(m_doc->scene()));
    m_haveTopology = true;
    m_lines.clear();
    publish();
    m_lastMs = double(clock.nsecsElapsed()) * 1e-6;
}

void EdgeContinuityOverlay::forget() {
    m_report = {};
    m_haveTopology = false;
    ++m_generation; // a pairing under way is of a scene that has changed since
    // The edges must be paired before the first edit moves a face off its neighbours (a
    // dragged boundary would match nothing): once the event loop turns after the change, so
    // a burst of structural changes pairs once.
    if (!m_pairingScheduled) {
        m_pairingScheduled = true;
        QTimer::singleShot(0, this, [this] {
            m_pairingScheduled = false;
            if (!m_enabled && !m_haveTopology)
                pairInBackground();
        });
    }
}

void EdgeContinuityOverlay::pairInBackground() {
    // Pairing a large model takes seconds (10,000 faces: docs/PERFORMANCE.md ## Editing), so
    // it runs on a pool thread over a copy of the scene as it is now, before any edit, and
    // the view stays live; until it is in, edits say nothing.
    auto scene = std::make_shared<const Scene>(m_doc->scene());
    const std::uint64_t generation = m_generation;
    const std::weak_ptr<EdgeContinuityOverlay*> alive = m_alive;
    QThreadPool::globalInstance()->start([scene, generation, alive] {
        auto report = std::make_shared<ContinuityReport>(
            continuityWatch(*scene, continuityTolerances(*scene)));
        if (QCoreApplication* app = QCoreApplication::instance())
            QMetaObject::invokeMethod(
                app,
                [report, generation, alive] {
                    // On the GUI thread, as the overlay's destructor: lock() is safe there.
                    if (const std::shared_ptr<EdgeContinuityOverlay*> self = alive.lock())
                        (*self)->paired(std::move(*report), generation);
                },
                Qt::QueuedConnection);
    });
}

void EdgeContinuityOverlay::paired(ContinuityReport&& report, std::uint64_t generation) {
    if (generation != m_generation || m_enabled || m_haveTopology)
        return;
    m_report = std::move(report);
    m_haveTopology = true;
}

void EdgeContinuityOverlay::faceChanged(SurfaceId id, Aspects aspects) {
    // Shape and trims move edges; hiding changes what is drawn (with the overlay on); a rename
    // changes nothing.
    const bool shape = (aspects & (Aspect::Points | Aspect::Knots | Aspect::Trims)) != Aspects();
    if (!shape && !(m_enabled && aspects.testFlag(Aspect::Display)))
        return;
    if (!m_enabled) {
        // Off, the check is for drags, which change one face or a few per event: an edit of
        // many faces at once (a whole part moved) is not measured past the first few, so
        // it costs the user nothing they did not ask for.
        if (m_facesThisTurn == 0)
            QTimer::singleShot(0, this, [this] { m_facesThisTurn = 0; });
        if (++m_facesThisTurn > kMaxFacesPerTurnOff)
            return;
    }
    QElapsedTimer clock;
    clock.start();
    if (!m_haveTopology)
        return; // off, and the pairing of the scene's faces is not in yet
    updateContinuity(m_report, m_doc->scene(), {id});
    if (m_enabled)
        publish({id});
    m_lastMs = double(clock.nsecsElapsed()) * 1e-6;
    if (shape)
        Q_EMIT seamMessage(
            seamOpeningText(seamsOpenAt(m_report, {id}), lengthUnitKey(m_doc->scene().unit)));
}

void EdgeContinuityOverlay::publish(const std::vector<SurfaceId>& faces) {
    m_bands = m_lines.update(m_doc->scene(), m_report, faces);
    m_viewport->setEdgeBands(m_bands);
}

} // namespace kw
