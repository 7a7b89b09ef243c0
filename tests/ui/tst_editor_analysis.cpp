// Editor GUI test of the analysis colour maps through the real main window under Xvfb: the
// View > Analysis actions, the Colour Range dialog (automatic percentile range, a user range,
// linear / symmetric / log scales) and the legend drawn in the viewport. Each state is checked
// in the frame report (the range the shader used), in the legend's pixels and in the surface's
// pixels against the colour the kernel's curvature at the picked (u, v) must give.
#include "editor_test_util.h"
#include "model/nurbs/nurbs_curvature.h"
#include "render/offscreen_renderer.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QPushButton>
#include <QSettings>
#include <QTimer>
#include <glm/glm.hpp>

using namespace kw;
using namespace kwtest;

namespace {

/// What the Colour Range dialog is told: automatic, or LOW..HIGH; scale index 0 = mode default,
/// 1 + ColourScale otherwise.
struct RangeAnswer {
    bool automatic = true;
    double low = 0.0, high = 0.0;
    int scaleIndex = 0;
};

/// The legend's rectangle in the viewport (Viewport::drawLegend), with its dark backing.
QRect legendArea(const QWidget* vp) {
    return QRect(vp->width() - 150, 16, 130, std::min(260, vp->height() - 32))
        .adjusted(-6, -4, 6, 4);
}

} // namespace

class TestEditorAnalysis : public QObject {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
        qputenv("XDG_CONFIG_HOME", QByteArrayLiteral(KW_TEST_OUTPUT_DIR "/analysis-config"));
    }

