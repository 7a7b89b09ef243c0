// View > Analysis > Edge Continuity: keeps the continuity kernel's report of the document and
// the overlay's bands up to date, re-measuring only the changed faces' edges on the document's
// change signal (so it is live during a drag without knowing about gestures). With the overlay
// off it still measures a changed face's edges (and no others), so the status bar can say what
// an edit opens.
#pragma once

#include "model/analysis/continuity.h"
#include "model/document/document.h"
#include "render/edge_bands.h"

#include <QObject>
#include <QPoint>
#include <memory>
#include <optional>

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
    /// On: every edge measured. Off: the edges paired (in the background after the last change
    /// of the scene's faces), only those of faces changed since measured; empty until then.
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
    /// What the last edit of a face's shape opened ("opens 2 seams, max gap 0.8 mm"), empty
    /// when nothing: for the status bar, with the overlay on or off.
    void seamMessage(const QString& text);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    void rebuild(); ///< topology and every edge
    /// Off: forgets the topology and pairs the edges again once the event loop turns.
    void forget();
    /// Off: the edges paired (continuityWatch, none measured) on a pool thread; each change of
    /// a face then measures its edges only.
    void pairInBackground();
    /// The pairing's result, kept unless the scene's faces changed since (`generation`) or
    /// the overlay was turned on.
    void paired(ContinuityReport&& report, std::uint64_t generation);
    void faceChanged(SurfaceId id, Aspects aspects);
    /// The bands again from the cached lines, after re-making those of the edges and free
    /// sides of `faces` (all of them when empty).
    void publish(const std::vector<SurfaceId>& faces = {});

    Document* m_doc;
    Viewport* m_viewport;
    bool m_enabled = false;
    ContinuityReport m_report;
    bool m_haveTopology = false; ///< m_report's topology is the document's
    bool m_pairingScheduled = false;
    std::uint64_t m_generation = 0; ///< counts the changes of the scene's faces
    /// Expires with the overlay: a pairing that ends after it is dropped.
    std::shared_ptr<EdgeContinuityOverlay*> m_alive;
    /// Faces changed since the event loop last turned, and how many of them the status bar's
    /// check (overlay off) measures.
    int m_facesThisTurn = 0;
    static constexpr int kMaxFacesPerTurnOff = 8;
    std::shared_ptr<const EdgeBands> m_bands;
    /// Per edge of m_report and per free side, its band's segments, so that a drag step
    /// re-makes only the dragged face's.
    EdgeBandCache m_lines;
    double m_lastMs = 0.0;
};

} // namespace kw
