// The closed forms of an analytic part's faces through the CAD child process (the hand-over)
// arrive as the in-process import makes them, and `knotwork info --json` names each face's
// importer kind, which Properties' type then prefers.
#include "knotwork_process.h"
#include "model/cad/cadimport.h"
#include "model/cad/occtimport.h"
#include "model/nurbs/analytic_eval.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTest>

using namespace kw;
using Kind = AnalyticForm::Kind;

class TestAnalyticInfo : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void throughTheChildAndInfo();
};

// Through the child process (the hand-over), `knotwork info --json` and a .knot file: the
// forms arrive as the in-process import made them.
void TestAnalyticInfo::throughTheChildAndInfo() {
    const QString path = QStringLiteral(KW_TEST_DATA_DIR "/screw.step");
    Expected<ImportResult> direct = importOcctFile(path, CadFormat::Step);
    QVERIFY2(direct, qPrintable(direct.message()));
    const Expected<ImportResult> child = importFile(path);
    QVERIFY2(child, qPrintable(child.message()));
    QCOMPARE(child->scene.surfaces.size(), direct->scene.surfaces.size());
    for (size_t k = 0; k < child->scene.surfaces.size(); ++k)
        QVERIFY(child->scene.surfaces[k].analytic == direct->scene.surfaces[k].analytic);

    const Run run = knotwork({QStringLiteral("info"), path, QStringLiteral("--json")});
    QVERIFY2(run.code == 0, qPrintable(run.err));
    const QJsonArray faces = QJsonDocument::fromJson(run.out.toUtf8())
                                 .object()
                                 .value(QStringLiteral("surfaces"))
                                 .toArray();
    QCOMPARE(qsizetype(faces.size()), qsizetype(child->scene.surfaces.size()));
    int kept = 0;
    for (qsizetype k = 0; k < faces.size(); ++k) {
        const QJsonObject o = faces[k].toObject();
        const Kind kind = child->scene.surfaces[size_t(k)].analytic.kind;
        QCOMPARE(o.value(QStringLiteral("analytic")).toString(),
                 QString::fromLatin1(analyticKindName(kind)));
        // Properties' type is the importer's kind where there is one.
        kept += kind != Kind::None;
        if (kind != Kind::None)
            QCOMPARE(o.value(QStringLiteral("type")).toString(),
                     QString::fromLatin1(analyticKindName(kind)));
    }
    QCOMPARE(kept, 10); // every face of the screw is analytic
}

QTEST_GUILESS_MAIN(TestAnalyticInfo)
#include "tst_analytic_info.moc"