private:
    std::unique_ptr<MainWindow> m_window;
    DialogScript m_script;

    Viewport* vp() const { return m_window->viewport(); }

    QAction* action(const char* name) const {
        return m_window->findChild<QAction*>(QString::fromLatin1(name));
    }

    /// Triggers View > Analysis > Colour Range… and answers the modal dialog.
    bool answerRangeDialog(const RangeAnswer& answer) {
        bool seen = false;
        QTimer::singleShot(0, this, [&] {
            auto* dialog = qobject_cast<QDialog*>(QApplication::activeModalWidget());
            if (!dialog || dialog->objectName() != QLatin1String("colourRangeDialog"))
                return;
            seen = true;
            dialog->findChild<QCheckBox*>(QStringLiteral("rangeAutomatic"))
                ->setChecked(answer.automatic);
            if (!answer.automatic) {
                dialog->findChild<QDoubleSpinBox*>(QStringLiteral("rangeLow"))
                    ->setValue(answer.low);
                dialog->findChild<QDoubleSpinBox*>(QStringLiteral("rangeHigh"))
                    ->setValue(answer.high);
            }
            dialog->findChild<QComboBox*>(QStringLiteral("rangeScale"))
                ->setCurrentIndex(answer.scaleIndex);
            dialog->accept();
        });
        action("actionAnalysisRange")->trigger();
        return seen;
    }

    /// Triggers View > Analysis > Draft Settings… and answers it with `pull` and `angle`; a
    /// zero pull must be refused with a reason, after which the dialog is cancelled.
    /// Returns false when the dialog did not show or behaved otherwise.
    bool answerDraftDialog(const glm::dvec3& pull, double angle) {
        bool ok = false;
        QTimer::singleShot(0, this, [&] {
            auto* dialog = qobject_cast<QDialog*>(QApplication::activeModalWidget());
            if (!dialog || dialog->objectName() != QLatin1String("draftSettingsDialog"))
                return;
            const auto set = [&](const char* name, double v) {
                auto* s = dialog->findChild<QDoubleSpinBox*>(QString::fromLatin1(name));
                if (s)
                    s->setValue(v);
                return s != nullptr;
            };
            if (!set("draftPullX", pull.x) || !set("draftPullY", pull.y) ||
                !set("draftPullZ", pull.z) || !set("draftAngle", angle))
                return;
            auto* buttons = dialog->findChild<QDialogButtonBox*>();
            buttons->button(QDialogButtonBox::Ok)->click();
            if (glm::length(pull) > 0.0) {
                ok = dialog->result() == QDialog::Accepted;
                return;
            }
            // Refused: still open, the reason shown.
            auto* why = dialog->findChild<QLabel*>(QStringLiteral("draftError"));
            ok = dialog->isVisible() && why && !why->text().isEmpty();
            dialog->reject();
        });
        action("actionDraftSettings")->trigger();
        return ok;
    }

    /// The draft colour of each surface pixel on a grid against the kernel's normal at the
    /// picked (u, v) (analysis.glsl: kw::draftColours() by the angle to the pull direction,
    /// times the headlight factor), within 3 of 255; pixels within 0.5 degrees of a threshold
    /// are skipped. Returns the number checked, -1 on a mismatch.
    int checkDraftPixels(const QImage& frame, const glm::dvec3& pull, double angle) {
        const QRect legend(vp()->width() - 196, 12, 182, 108);
        const glm::dvec3 eye = vp()->cameraController().camera().eye;
        const DraftColours& colours = draftColours();
        int checked = 0;
        for (int y = 40; y < vp()->height() - 40; y += 23)
            for (int x = 40; x < vp()->width() - 40; x += 23) {
                if (legend.contains(x, y))
                    continue;
                const auto hit = vp()->pickSurface(QPointF(x + 0.5, y + 0.5));
                const Surface* s = hit ? m_window->document()->surface(hit->surface) : nullptr;
                if (!s)
                    continue;
                const SurfaceCurvature c = surfaceCurvature(s->geometry, hit->uv.x, hit->uv.y);
                const double a = glm::degrees(
                    std::asin(std::clamp(glm::dot(c.normal, glm::normalize(pull)), -1.0, 1.0)));
                if (std::abs(std::abs(a) - angle) < 0.5)
                    continue;
                const glm::vec3 base =
                    a >= angle ? colours.draft
                               : (a <= -angle ? colours.undercut : colours.insufficient);
                const double light =
                    0.35 + 0.65 * std::abs(glm::dot(c.normal, glm::normalize(eye - c.point)));
                const QRgb got = frame.pixel(x, y);
                const int rgb[3] = {qRed(got), qGreen(got), qBlue(got)};
                for (int k = 0; k < 3; ++k) {
                    const int want =
                        int(std::lround(std::clamp(base[k] * light, 0.0, 1.0) * 255.0));
                    if (std::abs(rgb[k] - want) > 3) {
                        qWarning("pixel (%d, %d): channel %d is %d, expected %d (draft %g deg)", x,
                                 y, k, rgb[k], want, a);
                        return -1;
                    }
                }
                ++checked;
            }
        return checked;
    }

    /// Checks the surface's pixels at a grid of view positions: each must have the colour of
    /// analysis.glsl for the kernel's mean curvature at the picked (u, v) under `range` and
    /// `scale` (ramp colour times the headlight factor), within 3 of 255 per channel.
    /// Returns the number of pixels checked.
    int checkSurfacePixels(const QImage& frame, const ValueRange& range, ColourScale scale) {
        const QRect legend = legendArea(vp());
        const glm::dvec3 eye = vp()->cameraController().camera().eye;
        int checked = 0;
        for (int y = 40; y < vp()->height() - 40; y += 23)
            for (int x = 40; x < vp()->width() - 40; x += 23) {
                if (legend.adjusted(-4, -4, 4, 4).contains(x, y))
                    continue;
                const auto hit = vp()->pickSurface(QPointF(x + 0.5, y + 0.5));
                if (!hit)
                    continue;
                const Surface* s = m_window->document()->surface(hit->surface);
                if (!s)
                    continue;
                const SurfaceCurvature c = surfaceCurvature(s->geometry, hit->uv.x, hit->uv.y);
                const glm::dvec3 v = glm::normalize(eye - c.point);
                const double light = 0.35 + 0.65 * std::abs(glm::dot(c.normal, v));
                const glm::vec3 ramp = rampColour(colourScalePosition(c.mean, range, scale));
                const QRgb got = frame.pixel(x, y);
                const int rgb[3] = {qRed(got), qGreen(got), qBlue(got)};
                // The pick and the frame evaluate the same pixel centre; 3 levels allow for float
                // against the kernel's double and 8-bit rounding.
                for (int k = 0; k < 3; ++k) {
                    const int want =
                        int(std::lround(std::clamp(ramp[k] * light, 0.0, 1.0) * 255.0));
                    if (std::abs(rgb[k] - want) > 3) {
                        qWarning("pixel (%d, %d): channel %d is %d, expected %d (H %g, t %g)", x, y,
                                 k, rgb[k], want, c.mean,
                                 colourScalePosition(c.mean, range, scale));
                        return -1;
                    }
                }
                ++checked;
            }
        return checked;
    }

