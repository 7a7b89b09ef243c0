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
#include <atomic>

namespace kw {

EdgeContinuityOverlay::EdgeContinuityOverlay(Document* document, Viewport* viewport,
                                             QObject* parent)
    : QObject(parent), m_doc(document), m_viewport(viewport),
      m_latest(std::make_shared<std::atomic<std::uint64_t>>(0)),
      m_alive(std::make_shared<EdgeContinuityOverlay*>(this)) {
    const auto whole = [this] {
        restart();
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
    restart(); // off: the status bar's check pairs the document's edges
}

EdgeContinuityOverlay::~EdgeContinuityOverlay() {
    m_latest->store(++m_generation);
}

std::optional<size_t> EdgeContinuityOverlay::edgeAt(QPoint pos) const {
    if (!m_enabled || m_lines.edgeCount() != m_report.edges.size() || m_viewport->width() <= 0 ||
        m_viewport->height() <= 0)
        return std::nullopt;
    const double w = m_viewport->width(), h = m_viewport->height();
    const CameraMatrices m =
        cameraMatrices(m_viewport->cameraController().camera(), m_doc->scene(), w / h);
    const glm::dmat4 vp = m.projection * m.view;
    const glm::dvec2 at(pos.x(), pos.y());
    std::optional<size_t> best;
    double bestDistance = 8.0;
    for (size_t k = 0; k < m_lines.edgeCount(); ++k) {
        const std::span<const EdgeBandVertex> line = m_lines.edgeLine(k);
        for (size_t v = 0; v + 1 < line.size(); v += 2) {
            glm::dvec2 ends[2];
            bool visible = true;
            for (int e = 0; e < 2; ++e) {
                const glm::dvec4 c = vp * glm::dvec4(glm::dvec3(line[v + size_t(e)].position), 1.0);
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
        if (int(m_doc->scene().surfaces.size()) <= kForegroundFaces) {
            invalidate();
            rebuild();
            return;
        }
        // The pairing done while off (if in) is the scene's: only the measure is left to do.
        const bool paired = m_haveTopology;
        invalidate();
        m_haveTopology = paired;
        startBackground();
    } else {
        // Measured, the topology serves the status bar's check, its edges set back to "not
        // measured" as that check keeps them (it reports only what the next edits open); a
        // measure under way is dropped (its result would be of an overlay since turned off)
        // and the edges paired again for that check.
        if (m_haveTopology) {
            invalidate();
            for (EdgeContinuity& e : m_report.edges)
                e = EdgeContinuity{e.edge};
        } else {
            restart();
        }
        m_bands.reset();
        m_lines.clear();
        m_viewport->setEdgeBands(nullptr);
    }
}

void EdgeContinuityOverlay::invalidate() {
    m_latest->store(++m_generation);
    if (m_measuring) {
        m_measuring = false;
        Q_EMIT measureStatus(QString());
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

void EdgeContinuityOverlay::restart() {
    invalidate();
    m_report = {};
    m_haveTopology = false;
    if (m_enabled) {
        // Bands of the scene as it was are not shown over the scene as it is.
        m_lines.clear();
        m_bands.reset();
        m_viewport->setEdgeBands(nullptr);
        if (int(m_doc->scene().surfaces.size()) <= kForegroundFaces) {
            rebuild();
            return;
        }
    }
    // The edges must be paired before the first edit moves a face off its neighbours (a
    // dragged boundary would match nothing): once the event loop turns after the change, so
    // a burst of structural changes pairs (or measures) once.
    if (!m_pairingScheduled) {
        m_pairingScheduled = true;
        QTimer::singleShot(0, this, [this] {
            m_pairingScheduled = false;
            if (!m_haveTopology && !m_measuring)
                startBackground();
        });
    }
}

struct EdgeContinuityOverlay::BackgroundResult {
    std::uint64_t generation = 0;
    bool measured = false;
    ContinuityReport report;
    EdgeBandCache lines;
    std::shared_ptr<const EdgeBands> bands;
    /// The document's revisions of each face when the scene was copied.
    std::vector<Revisions> revisions;
};

void EdgeContinuityOverlay::startBackground() {
    // Pairing a large model takes seconds and measuring every edge tens of seconds (10,000
    // faces: docs/PERFORMANCE.md ## Editing), so both run on a pool thread over a copy of the
    // scene as it is now, and the view stays live; until they are in, the overlay shows nothing
    // and edits say nothing.
    auto scene = std::make_shared<const Scene>(m_doc->scene());
    auto job = std::make_shared<BackgroundResult>();
    job->generation = m_generation;
    job->measured = m_enabled;
    job->revisions.reserve(scene->surfaces.size());
    for (int i = 0; i < int(scene->surfaces.size()); ++i)
        job->revisions.push_back(m_doc->revisionsAt(i));
    if (m_haveTopology) {
        job->report.tolerances = m_report.tolerances;
        job->report.topology = m_report.topology;
    }
    const bool paired = m_haveTopology;
    m_haveTopology = false; // until the run is in, edits measure nothing
    m_report = {};
    if (m_enabled) {
        m_measuring = true;
        Q_EMIT measureStatus(tr("Measuring edge continuity… pairing the edges"));
    }
    const std::shared_ptr<std::atomic<std::uint64_t>> latest = m_latest;
    const std::weak_ptr<EdgeContinuityOverlay*> alive = m_alive;
    // Posts to the GUI thread, where the overlay lives and dies: lock() is safe there.
    const auto post = [alive](auto&& call) {
        if (QCoreApplication* app = QCoreApplication::instance())
            QMetaObject::invokeMethod(
                app,
                [alive, call] {
                    if (const std::shared_ptr<EdgeContinuityOverlay*> self = alive.lock())
                        call(*self);
                },
                Qt::QueuedConnection);
    };
    QThreadPool::globalInstance()->start([scene, job, paired, latest, post] {
        const std::uint64_t generation = job->generation;
        const auto current = [&] {
            return latest->load() == generation;
        };
        if (!paired)
            job->report = continuityWatch(*scene, continuityTolerances(*scene));
        if (!current())
            return;
        if (job->measured) {
            const bool done = measureContinuity(job->report, *scene, [&](size_t n, size_t total) {
                post([n, total, generation](EdgeContinuityOverlay* self) {
                    self->backgroundProgress(n, total, generation);
                });
                return current();
            });
            if (!done)
                return;
            job->bands = job->lines.update(*scene, job->report);
        }
        if (current())
            post([job](EdgeContinuityOverlay* self) { self->backgroundDone(*job); });
    });
}

void EdgeContinuityOverlay::backgroundProgress(size_t done, size_t total,
                                               std::uint64_t generation) {
    if (generation == m_generation && m_measuring)
        Q_EMIT measureStatus(tr("Measuring edge continuity… %1 of %2 edges").arg(done).arg(total));
}

void EdgeContinuityOverlay::backgroundDone(BackgroundResult& result) {
    if (result.generation != m_generation || result.measured != m_enabled || m_haveTopology)
        return;
    const Scene& scene = m_doc->scene();
    // Same generation: no face was added or removed, so the copy's faces are the document's,
    // in order. Those edited while the run was under way (a drag) are measured again now.
    std::vector<SurfaceId> reshaped, redrawn;
    for (size_t i = 0; i < scene.surfaces.size() && i < result.revisions.size(); ++i) {
        const Revisions now = m_doc->revisionsAt(int(i)), then = result.revisions[i];
        if (now.points != then.points || now.knots != then.knots || now.trims != then.trims)
            reshaped.push_back(scene.surfaces[i].id);
        if (now != then)
            redrawn.push_back(scene.surfaces[i].id);
    }
    std::sort(reshaped.begin(), reshaped.end());
    m_report = std::move(result.report);
    m_haveTopology = true;
    if (!reshaped.empty())
        updateContinuity(m_report, scene, reshaped);
    if (!result.measured)
        return;
    m_lines = std::move(result.lines);
    m_bands = redrawn.empty() ? result.bands : m_lines.update(scene, m_report, redrawn);
    m_viewport->setEdgeBands(m_bands);
    m_measuring = false;
    Q_EMIT measureStatus(QString());
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
