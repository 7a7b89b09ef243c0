// The editor's View › Section…: a plane added, moved and flipped in the dialog cuts the view at
// once, pushes no undo step (view state), is saved with the project and comes back with it; a
// zero normal says so and cuts nothing; a project without sections opens uncut.
#include "editor_test_util.h"
#include "model/io/knotfile.h"
#include "render/offscreen_renderer.h"
#include "ui/sectiondialog.h"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QMouseEvent>
#include <QSurfaceFormat>
#include <QTemporaryDir>

using namespace kw;

namespace {

/// Pixels that differ from the top left one (the background).
int covered(const QImage& image) {
    const QRgb background = image.pixel(0, 0);
    int n = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            n += image.pixel(x, y) != background;
    return n;
}

} // namespace

class TestEditorSections : public kwtest::EditorTestBase {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
    }

    template <typename T> T* child(const QString& name) const {
        auto* d = m_window->findChild<SectionDialog*>(QStringLiteral("sectionDialog"));
        return d ? d->findChild<T*>(name) : nullptr;
    }

private Q_SLOTS:
    void cleanup() { closeWindow(); }

    // "section plane (add, move, flip)", undo-free.
    void sectionPlaneAddMoveFlip() {
        openWindow("sphere");
        Viewport* view = m_window->viewport();
        // What the view shows without the surface (its control net and outline: overlays,
        // which no plane cuts), for the empty view below.
        QAction* hide = act("actionHide");
        QVERIFY(hide);
        hide->trigger();
        QVERIFY(scene().surfaces.front().hidden);
        const int overlays = covered(view->grabFramebuffer());
        m_window->undoStack()->undo();
        QVERIFY(!scene().surfaces.front().hidden);
        const int undoSteps = m_window->undoStack()->count();
        const int undoIndex = m_window->undoStack()->index();
        const int whole = covered(view->grabFramebuffer());
        QVERIFY(whole > 1000);
        QAction* section = act("actionSection");
        QVERIFY(section);
        section->trigger();
        auto* enabled = child<QCheckBox>(QStringLiteral("sectionEnabled0"));
        QVERIFY(enabled);

        // Add: through the model's middle, normal +x: half the sphere goes, a cap shows.
        enabled->setChecked(true);
        QCOMPARE(int(view->sections().size()), 1);
        glm::dvec3 lo, hi;
        sceneBounds(scene(), lo, hi);
        const glm::dvec3 mid = 0.5 * (lo + hi);
        QVERIFY(glm::length(view->sections()[0].position - mid) < 1e-9);
        const int half = covered(view->grabFramebuffer());
        QVERIFY2(half < whole && half > whole / 5,
                 qPrintable(QStringLiteral("%1 of %2").arg(half).arg(whole)));

        // Move: past the sphere's far side along +x nothing is removed.
        auto* x = child<QDoubleSpinBox>(QStringLiteral("sectionPosition0X"));
        QVERIFY(x);
        x->setValue(hi.x + 1.0);
        QCOMPARE(view->sections()[0].position.x, hi.x + 1.0);
        // The same pixels, up to the outline's (the view refines its anti-aliasing by frames).
        const int moved = covered(view->grabFramebuffer());
        QVERIFY2(std::abs(moved - whole) <= whole / 100,
                 qPrintable(QStringLiteral("%1 of %2").arg(moved).arg(whole)));

        // Flip: now everything is on the removed side: an empty view (but for the overlays),
        // not a failure.
        auto* flip = child<QCheckBox>(QStringLiteral("sectionFlip0"));
        QVERIFY(flip);
        flip->setChecked(true);
        QVERIFY(view->sections()[0].flip);
        const int empty = covered(view->grabFramebuffer());
        QVERIFY2(std::abs(empty - overlays) <= whole / 100,
                 qPrintable(QStringLiteral("%1, overlays %2").arg(empty).arg(overlays)));
        QVERIFY(view->glError());

        // A zero normal: said in the dialog, no plane.
        x->setValue(mid.x);
        for (const char* axis : {"X", "Y", "Z"})
            child<QDoubleSpinBox>(QStringLiteral("sectionNormal0%1").arg(QLatin1String(axis)))
                ->setValue(0.0);
        QVERIFY(view->sections().empty());
        QVERIFY(child<QLabel>(QStringLiteral("sectionStatus0"))
                    ->text()
                    .contains(QStringLiteral("zero length")));
        const int restored = covered(view->grabFramebuffer());
        QVERIFY2(std::abs(restored - whole) <= whole / 100,
                 qPrintable(QStringLiteral("%1 of %2").arg(restored).arg(whole)));
        child<QDoubleSpinBox>(QStringLiteral("sectionNormal0Z"))->setValue(1.0);
        QCOMPARE(int(view->sections().size()), 1);

        // View state: no undo step, and saved with the project.
        QCOMPARE(m_window->undoStack()->count(), undoSteps);
        QCOMPARE(m_window->undoStack()->index(), undoIndex);
        QTemporaryDir dir;
        const QString path = dir.filePath(QStringLiteral("cut.knot"));
        QVERIFY(m_window->saveFile(path));
        QString error;
        const auto saved = readKnotFile(path);
        QVERIFY2(saved, qPrintable(saved.message()));
        QCOMPARE(int(saved->display.sections.size()), 1);
        QCOMPARE(saved->display.sections[0], view->sections()[0]);

        // Another project: uncut; this one again: cut, and the dialog shows it.
        QVERIFY(m_window->openFile(kwtest::samplePath("torus")));
        QVERIFY(view->sections().empty());
        QVERIFY(!enabled->isChecked());
        QVERIFY(m_window->openFile(path));
        QCOMPARE(int(view->sections().size()), 1);
        QVERIFY(enabled->isChecked());
        QVERIFY(child<QCheckBox>(QStringLiteral("sectionFlip0"))->isChecked());
    }

    // "section plane (move)" by its handle in the view: a left drag on the arrow moves the
    // plane along its normal with the cursor, live, the dialog's fields follow, no undo step;
    // Esc during a drag puts it back.
    void sectionPlaneDragHandle() {
        openWindow("sphere");
        Viewport* view = m_window->viewport();
        act("actionSection")->trigger();
        child<QCheckBox>(QStringLiteral("sectionEnabled0"))->setChecked(true);
        QCOMPARE(int(view->sections().size()), 1);
        const SectionPlane before = view->sections()[0];
        const int undoSteps = m_window->undoStack()->count();
        // The handle starts at the plane's point and runs along the normal's image.
        const ViewProjection vp = view->viewProjection();
        const QPointF base = *vp.project(before.position);
        const QPointF ahead = *vp.project(before.position + 0.1 * before.normal);
        const QPointF dir = (ahead - base) / std::hypot((ahead - base).x(), (ahead - base).y());
        const QPoint press = base.toPoint();
        const QPoint to = (base + 40.0 * dir).toPoint();
        const auto send = [view](QEvent::Type type, QPoint at, Qt::MouseButtons buttons) {
            QMouseEvent e(type, at, view->mapToGlobal(at), Qt::LeftButton, buttons, Qt::NoModifier);
            QCoreApplication::sendEvent(view, &e);
        };
        const std::int64_t frames = view->framesDrawn();
        send(QEvent::MouseButtonPress, press, Qt::LeftButton);
        for (int k = 1; k <= 4; ++k) {
            send(QEvent::MouseMove, press + (to - press) * k / 4, Qt::LeftButton);
            QTest::qWait(20);
        }
        const SectionPlane during = view->sections()[0];
        QVERIFY(view->framesDrawn() > frames); // the cut follows the drag
        send(QEvent::MouseButtonRelease, to, Qt::NoButton);
        const SectionPlane after = view->sections()[0];
        QCOMPARE(after.position, during.position);
        // Along the normal only, forward, and under the cursor.
        QCOMPARE(after.normal, before.normal);
        QCOMPARE(after.flip, before.flip);
        const glm::dvec3 n = glm::normalize(before.normal);
        const glm::dvec3 shift = after.position - before.position;
        QVERIFY2(glm::dot(shift, n) > 0.05, qPrintable(QString::number(glm::dot(shift, n))));
        QVERIFY(glm::length(shift - glm::dot(shift, n) * n) < 1e-9);
        const QPointF landed = *view->viewProjection().project(after.position);
        QVERIFY2(std::hypot(landed.x() - to.x(), landed.y() - to.y()) < 1.0,
                 qPrintable(QStringLiteral("%1, %2 for %3, %4")
                                .arg(landed.x())
                                .arg(landed.y())
                                .arg(to.x())
                                .arg(to.y())));
        auto* x = child<QDoubleSpinBox>(QStringLiteral("sectionPosition0X"));
        QVERIFY(std::abs(x->value() - after.position.x) <= std::pow(10.0, -x->decimals()));
        QCOMPARE(m_window->undoStack()->count(), undoSteps);
        // Esc during a drag: the plane goes back to where the drag started.
        const QPoint again = to;
        send(QEvent::MouseButtonPress, again, Qt::LeftButton);
        send(QEvent::MouseMove, again + QPoint(int(-30 * dir.x()), int(-30 * dir.y())),
             Qt::LeftButton);
        QVERIFY(view->sections()[0].position != after.position);
        QTest::keyClick(view, Qt::Key_Escape);
        QCOMPARE(view->sections()[0].position, after.position);
        send(QEvent::MouseButtonRelease, again, Qt::NoButton);
        QCOMPARE(view->sections()[0].position, after.position);
        QCOMPARE(m_window->undoStack()->count(), undoSteps);
    }

    // The selected surface's outline and control net (drawn over the frame) are cut as the
    // surface is: with a plane that removes everything, selecting it adds nothing to the view.
    void overlaysAreCut() {
        openWindow("sphere");
        Viewport* view = m_window->viewport();
        glm::dvec3 lo, hi;
        sceneBounds(scene(), lo, hi);
        view->setSections({SectionPlane{hi + glm::dvec3(1.0), glm::dvec3(-1, -1, -1), false}},
                          true);
        view->selectClickedSurface(scene().surfaces.front().id, false);
        const int selected = covered(view->grabFramebuffer());
        view->selection()->itemSelection()->clearSelection();
        const int none = covered(view->grabFramebuffer());
        QVERIFY2(std::abs(selected - none) <= 20,
                 qPrintable(QStringLiteral("%1 selected, %2 not").arg(selected).arg(none)));
        // Uncut, the selection shows its outline and net.
        view->setSections({}, true);
        const int bare = covered(view->grabFramebuffer());
        view->selectClickedSurface(scene().surfaces.front().id, false);
        QVERIFY(covered(view->grabFramebuffer()) > bare + 200);
    }
};

QTEST_MAIN(TestEditorSections)
#include "tst_editor_sections.moc"