private Q_SLOTS:
    void initTestCase() {
        QCoreApplication::setOrganizationName(QStringLiteral("KnotworkTest"));
        QSettings().clear();
        m_window = std::make_unique<MainWindow>();
        scriptDialogs(*m_window, m_script);
        // A large view without the docks, the control net and the selection outline, so
        // the legend and the sampled surface pixels do not overlap anything.
        m_window->resize(1200, 900);
        for (QDockWidget* dock : m_window->findChildren<QDockWidget*>())
            dock->hide();
        m_window->show();
        QVERIFY(QTest::qWaitForWindowExposed(m_window.get()));
        QVERIFY(m_window->openFile(samplePath("bicubic")));
        QAction* net = m_window->findChild<QAction*>(QStringLiteral("actionControlNet"));
        QVERIFY(net);
        if (net->isChecked())
            net->trigger();
        m_window->selection()->clear(); // no selection outline over the surface
        // Each checked pixel is compared with the kernel at the pixel's centre, which the
        // anti-aliased frame (Preferences' default) mixes with the neighbouring triangle's
        // fragment where a base-polygon edge crosses the pixel.
        vp()->setSamples(1);
        QTest::qWait(20);
        QTest::qWait(50);
        QVERIFY2(vp()->glError(), qPrintable(vp()->glError().message()));
    }
    void cleanupTestCase() {
        m_window->close();
        m_window.reset();
    }

    void legendAndRangeDialogDriveThePixels();
    void draftLegendAndSettings();
};

