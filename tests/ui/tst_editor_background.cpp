// The editor's View › Light Background: the view draws the light gradient, Save writes it into
// the project's display settings, opening the project brings it back, and a project without
// it opens on the dark background.
#include "editor_test_util.h"
#include "model/io/knotfile.h"
#include "render/offscreen_renderer.h"

#include <QSurfaceFormat>
#include <QTemporaryDir>

using namespace kw;

class TestEditorBackground : public kwtest::EditorTestBase {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
    }
private Q_SLOTS:
    void cleanup() { closeWindow(); }

    void savedWithTheProject() {
        openWindow("sphere");
        QAction* light = act("actionLightBackground");
        QVERIFY(light && light->isCheckable());
        QVERIFY(!light->isChecked()); // the sample has no background: dark
        QVERIFY(!m_window->viewport()->renderOptions().backgroundTop);
        const QImage dark = m_window->viewport()->grabFramebuffer();
        light->trigger();
        QVERIFY(m_window->viewport()->renderOptions().backgroundTop);
        const QImage lit = m_window->viewport()->grabFramebuffer();
        // The corner is background in both: light grey at the top now.
        QVERIFY2(qGray(lit.pixel(2, 2)) > qGray(dark.pixel(2, 2)) + 100,
                 qPrintable(QStringLiteral("corner %1 vs %2")
                                .arg(qGray(lit.pixel(2, 2)))
                                .arg(qGray(dark.pixel(2, 2)))));

        QTemporaryDir dir;
        const QString path = dir.filePath(QStringLiteral("light.knot"));
        QVERIFY(m_window->saveFile(path));
        QString error;
        const auto saved = readKnotFile(path);
        QVERIFY2(saved, qPrintable(saved.message()));
        QCOMPARE(saved->display.background, QStringLiteral("light"));

        // Another project (none saved): dark; this one again: light.
        QVERIFY(m_window->openFile(kwtest::samplePath("torus")));
        QVERIFY(!act("actionLightBackground")->isChecked());
        QVERIFY(!m_window->viewport()->renderOptions().backgroundTop);
        QVERIFY(m_window->openFile(path));
        QVERIFY(act("actionLightBackground")->isChecked());
        QVERIFY(m_window->viewport()->renderOptions().backgroundTop);
    }
};

QTEST_MAIN(TestEditorBackground)
#include "tst_editor_background.moc"
