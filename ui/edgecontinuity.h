// View > Analysis > Edge Continuity: keeps the continuity kernel's report of the document and
// the overlay's bands up to date, re-measuring only the changed faces' edges on the document's
// change signal (so it is live during a drag without knowing about gestures).
#pragma once

#include "model/analysis/continuity.h"
#include "model/document/document.h"
#include "render/edge_bands.h"

#include <QObject>
#include <QPoint>
#include <optional>

class QWidget;
#include <memory>

namespace kw {

class Viewport;

class EdgeContinuityOverlay : public QObject {
    Q_OBJECT
public:
    /// Both must outlive the overlay.
    EdgeContinuityOverlay(Document* document, Viewport* viewport, QObject* parent = nullptr);

    bool enabled() const { return m_enabled; }
    /// On: measures every edge and shows the bands and the legend; off: drops them.
    void setEnabled(bool on);
    const ContinuityReport& report() const { return m_report; }
    /// The bands last handed to the viewport (null when off).
    std::shared_ptr<const EdgeBands> bands() const { return m_bands; }
    /// The edge (index into report().edges) whose band passes within 8 pixels of `pos` in the
    /// view (widget coordinates), the nearest; nullopt for none. Hovering it shows its values.
    std::optional<size_t> edgeAt(QPoint pos) const;
    /// The hover text of edge `k`: its class, gap, angle, jump and faces.
    QString edgeText(size_t k) const;
    /// Milliseconds the last update took (measure and bands), for the bench and the note.
    double lastUpdateMs() const { return m_lastMs; }

Q_SIGNALS:
    /// What the last edit opened ("opens 2 seams, max gap 0.8"), empty when nothing: for the
    /// status bar.
    void seamMessage(const QString& text);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    void rebuild(); ///< topology and every edge
    void faceChanged(SurfaceId id, Aspects aspects);
    /// The bands again from the cached lines, after re-making those of the edges and free
    /// sides of `faces` (all of them when empty).
    void publish(const std::vector<SurfaceId>& faces = {});

    Document* m_doc;
    Viewport* m_viewport;
    bool m_enabled = false;
    ContinuityReport m_report;
    std::shared_ptr<const EdgeBands> m_bands;
    /// Per edge of m_report and per free side, its band's segments, so that a drag step
    /// re-makes only the dragged face's.
    std::vector<std::vector<EdgeBandVertex>> m_edgeLines, m_freeLines;
    std::uint64_t m_revision = 0;
    double m_lastMs = 0.0;
};

/// The tolerances dialog (G0 and match distance in model units, G1 in degrees, G2 in percent);
/// nullopt when cancelled. It accepts only valid values (continuityTolerancesError).
std::optional<ContinuityTolerances> editContinuityTolerances(QWidget* parent,
                                                             const ContinuityTolerances& initial);

} // namespace kw
