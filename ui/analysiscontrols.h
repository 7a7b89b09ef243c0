// Analysis controls of the editor: View ▸ Analysis menu and the Analysis toolbar (modes,
// isocurves, colour range), and the colour-scale legend drawn over the 3D view.
#pragma once

#include "render/analysis.h"

#include <QObject>
#include <QRect>

class QMainWindow;
class QMenu;
class QPainter;
class QToolBar;

namespace kw {

class Viewport;

/// Builds the Analysis submenu in `viewMenu` and an "Analysis" toolbar on `window`, wired to
/// `viewport` (objects named actionAnalysis<Mode> with the mode's name in CamelCase,
/// actionIsocurves, actionAnalysisRange, actionDraftSettings, for tests). All pointers must outlive
/// the controls.
class AnalysisControls : public QObject {
    Q_OBJECT
public:
    AnalysisControls(QMainWindow* window, QMenu* viewMenu, Viewport* viewport);

    /// Opens the colour range dialog (automatic or LOW..HIGH, scale).
    void editRange();
    /// Opens the draft settings dialog (pull direction X, Y, Z and the minimum draft angle);
    /// saved with the project's display settings.
    void editDraft();
    /// The View > Analysis submenu (for the overlays other parts add to it).
    QMenu* menu() const { return m_menu; }

private:
    QMenu* m_menu = nullptr;
    QMainWindow* m_window;
    Viewport* m_viewport;
};

/// Draws the colour-map legend of `mode` in `area` (a vertical bar with five labelled ticks,
/// the mode's title and the scale): what the shader's colour scale means for `range`.
void drawColourLegend(QPainter& painter, const QRect& area, AnalysisMode mode,
                      const ValueRange& range, ColourScale scale, bool automatic);

/// Draws the draft legend in `area`: the three colours of kw::draftColours() with what each
/// means for `angleDegrees`, and the pull direction.
void drawDraftLegend(QPainter& painter, const QRect& area, const glm::dvec3& pull,
                     double angleDegrees);

} // namespace kw
