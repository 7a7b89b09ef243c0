// The names a STEP file carries reach the document: a face's own name (ADVANCED_FACE's), else
// its product's (PRODUCT's name, numbered within the product), else "Face K" by its order in
// the file; OCCT's writer default product name ("Open CASCADE STEP translator ...") is no name.
#include "model/cad/cadimport.h"

#include <QFile>
#include <QTest>

using namespace kw;

namespace {

QStringList namesOf(const QString& file) {
    const auto result = importFile(QStringLiteral(KW_TEST_DATA_DIR "/") + file);
    if (!result) {
        qWarning("%s", qPrintable(result.message()));
        return {};
    }
    QStringList names;
    for (const Surface& s : result->scene.surfaces)
        names << s.name;
    return names;
}

QByteArray readAll(const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

} // namespace

class TestStepNames : public QObject {
    Q_OBJECT
private Q_SLOTS:
    // A cone and two discs: product "Nozzle cap" (id KW-0042), the top disc named itself.
    void unnamedFacesTakeTheProductName() {
        const QByteArray bytes = readAll(QStringLiteral(KW_TEST_DATA_DIR "/product_named.step"));
        QVERIFY(bytes.contains("PRODUCT('KW-0042','Nozzle cap'"));
        QVERIFY(bytes.contains("ADVANCED_FACE('Top disc'"));
        QCOMPARE(namesOf(QStringLiteral("product_named.step")),
                 QStringList({QStringLiteral("Nozzle cap face 1"), QStringLiteral("Top disc"),
                              QStringLiteral("Nozzle cap face 2")}));
    }

    // The same solid as OCCT wrote it, its product named by the writer's default: no name.
    void writerDefaultProductIsNoName() {
        QVERIFY(readAll(QStringLiteral(KW_TEST_DATA_DIR "/rhino_unset_names.step"))
                    .contains("PRODUCT('Open CASCADE STEP translator"));
        QCOMPARE(namesOf(QStringLiteral("rhino_unset_names.step")),
                 QStringList({QStringLiteral("Face 1"), QStringLiteral("Face 2"),
                              QStringLiteral("Face 3")}));
    }
};

QTEST_MAIN(TestStepNames)
#include "tst_step_names.moc"
