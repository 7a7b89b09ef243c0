// The Probe and Measure tools of the 3D view: the exact point under the cursor with its
// surface, (u, v), position, normal and curvature in a small panel that can be copied, and
// clicks that place measurements (ui/measure_tool.h).
#pragma once

#include "model/analysis/probe.h"
#include "render/frame_report.h"
#include "ui/measure_tool.h"
#include "ui/tools/tool.h"

#include <QObject>
#include <optional>

class QAction;
class QFrame;
class QLabel;
class QMenuBar;

namespace kw {

class Document;
class Viewport;

/// A tool of the view (ui/tools/tool.h): it listens to the view (Viewport::listen), and a
/// Probe or Measure mode installs it (Viewport::setTool). While Probe is on, or P is held over
/// the view, each hover move picks the surface under the cursor (Renderer::pick, one pixel),
/// refines the pick onto the pixel's ray (probeOnRay) and shows the values in a panel and a
/// marker, both child widgets of the view: a hover draws no frame of the view. Over background
/// the panel hides. In a Measure mode a plain left click probes the point and hands it to the
/// MeasureTool (the click does not select); Esc drops a half-made measurement, then leaves the
/// mode. Installing another tool (the curve tool) turns the mode off.
class ProbeTool : public QObject, public Tool {
    Q_OBJECT
public:
    enum class Mode { Off, Probe, Distance, Angle, Radius };

    /// Both must outlive the tool; the tool's parent is the viewport.
    ProbeTool(Document* document, Viewport* viewport);

    /// The Measure menu: Probe, Distance, Angle, Radius (one at a time), Copy Probe Values and
    /// Clear Measurements.
    void buildMenu(QMenuBar* bar);

    void setMode(Mode mode);
    Mode mode() const { return m_mode; }
    /// True while P is held over the view (the probe without the tool).
    bool probeHeld() const { return m_held; }

    /// Probes at a viewport position (logical pixels), as a mouse move does: updates the panel
    /// and marker; nullopt over background (panel hidden).
    std::optional<ProbePoint> probeAt(QPointF position);
    /// A measure click at a viewport position: false when nothing is there (a message says so).
    bool measureAt(QPointF position);
    /// The last probe (nullopt over background) and the panel's text (empty then).
    const std::optional<ProbePoint>& lastProbe() const { return m_probe; }
    QString panelText() const;
    /// Puts the panel's text on the clipboard; false when there is no probe.
    bool copyProbe();

    MeasureTool* measureTool() const { return m_measure; }
    QFrame* panel() const { return m_panel; }
    /// Wall time of the last probe update (pick, refinement, panel), its calling thread's CPU
    /// time, and the CPU part after the pick (refinement, curvature and text), in ms.
    double lastUpdateMs() const { return m_updateMs; }
    double lastUpdateCpuMs() const { return m_updateCpuMs; }
    double lastRefineMs() const { return m_refineMs; }

    // Tool
    bool press(QMouseEvent* event) override;
    void hover(QMouseEvent* event) override;
    bool key(QKeyEvent* event) override;
    bool keyRelease(QKeyEvent* event) override;
    bool overridesShortcut(const QKeyEvent* event) const override;
    void leave() override;
    void focusOut() override;
    void uninstalled() override;

Q_SIGNALS:
    /// For the status bar.
    void message(const QString& text);
    void probed();
    void measured(const kw::Measurement& m);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    /// The panel of values (a native window over a native view window).
    void makePanel();
    bool probing() const { return m_mode == Mode::Probe || m_held; }
    void hideProbe();
    /// The probe point at a position: pick, then refinement onto the ray through the centre of
    /// the picked device pixel.
    std::optional<ProbePoint> probePoint(QPointF position);
    std::optional<ProbePoint> refine(const PickHit& hit, QPointF position) const;

    Document* m_doc;
    Viewport* m_view;
    MeasureTool* m_measure;
    QFrame* m_panel;
    QLabel* m_text;
    Mode m_mode = Mode::Off;
    bool m_held = false;
    std::optional<ProbePoint> m_probe;
    double m_updateMs = 0.0, m_updateCpuMs = 0.0, m_refineMs = 0.0;
    QAction* m_actions[4] = {nullptr, nullptr, nullptr, nullptr}; ///< Probe .. Radius
};

} // namespace kw
