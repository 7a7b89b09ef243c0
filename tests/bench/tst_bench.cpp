// GL test: 'knotwork bench' smoke run (both tables, 2 frames, 64x64), --trim-drag and --no-trims
// on Table 1, and the error exits. Checks the report's shape and the numbers' meaning, never
// timings.
#include "knotwork_process.h"

#include <QDir>
#include <QFile>
#include <QImage>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTest>
#include <cmath>
#include <tuple>

namespace {

QString sample(const char* name) {
    return QStringLiteral(KW_SAMPLES_DIR "/%1.knot").arg(QString::fromLatin1(name));
}

QString outDir() {
    const QString dir = QStringLiteral(KW_TEST_OUTPUT_DIR "/bench");
    QDir(dir).removeRecursively();
    QDir().mkpath(dir);
    return dir;
}

/// Every key in `keys` is present in `o` and is a finite, non-negative number.
void checkNumbers(const QJsonObject& o, const QStringList& keys, const QString& where) {
    for (const QString& k : keys) {
        QVERIFY2(o.contains(k), qPrintable(where + QStringLiteral(": no key ") + k));
        QVERIFY2(o.value(k).isDouble(), qPrintable(where + QStringLiteral(": not a number: ") + k));
        const double v = o.value(k).toDouble();
        QVERIFY2(std::isfinite(v) && v >= 0.0, qPrintable(where + QStringLiteral(": ") + k));
    }
}

void checkQuality(const QJsonObject& o, const QString& where) {
    checkNumbers(
        o.value(QStringLiteral("normalError")).toObject(),
        {QStringLiteral("meanDegrees"), QStringLiteral("maxDegrees"), QStringLiteral("pixels")},
        where + QStringLiteral(" normalError"));
    checkNumbers(o.value(QStringLiteral("silhouetteError")).toObject(),
                 {QStringLiteral("mismatched"), QStringLiteral("silhouettePixels"),
                  QStringLiteral("meanPixels"), QStringLiteral("maxPixels"),
                  QStringLiteral("perSilhouettePixel")},
                 where + QStringLiteral(" silhouetteError"));
}

QJsonObject readJson(const QString& path) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        return {};
    return QJsonDocument::fromJson(f.readAll()).object();
}

QString readText(const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? QString::fromUtf8(f.readAll()) : QString();
}

const QStringList kDragKeys = {QStringLiteral("trimDragMsMedian"),
                               QStringLiteral("maskRedrawCpuMs"), QStringLiteral("maskSide")};
const QString kDragHeader =
    QStringLiteral("| trim drag ms/frame | mask redraw CPU ms | mask side |");

const QStringList kTiming = {QStringLiteral("fps"), QStringLiteral("fpsMin"),
                             QStringLiteral("fpsMax"), QStringLiteral("msMedian"),
                             QStringLiteral("cpuMsPerFrame")};

} // namespace

class TestBench : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void smokeRunWritesWellFormedReport() {
        const QString dir = outDir();
        const QString json = dir + QStringLiteral("/bench.json");
        const QString md = dir + QStringLiteral("/bench.md");
        const Run r = knotwork(
            {QStringLiteral("bench"), sample("bicubic"), QStringLiteral("--smoke"),
             QStringLiteral("--sizes"), QStringLiteral("64"), QStringLiteral("--table2-size"),
             QStringLiteral("64x64"), QStringLiteral("--partitions"), QStringLiteral("4,8"),
             QStringLiteral("--json"), json, QStringLiteral("--markdown"), md});
        QVERIFY2(r.code == 0, qPrintable(r.err));
        QVERIFY(r.err.contains(QStringLiteral("GLU tolerance"))); // progress on stderr

        QFile f(json);
        QVERIFY(f.open(QIODevice::ReadOnly));
        QJsonParseError parseError;
        const QJsonDocument doc = QJsonDocument::fromJson(f.readAll(), &parseError);
        QVERIFY2(parseError.error == QJsonParseError::NoError,
                 qPrintable(parseError.errorString()));
        const QJsonObject root = doc.object();
        QVERIFY(root.value(QStringLiteral("command"))
                    .toString()
                    .startsWith(QStringLiteral("knotwork bench")));
        const QJsonObject machine = root.value(QStringLiteral("machine")).toObject();
        QVERIFY(!machine.value(QStringLiteral("cpu")).toString().isEmpty());
        QVERIFY(!machine.value(QStringLiteral("gl")).toString().isEmpty());
        const QJsonObject settings = root.value(QStringLiteral("settings")).toObject();
        QCOMPARE(settings.value(QStringLiteral("frames")).toInt(), 2);
        QCOMPARE(settings.value(QStringLiteral("table2Width")).toInt(), 64);

