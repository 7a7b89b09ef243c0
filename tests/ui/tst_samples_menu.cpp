// File > Open Sample (label gui): the menu lists share/knotwork/samples of the build tree's data
// folder (build/share/knotwork, as an installed prefix's share/knotwork), and a sample opens as
// an unsaved copy with no .knot path, kept out of the recent files.
#include "editor_test_util.h"
#include "model/io/install_layout.h"
#include "render/offscreen_renderer.h"

#include <QAction>
#include <QDir>
#include <QFileInfo>
#include <QMenu>
#include <QSettings>
#include <QSurfaceFormat>

using namespace kw;
using namespace kwtest;

class TestSamplesMenu : public EditorTestBase {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
        qputenv("XDG_CONFIG_HOME", QByteArrayLiteral(KW_TEST_OUTPUT_DIR "/samples-menu-config"));
    }

private Q_SLOTS:
    void initTestCase() {
        QCoreApplication::setOrganizationName(QStringLiteral("KnotworkTest"));
        QSettings().clear();
    }
    void cleanup() { closeWindow(); }

    void listsTheDataFoldersSamples() {
        // Found from this executable (build/tests) by the programs' own rule.
        QVERIFY(!samplesDir().isEmpty());
        QCOMPARE(QFileInfo(samplesDir() + QStringLiteral("/teapot.knot")).canonicalFilePath(),
                 QFileInfo(samplePath("teapot")).canonicalFilePath());
        openWindow();
        auto* menu = m_window->findChild<QMenu*>(QStringLiteral("menuSamples"));
        QVERIFY(menu);
        QStringList names;
        for (QAction* a : menu->actions())
            names << a->text();
        const QStringList knots =
            QDir(QStringLiteral(KW_SAMPLES_DIR))
                .entryList({QStringLiteral("*.knot")}, QDir::Files, QDir::Name);
        QVERIFY(knots.size() >= 5);
        QCOMPARE(names.mid(0, knots.size()), knots); // projects first, by name
        QVERIFY2(names.contains(QStringLiteral("hammer.iges")), qPrintable(names.join(' ')));
    }

    void opensASampleAsAnUnsavedCopy() {
        openWindow();
        QAction* teapot = m_window->findChild<QAction*>(QStringLiteral("actionSample_teapot"));
        QVERIFY(teapot);
        teapot->trigger();
        QCOMPARE(m_window->document()->scene().surfaces.size(), size_t(32));
        QVERIFY(m_window->filePath().isEmpty()); // Save asks where: the samples are read-only
        QCOMPARE(QFileInfo(m_window->importedFrom()).fileName(), QStringLiteral("teapot.knot"));
        QVERIFY(m_window->windowTitle().startsWith(QStringLiteral("teapot")));
        QVERIFY(m_window->recentFiles().isEmpty());
        QVERIFY(m_script.errors.isEmpty());
    }
};

QTEST_MAIN(TestSamplesMenu)
#include "tst_samples_menu.moc"
