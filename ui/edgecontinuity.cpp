// The live Edge Continuity overlay: report, bands and the seams a drag opens.
#include "ui/edgecontinuity.h"

#include "model/document/document.h"
#include "render/render_types.h"
#include "ui/viewport.h"

#include <QDialog>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFormLayout>
#include <QHelpEvent>
#include <QLabel>
#include <QToolTip>
#include <algorithm>

namespace kw {

EdgeContinuityOverlay::EdgeContinuityOverlay(Document* document, Viewport* viewport,
                                             QObject* parent)
    : QObject(parent), m_doc(document), m_viewport(viewport) {
    const auto whole = [this] {
        if (m_enabled)
            rebuild();
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
}

std::optional<size_t> EdgeContinuityOverlay::edgeAt(QPoint pos) const {
    if (!m_enabled || m_edgeLines.size() != m_report.edges.size() || m_viewport->width() <= 0 ||
        m_viewport->height() <= 0)
        return std::nullopt;
    const double w = m_viewport->width(), h = m_viewport->height();
    const CameraMatrices m =
        cameraMatrices(m_viewport->cameraController().camera(), m_doc->scene(), w / h);
    const glm::dmat4 vp = m.projection * m.view;
    const glm::dvec2 at(pos.x(), pos.y());
    std::optional<size_t> best;
    double bestDistance = 8.0;
    for (size_t k = 0; k < m_edgeLines.size(); ++k)
        for (size_t v = 0; v + 1 < m_edgeLines[k].size(); v += 2) {
            glm::dvec2 ends[2];
            bool visible = true;
            for (int e = 0; e < 2; ++e) {
                const glm::dvec4 c =
                    vp * glm::dvec4(glm::dvec3(m_edgeLines[k][v + size_t(e)].position), 1.0);
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
        m_report = {};
        m_bands.reset();
        m_edgeLines.clear();
        m_freeLines.clear();
        m_viewport->setEdgeBands(nullptr);
    }
}

void EdgeContinuityOverlay::rebuild() {
    QElapsedTimer clock;
    clock.start();
    m_report = continuityReport(m_doc->scene(), continuityTolerances(m_doc->scene()));
    m_edgeLines.clear();
    m_freeLines.clear();
    publish();
    m_lastMs = double(clock.nsecsElapsed()) * 1e-6;
}

void EdgeContinuityOverlay::faceChanged(SurfaceId id, Aspects aspects) {
    if (!m_enabled)
        return;
    // Shape and trims move edges; hiding changes what is drawn; a rename changes nothing.
    if (!(aspects & (Aspect::Points | Aspect::Knots | Aspect::Trims | Aspect::Display)))
        return;
    QElapsedTimer clock;
    clock.start();
    updateContinuity(m_report, m_doc->scene(), {id});
    publish({id});
    m_lastMs = double(clock.nsecsElapsed()) * 1e-6;
    Q_EMIT seamMessage(seamOpeningText(seamsOpenAt(m_report, {id})));
}

void EdgeContinuityOverlay::publish(const std::vector<SurfaceId>& faces) {
    const bool all = faces.empty() || m_edgeLines.size() != m_report.edges.size() ||
                     m_freeLines.size() != m_report.topology.freeSides.size();
    const auto touched = [&](const ContinuitySide& side) {
        return all || std::find(faces.begin(), faces.end(), side.surface) != faces.end();
    };
    const auto line = [&](const ContinuitySide& side, const glm::vec4& color) {
        const Surface* s = m_doc->surface(side.surface);
        return s && !s->hidden ? edgeBandLine(*s, side, color) : std::vector<EdgeBandVertex>{};
    };
    m_edgeLines.resize(m_report.edges.size());
    m_freeLines.resize(m_report.topology.freeSides.size());
    for (size_t k = 0; k < m_report.edges.size(); ++k) {
        const EdgeContinuity& e = m_report.edges[k];
        const ContinuitySide& side = e.edge.covers[0] ? e.edge.sides[0] : e.edge.sides[1];
        // A class may change with the other side's edit: colours are re-made for every edge
        // of the faces, the curve only where the side's own face changed.
        if (touched(e.edge.sides[0]) || touched(e.edge.sides[1]))
            m_edgeLines[k] = line(side, continuityColor(e.continuity));
    }
    for (size_t k = 0; k < m_report.topology.freeSides.size(); ++k)
        if (touched(m_report.topology.freeSides[k]))
            m_freeLines[k] = line(m_report.topology.freeSides[k], freeEdgeColor());
    auto bands = std::make_shared<EdgeBands>();
    bands->revision = ++m_revision;
    for (const auto* lines : {&m_edgeLines, &m_freeLines})
        for (const std::vector<EdgeBandVertex>& l : *lines)
            bands->vertices.insert(bands->vertices.end(), l.begin(), l.end());
    m_bands = bands;
    m_viewport->setEdgeBands(m_bands);
}

std::optional<ContinuityTolerances> editContinuityTolerances(QWidget* parent,
                                                             const ContinuityTolerances& initial) {
    QDialog d(parent);
    d.setWindowTitle(QObject::tr("Continuity tolerances"));
    auto* form = new QFormLayout(&d);
    const auto spin = [](double value, const char* name, const QString& suffix) {
        auto* s = new QDoubleSpinBox;
        s->setObjectName(QLatin1String(name));
        s->setDecimals(6);
        s->setRange(1e-6, 1e6);
        s->setValue(value);
        s->setSuffix(suffix);
        return s;
    };
    QDoubleSpinBox* g0 = spin(initial.g0, "toleranceG0", QString());
    QDoubleSpinBox* g1 = spin(initial.g1Degrees, "toleranceG1", QObject::tr(" deg"));
    QDoubleSpinBox* g2 = spin(initial.g2Percent, "toleranceG2", QObject::tr(" %"));
    QDoubleSpinBox* match = spin(initial.match, "toleranceMatch", QString());
    form->addRow(QObject::tr("G0 gap (model units)"), g0);
    form->addRow(QObject::tr("G1 angle"), g1);
    form->addRow(QObject::tr("G2 curvature jump"), g2);
    form->addRow(QObject::tr("Edges of faces without a record: match within"), match);
    auto* why = new QLabel;
    form->addRow(why);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    QObject::connect(buttons, &QDialogButtonBox::rejected, &d, &QDialog::reject);
    ContinuityTolerances result;
    QObject::connect(buttons, &QDialogButtonBox::accepted, &d, [&] {
        result = {g0->value(), g1->value(), g2->value(), match->value()};
        const QString error = continuityTolerancesError(result);
        if (error.isEmpty())
            d.accept();
        else
            why->setText(error);
    });
    form->addRow(buttons);
    if (d.exec() != QDialog::Accepted)
        return std::nullopt;
    return result;
}

} // namespace kw