        const QJsonArray t1 = root.value(QStringLiteral("table1")).toArray();
        QCOMPARE(t1.size(), 1);
        const QJsonObject row1 = t1.at(0).toObject();
        QCOMPARE(row1.value(QStringLiteral("model")).toString(), QStringLiteral("bicubic.knot"));
        QCOMPARE(row1.value(QStringLiteral("width")).toInt(), 64);
        QCOMPARE(row1.value(QStringLiteral("partitions")).toInt(), 30);
        checkNumbers(row1, kTiming + QStringList{QStringLiteral("coverage")},
                     QStringLiteral("table1"));
        checkQuality(row1, QStringLiteral("table1"));
        QVERIFY(row1.value(QStringLiteral("coverage")).toDouble() > 0.0);

        const QJsonArray t2 = root.value(QStringLiteral("table2")).toArray();
        QCOMPARE(t2.size(), 2);
        for (int k = 0; k < 2; ++k) {
            const QJsonObject row = t2.at(k).toObject();
            const int parts = k == 0 ? 4 : 8;
            QCOMPARE(row.value(QStringLiteral("partitions")).toInt(), parts);
            checkNumbers(row.value(QStringLiteral("ratios")).toObject(),
                         {QStringLiteral("exactOverBaseline"), QStringLiteral("exactOverFineMesh"),
                          QStringLiteral("exactOverGlu")},
                         QStringLiteral("ratios"));
            for (const char* m : {"exact", "baseline", "fineMesh", "glu"}) {
                const QString where = QStringLiteral("table2 %1 %2").arg(parts).arg(m);
                const QJsonObject method = row.value(QString::fromLatin1(m)).toObject();
                checkNumbers(
                    method,
                    kTiming + QStringList{QStringLiteral("parameter"), QStringLiteral("triangles")},
                    where);
                checkQuality(method, where);
                QVERIFY(method.value(QStringLiteral("matched")).isBool());
                QVERIFY(method.value(QStringLiteral("triangles")).toDouble() > 0.0);
                QVERIFY(method.value(QStringLiteral("normalError"))
                            .toObject()
                            .value(QStringLiteral("pixels"))
                            .toDouble() > 0.0);
            }
            const auto maxError = [&](const char* m) {
                return row.value(QString::fromLatin1(m))
                    .toObject()
                    .value(QStringLiteral("normalError"))
                    .toObject()
                    .value(QStringLiteral("maxDegrees"))
                    .toDouble();
            };
            // Exact mode shows the kernel's normal up to float rounding; the coarse baseline's
            // interpolated normals are visibly off; the searched fine mesh and GLU either
            // reached the target or say they did not.
            QVERIFY2(maxError("exact") < 0.05, qPrintable(QString::number(maxError("exact"))));
            QVERIFY(maxError("baseline") > maxError("exact"));
            const double target = row.value(QStringLiteral("targetMaxNormalDegrees")).toDouble();
            QVERIFY(target >= maxError("exact"));
            for (const char* m : {"fineMesh", "glu"})
                QCOMPARE(row.value(QString::fromLatin1(m))
                             .toObject()
                             .value(QStringLiteral("matched"))
                             .toBool(),
                         maxError(m) <= target);
            QVERIFY(row.value(QStringLiteral("fineMesh"))
                        .toObject()
                        .value(QStringLiteral("parameter"))
                        .toDouble() >= parts);
        }

