// The 3D view's and the UV panel's tools under Xvfb: Esc cancels a drag and restores the
// document, every drag is one undo step, and a step the document refuses shows its reason in
// the status bar.
#include "editor_test_util.h"
#include "render/offscreen_renderer.h"
#include "ui/edit/commands.h"
#include "ui/uvpanel.h"

#include <QSettings>
#include <QStatusBar>
#include <QUndoStack>

using namespace kw;
using namespace kwtest;

/// A mode as a probe or measure tool would be: counts what the view routes to it, and takes
/// plain left presses as clicks.
struct RecordingTool : Tool {
    int presses = 0, hovers = 0, keys = 0, paints = 0;
    bool press(QMouseEvent* event) override {
        presses += event->button() == Qt::LeftButton;
        return event->button() == Qt::LeftButton;
    }
    void hover(QMouseEvent*) override { ++hovers; }
    bool key(QKeyEvent* event) override {
        keys += event->key() == Qt::Key_Escape;
        return event->key() == Qt::Key_Escape;
    }
    void paint(QPainter&) override { ++paints; }
};

class TestTools : public EditorTestBase {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
        qputenv("XDG_CONFIG_HOME", QByteArrayLiteral(KW_TEST_OUTPUT_DIR "/tools-config"));
    }

private:
    const NurbsSurface& geometry() const {
        return m_window->document()->scene().surfaces.front().geometry;
    }
    /// An interior control point of the first surface the picker finds at its own pixel.
    std::pair<ControlPointRef, QPoint> pickablePoint(int skip = 0) const {
        Viewport* vp = m_window->viewport();
        ControlPointPicker picker;
        picker.update(*m_window->document(), vp->viewProjection());
        const Surface& s = m_window->document()->scene().surfaces.front();
        for (int j = 1; j + 1 < s.geometry.countV; ++j)
            for (int i = 1; i + 1 < s.geometry.countU; ++i) {
                const ControlPointRef ref{s.id, i, j};
                const auto px = picker.pixelOf(ref);
                if (!px || !vp->rect().adjusted(60, 60, -60, -60).contains(px->toPoint()))
                    continue;
                if (picker.nearest(px->toPoint()) == ref && skip-- == 0)
                    return {ref, px->toPoint()};
            }
        return {};
    }
    void drag(QPoint from, QPoint to, Qt::KeyboardModifiers mods = Qt::NoModifier) {
        Viewport* vp = m_window->viewport();
        QTest::mousePress(vp, Qt::LeftButton, mods, from);
        QTest::mouseMove(vp, (from + to) / 2);
        QTest::mouseMove(vp, to);
        QTest::mouseRelease(vp, Qt::LeftButton, mods, to);
    }

