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
#include <atomic>
#include <memory>
#include <optional>

namespace kw {

class Viewport;

class EdgeContinuityOverlay : public QObject {
    Q_OBJECT
public:
    /// Both must outlive the overlay.
    EdgeContinuityOverlay(Document* document, Viewport* viewport, QObject* parent = nullptr);
    /// Stops a run under way at its next block.
    ~EdgeContinuityOverlay() override;

    bool enabled() const { return m_enabled; }
    /// On: measures every edge and shows the bands and the legend; off: drops them. On a model
    /// of more than kForegroundFaces faces the pairing and the measure run on a pool thread and
    /// the bands appear when they are in (measuring() until then, progress in measureStatus);
    /// turning it off meanwhile, or a change of the scene's faces, cancels that run.
    void setEnabled(bool on);
    /// On, and every edge not measured yet (the bands not shown).
    bool measuring() const { return m_measuring; }
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
    /// Up to this many faces, turning the overlay on measures at once (under ~0.1 s, hammer.iges's
    /// 45 faces 75 ms): a "Measuring…" flash would cost more attention than the wait.
    static constexpr int kForegroundFaces = 64;

Q_SIGNALS:
    /// What the last edit of a face's shape opened ("opens 2 seams, max gap 0.8 mm"), empty
    /// when nothing: for the status bar, with the overlay on or off.
    void seamMessage(const QString& text);

    /// "Measuring edge continuity… N of M edges" while the overlay's first measure runs in the
    /// background; empty when it has ended (done, cancelled or turned off): for the status bar.
    void measureStatus(const QString& text);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    void rebuild(); ///< topology and every edge, at once
    /// The scene's faces changed (or the tolerances): on, measures again; off, forgets the
    /// topology and pairs the edges again once the event loop turns.
    void restart();
    /// A run on a pool thread over a copy of the scene as it is now: the edges paired (unless
    /// m_report already has the scene's topology) and, with the overlay on, every edge measured
    /// and its band made. Off, none is measured: each change of a face then measures its edges.
    void startBackground();
    struct BackgroundResult;
    /// A run's result, dropped if the scene's faces changed or the overlay was toggled since
    /// (`generation`); faces edited meanwhile (revisions unlike `revisions`) are measured again.
    void backgroundDone(BackgroundResult& result);
    void backgroundProgress(size_t done, size_t total, std::uint64_t generation);
    /// A new generation: any run under way is of a scene (or a state) that has changed since.
    void invalidate();
    void faceChanged(SurfaceId id, Aspects aspects);
    /// The bands again from the cached lines, after re-making those of the edges and free
    /// sides of `faces` (all of them when empty).
    void publish(const std::vector<SurfaceId>& faces = {});

    Document* m_doc;
    Viewport* m_viewport;
    bool m_enabled = false;
    ContinuityReport m_report;
    bool m_haveTopology = false; ///< m_report's topology is the document's
    bool m_measuring = false;
    bool m_pairingScheduled = false;
    /// Counts the changes of the scene's faces and the toggles; shared with the runs under way,
    /// which stop when it moves on.
    std::uint64_t m_generation = 0;
    std::shared_ptr<std::atomic<std::uint64_t>> m_latest;
    /// Expires with the overlay: a run that ends after it is dropped.
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