        QFile mdFile(md);
        QVERIFY(mdFile.open(QIODevice::ReadOnly));
        const QString text = QString::fromUtf8(mdFile.readAll());
        QVERIFY(text.contains(QStringLiteral("### Table 1")));
        QVERIFY(text.contains(QStringLiteral("| bicubic.knot | 1 | 64x64 |")));
        QVERIFY(text.contains(QStringLiteral("| bicubic.knot | 4x4 |")));
        QVERIFY(text.contains(QStringLiteral("| bicubic.knot | 8x8 | GLU |")));
        for (const char* png :
             {"table1-fps.png", "table2-bicubic-fps.png", "table2-bicubic-error.png"}) {
            const QString path = dir + QLatin1Char('/') + QString::fromLatin1(png);
            QVERIFY2(text.contains(QStringLiteral("](%1)").arg(QString::fromLatin1(png))), png);
            QImage img;
            QVERIFY2(img.load(path, "PNG"), qPrintable(path));
            QVERIFY(img.width() > 100 && img.height() > 100);
        }
    }

    void trimDragAndNoTrimsOnTable1() {
        const QString dir = outDir();
        const QStringList table1 = {QStringLiteral("bench"),    sample("trimmed_plate"),
                                    sample("bicubic"),          QStringLiteral("--smoke"),
                                    QStringLiteral("--tables"), QStringLiteral("1"),
                                    QStringLiteral("--sizes"),  QStringLiteral("64")};
        // (json, markdown) of a run with `extra` options; QVERIFY fails the caller on error.
        const auto run = [&](const QStringList& extra, const QString& name) {
            const QString json = dir + QLatin1Char('/') + name + QStringLiteral(".json");
            const QString md = dir + QLatin1Char('/') + name + QStringLiteral(".md");
            const Run r = knotwork(
                table1 + extra +
                QStringList{QStringLiteral("--json"), json, QStringLiteral("--markdown"), md});
            return std::tuple{r, readJson(json), readText(md)};
        };

        // --trim-drag: the plate's row has finite drag numbers, the bicubic's (no trims) null.
        const auto [dragRun, drag, dragMd] =
            run({QStringLiteral("--trim-drag")}, QStringLiteral("drag"));
        QVERIFY2(dragRun.code == 0, qPrintable(dragRun.err));
        QVERIFY(dragRun.err.contains(QStringLiteral("trimmed_plate.knot 64x64 trim drag")));
        QVERIFY(drag.value(QStringLiteral("settings"))
                    .toObject()
                    .value(QStringLiteral("trimDrag"))
                    .toBool());
        const QJsonArray rows = drag.value(QStringLiteral("table1")).toArray();
        QCOMPARE(rows.size(), 2);
        const QJsonObject plate = rows.at(0).toObject(), bicubic = rows.at(1).toObject();
        QCOMPARE(plate.value(QStringLiteral("model")).toString(),
                 QStringLiteral("trimmed_plate.knot"));
        checkNumbers(plate, kDragKeys, QStringLiteral("trimmed_plate drag"));
        QVERIFY(plate.value(QStringLiteral("trimDragMsMedian")).toDouble() > 0.0);
        const int side = plate.value(QStringLiteral("maskSide")).toInt();
        QVERIFY2(side >= 32 && (side & (side - 1)) == 0, qPrintable(QString::number(side)));
        for (const QString& k : kDragKeys)
            QVERIFY2(bicubic.contains(k) && bicubic.value(k).isNull(), qPrintable(k));
        QVERIFY(dragMd.contains(kDragHeader));
        QVERIFY(dragMd.contains(
            QStringLiteral("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")));
        const QString bicubicLine = dragMd.mid(dragMd.indexOf(QStringLiteral("| bicubic.knot |")))
                                        .section(QLatin1Char('\n'), 0, 0);
        QVERIFY2(bicubicLine.endsWith(QStringLiteral("| - | - | - |")), qPrintable(bicubicLine));
        const QString plateLine =
            dragMd.mid(dragMd.indexOf(QStringLiteral("| trimmed_plate.knot |")))
                .section(QLatin1Char('\n'), 0, 0);
        QCOMPARE(plateLine.count(QLatin1Char('|')), 14);
        QVERIFY2(plateLine.endsWith(QStringLiteral(" | %1 |").arg(side)), qPrintable(plateLine));

        // Without --trim-drag the columns and keys are absent; --no-trims shows the whole plate.
        const auto [wholeRun, whole, wholeMd] =
            run({QStringLiteral("--no-trims")}, QStringLiteral("whole"));
        QVERIFY2(wholeRun.code == 0, qPrintable(wholeRun.err));
        QVERIFY(!wholeMd.contains(kDragHeader));
        QVERIFY(wholeMd.contains(QStringLiteral("partitions, trims off")));
        QVERIFY(!dragMd.contains(QStringLiteral("trims off")));
        const QJsonObject settings = whole.value(QStringLiteral("settings")).toObject();
        QCOMPARE(settings.value(QStringLiteral("trims")).toBool(true), false);
        QCOMPARE(settings.value(QStringLiteral("trimDrag")).toBool(true), false);
        const QJsonArray wholeRows = whole.value(QStringLiteral("table1")).toArray();
        QCOMPARE(wholeRows.size(), 2);
        for (const QJsonValue& row : wholeRows)
            for (const QString& k : kDragKeys)
                QVERIFY2(!row.toObject().contains(k), qPrintable(k));
        const auto coverage = [](const QJsonObject& o) {
            return o.value(QStringLiteral("coverage")).toDouble();
        };
        QVERIFY2(coverage(wholeRows.at(0).toObject()) > coverage(plate),
                 qPrintable(QStringLiteral("%1 <= %2")
                                .arg(coverage(wholeRows.at(0).toObject()))
                                .arg(coverage(plate))));
        QCOMPARE(coverage(wholeRows.at(1).toObject()), coverage(bicubic));
    }

    void cadFilesAreReadAsRenderReadsThem() {
        // A BREP part through kw::openModelFile (the CAD reader's child process), as `render`.
        const QString json = outDir() + QStringLiteral("/cad.json");
        const Run r = knotwork(
            {QStringLiteral("bench"), QStringLiteral(KW_TEST_DATA_DIR "/Pump_Nut.brep"),
             QStringLiteral("--smoke"), QStringLiteral("--tables"), QStringLiteral("1"),
             QStringLiteral("--sizes"), QStringLiteral("64"), QStringLiteral("--json"), json});
        QVERIFY2(r.code == 0, qPrintable(r.err));
        const QJsonArray rows = readJson(json).value(QStringLiteral("table1")).toArray();
        QCOMPARE(rows.size(), 1);
        QCOMPARE(rows.at(0).toObject().value(QStringLiteral("model")).toString(),
                 QStringLiteral("Pump_Nut.brep"));
        QVERIFY(rows.at(0).toObject().value(QStringLiteral("coverage")).toDouble() > 0.0);
        // A CAD file that cannot be read: exit 1, the reader's error naming the file.
        const QString bad = outDir() + QStringLiteral("/bench_broken.iges");
        QFile f(bad);
        QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
        f.write("not an IGES file\n");
        f.close();
        const Run broken = knotwork({QStringLiteral("bench"), bad, QStringLiteral("--smoke")});
        QCOMPARE(broken.code, 1);
        QVERIFY2(broken.err.contains(bad + QStringLiteral(": ")), qPrintable(broken.err));
    }

    void badInputIsAnErrorNotACrash() {
        const Run missing = knotwork({QStringLiteral("bench"), QStringLiteral("/no/such.knot")});
        QCOMPARE(missing.code, 1);
        QVERIFY(missing.err.contains(QStringLiteral("no such file")));
        for (const QStringList& bad :
             {QStringList{QStringLiteral("--partitions"), QStringLiteral("0,5")},
              QStringList{QStringLiteral("--partitions"), QStringLiteral("5,x")},
              QStringList{QStringLiteral("--frames"), QStringLiteral("2")},
              QStringList{QStringLiteral("--table2-size"), QStringLiteral("780")},
              QStringList{QStringLiteral("--sizes"), QStringLiteral("64,5000")},
              QStringList{QStringLiteral("--tables"), QStringLiteral("3")},
              QStringList{QStringLiteral("--trim-drag"), QStringLiteral("--no-trims")},
              QStringList{QStringLiteral("--trim-drag"), QStringLiteral("--tables"),
                          QStringLiteral("2")},
              QStringList{QStringLiteral("--normal-floor"), QStringLiteral("-1")},
              QStringList{QStringLiteral("--aa-method"), QStringLiteral("msaa")}}) {
            const Run r = knotwork(QStringList{QStringLiteral("bench"), sample("bicubic")} + bad);
            QVERIFY2(r.code == 2, qPrintable(bad.join(QLatin1Char(' ')) + r.err));
        }
        const QString broken = QStringLiteral(KW_TEST_OUTPUT_DIR "/bench_broken.knot");
        QDir().mkpath(QStringLiteral(KW_TEST_OUTPUT_DIR));
        QFile f(broken);
        QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
        f.write("this is not a knot file\n");
        f.close();
        const Run r = knotwork({QStringLiteral("bench"), broken, QStringLiteral("--smoke")});
        QCOMPARE(r.code, 1);
        QVERIFY(!r.err.isEmpty());
    }
};

QTEST_GUILESS_MAIN(TestBench)
#include "tst_bench.moc"