void TestEditorAnalysis::legendAndRangeDialogDriveThePixels() {
    // Phong: no legend.
    const QImage phong = vp()->grabFramebuffer();
    QAction* mean = action("actionAnalysisMean");
    QVERIFY(mean && action("actionAnalysisRange"));
    mean->trigger();
    QCOMPARE(vp()->renderOptions().analysis.mode, AnalysisMode::Mean);

    // 1. Automatic range: the frame used the kernel's area-weighted 10th-90th percentile range,
    // symmetric
    //    scale (the mean curvature's default); the legend appeared; the pixels follow.
    const QImage autoFrame = vp()->grabFramebuffer();
    autoFrame.save(QStringLiteral(KW_TEST_OUTPUT_DIR "/editor_analysis_auto.png"));
    const ValueRange autoExpected = autoRange(m_window->document()->scene(), AnalysisMode::Mean);
    const ValueRange autoUsed = vp()->lastFrameReport().analysisRange;
    QCOMPARE(autoUsed.low, autoExpected.low);
    QCOMPARE(autoUsed.high, autoExpected.high);
    QVERIFY(autoUsed.high > autoUsed.low);
    const QRect legend = legendArea(vp());
    QVERIFY2(differingPixels(phong.copy(legend), autoFrame.copy(legend)) > 500,
             "no legend drawn over the curvature map");
    // The legend's bar is the shader's ramp: top = high end (t = 1), bottom = low (t = 0).
    const QRect bar(vp()->width() - 150, 16 + 34, 18, std::min(260, vp()->height() - 32) - 34);
    for (double t : {0.1, 0.3, 0.5, 0.7, 0.9}) {
        const int y = bar.top() + int((1.0 - t) * bar.height());
        const glm::vec3 want = rampColour(1.0 - (y - bar.top() + 0.5) / bar.height());
        const QRgb got = autoFrame.pixel(bar.left() + 9, y);
        QVERIFY2(std::abs(qRed(got) - int(want.x * 255.0f + 0.5f)) <= 2 &&
                     std::abs(qGreen(got) - int(want.y * 255.0f + 0.5f)) <= 2 &&
                     std::abs(qBlue(got) - int(want.z * 255.0f + 0.5f)) <= 2,
                 qPrintable(QStringLiteral("legend bar at t %1 is %2, expected the ramp")
                                .arg(t)
                                .arg(QColor(got).name())));
    }
    int n = checkSurfacePixels(autoFrame, autoUsed, ColourScale::Symmetric);
    QVERIFY2(n >= 100, qPrintable(QStringLiteral("%1 surface pixels matched").arg(n)));
    qInfo("automatic range [%g, %g]: %d surface pixels match the kernel's colours", autoUsed.low,
          autoUsed.high, n);

    // 2. A user range, linear: the frame uses it exactly, the legend's labels change (its bar
    //    does not), and the surface is recoloured as the new range says.
    // (Values the dialog's 6-decimal spin boxes hold exactly; the bicubic's H spans about
    // -1..0.5, so the new range recolours most of it.)
    const ValueRange user{-0.25, 1.0};
    QVERIFY(answerRangeDialog({false, user.low, user.high, 1 + int(ColourScale::Linear)}));
    QVERIFY(vp()->renderOptions().analysis.range.has_value());
    QCOMPARE(vp()->renderOptions().analysis.scale, std::optional(ColourScale::Linear));
    const QImage userFrame = vp()->grabFramebuffer();
    QCOMPARE(vp()->lastFrameReport().analysisRange.low, user.low);
    QCOMPARE(vp()->lastFrameReport().analysisRange.high, user.high);
    const int legendChanged = differingPixels(autoFrame.copy(legend), userFrame.copy(legend));
    QVERIFY2(legendChanged > 50, "the legend did not change with the range");
    QCOMPARE(differingPixels(autoFrame.copy(bar), userFrame.copy(bar)), 0);
    n = checkSurfacePixels(userFrame, user, ColourScale::Linear);
    QVERIFY2(n >= 100, qPrintable(QStringLiteral("%1 surface pixels matched").arg(n)));
    const int recoloured = differingPixels(autoFrame, userFrame);
    qInfo("user range [%g, %g] linear: %d legend pixels and %d frame pixels changed; %d surface "
          "pixels match",
          user.low, user.high, legendChanged, recoloured, n);

    // 3. Same range, log scale: labels and pixels change again; the frame is deterministic.
    QVERIFY(answerRangeDialog({false, user.low, user.high, 1 + int(ColourScale::Log)}));
    QCOMPARE(vp()->renderOptions().analysis.scale, std::optional(ColourScale::Log));
    const QImage logFrame = vp()->grabFramebuffer();
    QCOMPARE(differingPixels(logFrame, vp()->grabFramebuffer()), 0);
    QVERIFY(differingPixels(userFrame.copy(legend), logFrame.copy(legend)) > 50);
    QVERIFY(differingPixels(userFrame, logFrame) > 1000);
    n = checkSurfacePixels(logFrame, user, ColourScale::Log);
    QVERIFY2(n >= 100, qPrintable(QStringLiteral("%1 surface pixels matched").arg(n)));

    // 4. Symmetric scale: the same as the log frame nowhere near zero; pixels still match.
    QVERIFY(answerRangeDialog({false, user.low, user.high, 1 + int(ColourScale::Symmetric)}));
    const QImage symFrame = vp()->grabFramebuffer();
    QVERIFY(differingPixels(logFrame.copy(legend), symFrame.copy(legend)) > 50);
    n = checkSurfacePixels(symFrame, user, ColourScale::Symmetric);
    QVERIFY2(n >= 100, qPrintable(QStringLiteral("%1 surface pixels matched").arg(n)));

    // 5. Back to automatic and the mode's default scale: the first frame, pixel for pixel.
    QVERIFY(answerRangeDialog({true, 0.0, 0.0, 0}));
    QVERIFY(!vp()->renderOptions().analysis.range.has_value());
    QVERIFY(!vp()->renderOptions().analysis.scale.has_value());
    QCOMPARE(differingPixels(autoFrame, vp()->grabFramebuffer()), 0);

    // Phong again: the legend goes away.
    action("actionAnalysisPhong")->trigger();
    QCOMPARE(differingPixels(phong, vp()->grabFramebuffer()), 0);
}