private Q_SLOTS:
    void initTestCase() {
        QCoreApplication::setOrganizationName(QStringLiteral("KnotworkTest"));
        QSettings().clear();
    }
    void cleanup() { closeWindow(); }

    void escapeCancelsDragOfSeveralPointsAndRestores() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        // Every visible point picked by a band, then a drag from one of them moves them all.
        const QPoint a(2, 2), b(vp->width() - 3, vp->height() - 3);
        drag(a, b);
        QVERIFY(m_window->selection()->controlPoints().size() > 4);
        const auto [ref, press] = pickablePoint();
        QVERIFY(ref.surface.isValid());
        const NurbsSurface before = geometry();
        QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, press);
        QVERIFY(vp->isDragging());
        QTest::mouseMove(vp, press + QPoint(30, 20));
        int moved = 0;
        for (size_t k = 0; k < before.points.size(); ++k)
            moved += geometry().points[k] != before.points[k];
        QVERIFY2(moved > 4, qPrintable(QString::number(moved)));
        QTest::keyClick(vp, Qt::Key_Escape);
        QVERIFY(!vp->isDragging());
        QVERIFY(geometry() == before);
        // The rest of the cancelled gesture does nothing, and no step was recorded.
        QTest::mouseMove(vp, press + QPoint(50, 40));
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, press + QPoint(50, 40));
        QVERIFY(geometry() == before);
        QCOMPARE(m_window->undoStack()->count(), 0);
        // The view takes the next drag.
        drag(press, press + QPoint(20, 0));
        QVERIFY(!(geometry() == before));
        QCOMPARE(m_window->undoStack()->count(), 1);
    }

    void everyDragIsOneUndoStep() {
        openWindow("bicubic");
        const NurbsSurface start = geometry();
        const auto [ref, press] = pickablePoint();
        drag(press, press + QPoint(25, -10));
        const NurbsSurface afterFirst = geometry();
        QVERIFY(!(afterFirst == start));
        const auto [ref2, press2] = pickablePoint(1);
        QVERIFY(ref2 != ref);
        drag(press2, press2 + QPoint(-15, 30));
        QUndoStack* stack = m_window->undoStack();
        QCOMPARE(stack->count(), 2);
        QCOMPARE(stack->undoText(), QStringLiteral("Move control point"));
        stack->undo();
        QVERIFY(geometry() == afterFirst);
        stack->undo();
        QVERIFY(geometry() == start);
    }

    void weightAndSurfaceDragsCancelAndCommit() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        const auto [ref, press] = pickablePoint();
        const NurbsSurface before = geometry();
        const Qt::KeyboardModifiers weight = Qt::ControlModifier | Qt::ShiftModifier;
        QTest::mousePress(vp, Qt::LeftButton, weight, press);
        QTest::mouseMove(vp, press - QPoint(0, 100)); // doubles the weight
        const int index = before.index(ref.i, ref.j);
        QCOMPARE(geometry().weights[size_t(index)], 2.0 * before.weights[size_t(index)]);
        QTest::keyClick(vp, Qt::Key_Escape);
        QVERIFY(geometry() == before);
        drag(press, press - QPoint(0, 100), weight);
        QCOMPARE(m_window->undoStack()->count(), 1);
        QVERIFY(m_window->undoStack()->undoText().startsWith(QStringLiteral("Set weight")));
        m_window->undoStack()->undo();
        QVERIFY(geometry() == before);

        // Ctrl + drag moves the whole surface; Esc puts it back.
        QTest::mousePress(vp, Qt::LeftButton, Qt::ControlModifier, press);
        QVERIFY(vp->isDragging());
        QTest::mouseMove(vp, press + QPoint(40, 0), 0);
        QVERIFY(geometry().points.front() != before.points.front());
        QVERIFY(geometry().points.back() != before.points.back());
        QTest::keyClick(vp, Qt::Key_Escape);
        QVERIFY(geometry() == before);
        drag(press, press + QPoint(40, 0), Qt::ControlModifier);
        QCOMPARE(m_window->undoStack()->count(), 1); // replaced the undone weight step
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Move surface"));
    }

    void refusedStepShowsItsReasonInTheStatusBar() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        QUndoStack* stack = m_window->undoStack();
        const SurfaceId id = m_window->document()->scene().surfaces.front().id;
        QVERIFY(
            pushCommand(stack, InsertKnot::create(m_window->document(), id, Direction::U, 0.3)));
        const auto [ref, press] = pickablePoint();
        QVERIFY(ref.surface.isValid());
        QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, press);
        QTest::mouseMove(vp, press + QPoint(10, 10));
        QVERIFY(!m_window->statusBar()->currentMessage().startsWith(QStringLiteral("Drag step")));
        // Ctrl+Z under the drag takes the knot out again: the net the drag holds is gone.
        stack->undo();
        const NurbsSurface undone = geometry();
        QTest::mouseMove(vp, press + QPoint(20, 20));
        const QString shown = m_window->statusBar()->currentMessage();
        QVERIFY2(shown.startsWith(QStringLiteral("Drag step refused: ")), qPrintable(shown));
        QVERIFY2(shown.contains(QStringLiteral("changed under the drag")), qPrintable(shown));
        QVERIFY(geometry() == undone); // the refused step changed nothing
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, press + QPoint(20, 20));
        QVERIFY(geometry() == undone);
        QCOMPARE(stack->index(), 0); // the release recorded nothing on top
        QVERIFY(!vp->isDragging());
    }

    void trimDragInTheUvPanelFollowsTheSameProtocol() {
        openWindow("trimmed_plate");
        UvPanel* uv = m_window->uvPanel();
        QUndoStack* stack = m_window->undoStack();
        auto trims = [this] {
            return m_window->document()->scene().surfaces[0].trims;
        };
        const Surface& s = m_window->document()->scene().surfaces[0];
        const SurfaceId id = s.id;
        const TrimLoop star = s.trims.back();
        const std::vector<TrimLoop> before = trims();
        const QPoint press = uv->toWidget(star.curves[0].points.front()).toPoint();
        QVERIFY(uv->trimPointAt(press));
        // Esc restores.
        QTest::mousePress(uv, Qt::LeftButton, Qt::NoModifier, press);
        QTest::mouseMove(uv, press + QPoint(-20, 10));
        QVERIFY(trims() != before);
        QTest::keyClick(uv, Qt::Key_Escape);
        QVERIFY(trims() == before);
        QTest::mouseRelease(uv, Qt::LeftButton, Qt::NoModifier, press + QPoint(-20, 10));
        QVERIFY(trims() == before);
        QCOMPARE(stack->count(), 0);
        // A drag is one step.
        QTest::mousePress(uv, Qt::LeftButton, Qt::NoModifier, press);
        QTest::mouseMove(uv, press + QPoint(-5, 5));
        QTest::mouseMove(uv, press + QPoint(-10, 10));
        QTest::mouseRelease(uv, Qt::LeftButton, Qt::NoModifier, press + QPoint(-10, 10));
        QCOMPARE(stack->count(), 1);
        QCOMPARE(stack->undoText(), QStringLiteral("Move 2 trim points")); // first = last
        stack->undo();
        QVERIFY(trims() == before);
        // The loop removed under a drag: the next step is refused, and says why.
        QTest::mousePress(uv, Qt::LeftButton, Qt::NoModifier, press);
        QTest::mouseMove(uv, press + QPoint(-5, 5));
        QVERIFY(pushCommand(stack, RemoveTrimLoop::create(m_window->document(), id, star.id)));
        const int steps = stack->count();
        QTest::mouseMove(uv, press + QPoint(-10, 10));
        const QString shown = m_window->statusBar()->currentMessage();
        QVERIFY2(shown.startsWith(QStringLiteral("Drag step refused: no trim point")),
                 qPrintable(shown));
        QTest::mouseRelease(uv, Qt::LeftButton, Qt::NoModifier, press + QPoint(-10, 10));
        QCOMPARE(stack->count(), steps);
    }

    void installedToolSeesClicksHoverKeysAndDraws() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        RecordingTool tool;
        vp->setTool(&tool);
        const auto [ref, press] = pickablePoint();
        const NurbsSurface before = geometry();
        // Sent to the view itself: QTest::mouseMove moves the X cursor, whose motion goes to
        // whichever window is on top there (another test's, when tests share the display).
        const QPoint at = press + QPoint(3, 3);
        QMouseEvent hover(QEvent::MouseMove, at, vp->mapToGlobal(at), Qt::NoButton, Qt::NoButton,
                          Qt::NoModifier);
        QCoreApplication::sendEvent(vp, &hover);
        QVERIFY(tool.hovers > 0);
        // A plain press on a control point is the tool's: no drag, no pick.
        QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, press);
        QCOMPARE(tool.presses, 1);
        QVERIFY(!vp->isDragging());
        QTest::mouseMove(vp, press + QPoint(30, 30));
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, press + QPoint(30, 30));
        QVERIFY(geometry() == before);
        QVERIFY(m_window->selection()->controlPoints().empty());
        // Ctrl + drag still reaches the registered tools under it.
        drag(press, press + QPoint(30, 0), Qt::ControlModifier);
        QCOMPARE(tool.presses, 1);
        QCOMPARE(m_window->undoStack()->count(), 1);
        QTest::keyClick(vp, Qt::Key_Escape);
        QCOMPARE(tool.keys, 1);
        vp->grabFramebuffer();
        QVERIFY(tool.paints > 0);
        vp->setTool(nullptr);
        QVERIFY(!vp->tool());
    }
};

QTEST_MAIN(TestTools)
#include "tst_tools.moc"