// Draft: its legend shows the shader's three colours and the settings; View > Analysis > Draft
// Settings… sets the pull direction and angle (a zero pull refused), the pixels follow, and
// Save keeps them with the project's display settings while another project shows the defaults.
void TestEditorAnalysis::draftLegendAndSettings() {
    const QImage phong = vp()->grabFramebuffer();
    QAction* draft = action("actionAnalysisDraft");
    QVERIFY(draft && action("actionDraftSettings"));
    draft->trigger();
    QCOMPARE(vp()->renderOptions().analysis.pullDirection, glm::dvec3(0.0, 0.0, 1.0));
    const QImage before = vp()->grabFramebuffer();
    // The legend (Viewport::drawLegend): a swatch per colour, 22 px apart.
    const QRect legend(vp()->width() - 196, 12, 182, 108);
    QVERIFY2(differingPixels(phong.copy(legend), before.copy(legend)) > 500, "no draft legend");
    const DraftColours& colours = draftColours();
    const glm::vec3 swatches[] = {colours.draft, colours.insufficient, colours.undercut};
    for (int k = 0; k < 3; ++k) {
        const QRgb got = before.pixel(vp()->width() - 190 + 9, 16 + 38 + 8 + 22 * k);
        const glm::vec3 want = swatches[k];
        QVERIFY2(
            std::abs(qRed(got) - int(want.x * 255.0f + 0.5f)) <= 2 &&
                std::abs(qGreen(got) - int(want.y * 255.0f + 0.5f)) <= 2 &&
                std::abs(qBlue(got) - int(want.z * 255.0f + 0.5f)) <= 2,
            qPrintable(QStringLiteral("legend swatch %1 is %2").arg(k).arg(QColor(got).name())));
    }
    int n = checkDraftPixels(before, {0.0, 0.0, 1.0}, 3.0);
    QVERIFY2(n >= 100, qPrintable(QStringLiteral("%1 draft pixels matched").arg(n)));

    // A zero pull is refused; a pull along x at 10 degrees recolours the surface and the legend.
    QVERIFY(answerDraftDialog(glm::dvec3(0.0), 5.0));
    QCOMPARE(vp()->renderOptions().analysis.pullDirection, glm::dvec3(0.0, 0.0, 1.0));
    const glm::dvec3 pull(1.0, 0.0, 0.0);
    QVERIFY(answerDraftDialog(pull, 10.0));
    QCOMPARE(vp()->renderOptions().analysis.pullDirection, pull);
    QCOMPARE(vp()->renderOptions().analysis.draftAngleDegrees, 10.0);
    const QImage after = vp()->grabFramebuffer();
    QVERIFY(differingPixels(before.copy(legend), after.copy(legend)) > 20);
    QVERIFY(differingPixels(before, after) > 1000);
    n = checkDraftPixels(after, pull, 10.0);
    QVERIFY2(n >= 100, qPrintable(QStringLiteral("%1 draft pixels matched").arg(n)));
    qInfo("draft along x at 10 degrees: %d surface pixels match the kernel's classes", n);

    // Saved with the project; another project shows the defaults; the saved one comes back.
    const QString path = QStringLiteral(KW_TEST_OUTPUT_DIR "/editor_draft.knot");
    QVERIFY(m_window->saveFile(path));
    QFile file(path);
    QVERIFY(file.open(QIODevice::ReadOnly));
    const QJsonObject display = QJsonDocument::fromJson(file.readAll())["display"].toObject();
    QCOMPARE(display["draftAngle"].toDouble(), 10.0);
    QCOMPARE(display["pullDirection"].toArray(), QJsonArray({1.0, 0.0, 0.0}));
    QVERIFY(m_window->openFile(samplePath("sphere")));
    QCOMPARE(vp()->renderOptions().analysis.pullDirection, glm::dvec3(0.0, 0.0, 1.0));
    QCOMPARE(vp()->renderOptions().analysis.draftAngleDegrees, 3.0);
    QVERIFY(m_window->openFile(path));
    QCOMPARE(vp()->renderOptions().analysis.pullDirection, pull);
    QCOMPARE(vp()->renderOptions().analysis.draftAngleDegrees, 10.0);
    action("actionAnalysisPhong")->trigger();
}

QTEST_MAIN(TestEditorAnalysis)
#include "tst_editor_analysis.moc"
