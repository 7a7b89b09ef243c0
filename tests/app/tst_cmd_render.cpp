// GL test: 'knotwork render' end to end (image, AOV EXR channels, error exits, CAD files) and
// 'bench'.
#include "knotwork_process.h"

#include <OpenImageIO/imageio.h>
#include <QDir>
#include <QFile>
#include <QProcess>
#include <QRegularExpression>
#include <QTest>
#include <vector>

namespace {

QString sample(const char* name) {
    return QStringLiteral(KW_SAMPLES_DIR "/%1.knot").arg(QString::fromLatin1(name));
}

QString output(const char* name) {
    QDir(QStringLiteral(KW_TEST_OUTPUT_DIR)).mkpath(QStringLiteral("."));
    return QStringLiteral(KW_TEST_OUTPUT_DIR "/%1").arg(QString::fromLatin1(name));
}

QString testData(const char* name) {
    return QStringLiteral(KW_TEST_DATA_DIR "/%1").arg(QString::fromLatin1(name));
}

/// An 8-bit RGB(A) image read with OpenImageIO: width, height, channels and pixels.
struct Pixels {
    int width = 0, height = 0, channels = 0;
    std::vector<unsigned char> data;
};

Pixels readPixels(const QString& path) {
    Pixels p;
    auto in = OIIO::ImageInput::open(path.toStdString());
    if (!in)
        return p;
    p.width = in->spec().width;
    p.height = in->spec().height;
    p.channels = in->spec().nchannels;
    p.data.resize(size_t(p.width) * size_t(p.height) * size_t(p.channels));
    if (!in->read_image(0, 0, 0, p.channels, OIIO::TypeDesc::UINT8, p.data.data()))
        p.data.clear();
    in->close();
    return p;
}

/// teapot.igs with the second patch's u knots all 1.0: OpenCASCADE cannot make that surface, so
/// the import skips one face of 32 (as tst_cadimport's untransferableEntityIsReported).
QString teapotWithBadPatch() {
    QFile in(testData("teapot.igs"));
    if (!in.open(QIODevice::ReadOnly))
        return {};
    QList<QByteArray> lines = in.readAll().split('\n');
    const int firstParameterLineOfPatch2 = 1 + 1 + 64 + 26; // S, G, 64 D lines, 26 P lines
    if (!lines.value(firstParameterLineOfPatch2).startsWith("128,3,3,3,3"))
        return {};
    lines[firstParameterLineOfPatch2 + 1].replace(0, 16, "1.0,1.0,1.0,1.0,");
    const QString path = output("cmd_teapot_bad_patch.igs");
    QFile out(path);
    if (!out.open(QIODevice::WriteOnly) || out.write(lines.join('\n')) < 0)
        return {};
    return path;
}

} // namespace

class TestCmdRender : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void writesImageAndAov() {
        const QString png = output("cmd_torus.png"), exr = output("cmd_torus_aov.exr");
        QFile::remove(png);
        QFile::remove(exr);
        const Run r = knotwork({QStringLiteral("render"), sample("torus"), QStringLiteral("-o"),
                                png, QStringLiteral("--size"), QStringLiteral("160x120"),
                                QStringLiteral("--partitions"), QStringLiteral("6x4"),
                                QStringLiteral("--lights"), QStringLiteral("3"),
                                QStringLiteral("--aov"), exr});
        QVERIFY2(r.code == 0, qPrintable(r.err));
        auto in = OIIO::ImageInput::open(png.toStdString());
        QVERIFY(in);
        QCOMPARE(in->spec().width, 160);
        QCOMPARE(in->spec().height, 120);
        in->close();
        auto aov = OIIO::ImageInput::open(exr.toStdString());
        QVERIFY(aov);
        const OIIO::ImageSpec& spec = aov->spec();
        QCOMPARE(spec.nchannels, 10);
        QCOMPARE(spec.format, OIIO::TypeDesc(OIIO::TypeDesc::FLOAT));
        QStringList names;
        for (const std::string& n : spec.channelnames)
            names << QString::fromStdString(n);
        for (const char* n : {"id", "u", "v", "P.x", "P.y", "P.z", "N.x", "N.y", "N.z", "Z"})
            QVERIFY2(names.contains(QString::fromLatin1(n)), n);
        // The background is -1 and the torus covers some pixels with id 1.
        std::vector<float> px(size_t(spec.width) * spec.height * 10);
        QVERIFY(aov->read_image(0, 0, 0, 10, OIIO::TypeDesc::FLOAT, px.data()));
        const int idChannel = int(names.indexOf(QStringLiteral("id")));
        int background = 0, torus = 0;
        for (size_t k = 0; k < px.size() / 10; ++k) {
            const float id = px[k * 10 + size_t(idChannel)];
            background += id == -1.0f;
            torus += id == 1.0f;
        }
        QVERIFY(background > 0);
        QVERIFY(torus > 1000);
        QCOMPARE(background + torus, spec.width * spec.height);
    }

    // --progressive draws the anti-aliased image a sample per frame, as the editor does on
    // software OpenGL: the same pixels as all samples at once; --time-frames then also times
    // whole images.
    void progressiveWritesTheSameImage() {
        const QString once = output("cmd_aa_once.png"), progressive = output("cmd_aa_prog.png"),
                      aliased = output("cmd_aa_aliased.png");
        const QStringList common{QStringLiteral("render"), sample("trimmed_plate"),
                                 QStringLiteral("--size"), QStringLiteral("160x120")};
        const Run a =
            knotwork(common + QStringList{QStringLiteral("-o"), once, QStringLiteral("--samples"),
                                          QStringLiteral("4")});
        QVERIFY2(a.code == 0, qPrintable(a.err));
        const Run b = knotwork(
            common + QStringList{QStringLiteral("-o"), progressive, QStringLiteral("--samples"),
                                 QStringLiteral("4"), QStringLiteral("--progressive"),
                                 QStringLiteral("--time-frames"), QStringLiteral("8"),
                                 QStringLiteral("--pass-times")});
        QVERIFY2(b.code == 0, qPrintable(b.err));
        QVERIFY2(b.out.contains(QStringLiteral("median whole image of 4 samples")) &&
                     b.out.contains(QStringLiteral("over 2 images")),
                 qPrintable(b.out));
        // --pass-times: the passes' CPU, the exact pass among them.
        QVERIFY2(QRegularExpression(QStringLiteral("median pass CPU ms:.* exact [0-9]"))
                     .match(b.out)
                     .hasMatch(),
                 qPrintable(b.out));
        const Run c = knotwork(common + QStringList{QStringLiteral("-o"), aliased});
        QVERIFY2(c.code == 0, qPrintable(c.err));
        const Pixels p = readPixels(once), q = readPixels(progressive), r = readPixels(aliased);
        QVERIFY(!p.data.empty() && p.data.size() == q.data.size() &&
                p.data.size() == r.data.size());
        QVERIFY(p.data == q.data);
        QVERIFY(p.data != r.data); // anti-aliased: the trim edges differ from the aliased frame
    }

    void badInputExitsOneNamingTheFile() {
        const Run r = knotwork({QStringLiteral("render"), QStringLiteral("/nonexistent/x.knot"),
                                QStringLiteral("-o"), output("x.png")});
        QCOMPARE(r.code, 1);
        QVERIFY2(r.err.contains(QStringLiteral("/nonexistent/x.knot")), qPrintable(r.err));
    }

    // `render part.step` draws what `convert part.step part.knot` then `render part.knot` draws:
    // the same import (in the CAD reader's child process), the same fitted camera.
    void cadFileRendersAsItsConvertedKnot_data() {
        QTest::addColumn<QString>("cad");
        QTest::addColumn<int>("faces");
        QTest::newRow("STEP") << testData("screw.step") << 10;
        QTest::newRow("IGES") << testData("hammer.iges") << 45;
        QTest::newRow("BREP") << testData("Pump_Nut.brep") << 25;
    }
    void cadFileRendersAsItsConvertedKnot() {
        QFETCH(QString, cad);
        QFETCH(int, faces);
        const Run probe = knotwork({QStringLiteral("convert"), cad, output("cmd_cad.knot")});
        if (probe.err.contains(QStringLiteral("built without OpenCASCADE")))
            QSKIP("built without OpenCASCADE");
        QVERIFY2(probe.code == 0, qPrintable(probe.err));
        const QString fromCad = output("cmd_cad_direct.png"), fromKnot = output("cmd_cad_knot.png");
        QFile::remove(fromCad);
        QFile::remove(fromKnot);
        const QString size = QStringLiteral("120x90");
        const Run direct = knotwork({QStringLiteral("render"), cad, QStringLiteral("-o"), fromCad,
                                     QStringLiteral("--size"), size});
        QVERIFY2(direct.code == 0, qPrintable(direct.err));
        QVERIFY2(direct.out.contains(QStringLiteral("render of %1 surface(s)").arg(faces)),
                 qPrintable(direct.out));
        const Run viaKnot =
            knotwork({QStringLiteral("render"), output("cmd_cad.knot"), QStringLiteral("-o"),
                      fromKnot, QStringLiteral("--size"), size});
        QVERIFY2(viaKnot.code == 0, qPrintable(viaKnot.err));
        const Pixels a = readPixels(fromCad), b = readPixels(fromKnot);
        QCOMPARE(a.width, 120);
        QCOMPARE(a.height, 90);
        QVERIFY(!a.data.empty());
        QCOMPARE(b.width, a.width);
        QCOMPARE(b.height, a.height);
        QCOMPARE(b.channels, a.channels);
        QCOMPARE(b.data.size(), a.data.size());
        // Tolerance: every channel of every pixel within 2 of 255 (the two paths run the same
        // code on the same scene, so they agree exactly today); and the part is in the picture.
        int differ = 0, part = 0;
        const size_t n = size_t(a.channels);
        for (size_t px = 0; px < a.data.size() / n; ++px) {
            bool same = true, background = true;
            for (size_t c = 0; c < n; ++c) {
                same = same && std::abs(int(a.data[px * n + c]) - int(b.data[px * n + c])) <= 2;
                background = background && a.data[px * n + c] == a.data[c]; // corner's colour
            }
            differ += !same;
            part += !background;
        }
        QCOMPARE(differ, 0);
        QVERIFY2(part > a.width * a.height / 40, qPrintable(QString::number(part)));
    }

    // A CAD file that cannot be read: exit 1, the message names the file, no image.
    void unreadableCadFileExitsOne_data() {
        QTest::addColumn<QString>("path");
        QTest::addColumn<QByteArray>("content"); // empty: the file does not exist
        QTest::newRow("missing STEP") << output("cmd_missing.step") << QByteArray();
        QTest::newRow("not IGES") << output("cmd_not_iges.iges")
                                  << QByteArray("this is not an IGES file\n").repeated(40);
        QFile screw(testData("screw.step"));
        QVERIFY(screw.open(QIODevice::ReadOnly));
        QTest::newRow("truncated STEP") << output("cmd_truncated.step") << screw.read(600);
        QTest::newRow("corrupt BREP") << output("cmd_corrupt.brep")
                                      << QByteArray("DBRep_DrawableShape\n\nCASCADE Topology "
                                                    "V1, (c) Matra-Datavision\nLocations 3\n");
    }
    void unreadableCadFileExitsOne() {
        QFETCH(QString, path);
        QFETCH(QByteArray, content);
        QFile::remove(path);
        if (!content.isEmpty()) {
            QFile f(path);
            QVERIFY(f.open(QIODevice::WriteOnly));
            QCOMPARE(f.write(content), content.size());
        }
        const QString png = output("cmd_unreadable.png");
        QFile::remove(png);
        const Run r = knotwork({QStringLiteral("render"), path, QStringLiteral("-o"), png,
                                QStringLiteral("--size"), QStringLiteral("64x64")},
                               QProcessEnvironment::systemEnvironment(), 120000);
        QCOMPARE(r.code, 1);
        QVERIFY2(r.err.contains(path), qPrintable(r.err));
        QVERIFY(!QFile::exists(png));
    }

    // Faces the importer skips are reported on stderr, naming the file; the rest is drawn.
    void skippedFacesWarn() {
        const QString igs = teapotWithBadPatch();
        QVERIFY(!igs.isEmpty());
        const QString png = output("cmd_teapot_bad_patch.png");
        QFile::remove(png);
        const Run r = knotwork({QStringLiteral("render"), igs, QStringLiteral("-o"), png,
                                QStringLiteral("--size"), QStringLiteral("64x64")});
        if (r.err.contains(QStringLiteral("built without OpenCASCADE")))
            QSKIP("built without OpenCASCADE");
        QVERIFY2(r.code == 0, qPrintable(r.err));
        QVERIFY2(r.err.contains(QStringLiteral("%1: 1 face(s) skipped, 31 imported").arg(igs)),
                 qPrintable(r.err));
        QVERIFY2(r.err.contains(QStringLiteral("%1: skipped: ").arg(igs)) &&
                     r.err.contains(QStringLiteral("IGESGeom_BSplineSurface")),
                 qPrintable(r.err));
        // The file's repaired numbering is an import warning, reported the same way.
        QVERIFY2(r.err.contains(QStringLiteral("%1: warning: ").arg(igs)), qPrintable(r.err));
        QVERIFY2(r.out.contains(QStringLiteral("render of 31 surface(s)")), qPrintable(r.out));
        QCOMPARE(readPixels(png).width, 64);
    }

    void usageErrorsExitTwo_data() {
        QTest::addColumn<QStringList>("args");
        QTest::newRow("bad extension")
            << QStringList{sample("torus"), QStringLiteral("-o"), output("x.bmp")};
        QTest::newRow("bad size") << QStringList{sample("torus"), QStringLiteral("-o"),
                                                 output("x.png"), QStringLiteral("--size"),
                                                 QStringLiteral("0x10")};
        QTest::newRow("bad mode") << QStringList{sample("torus"), QStringLiteral("-o"),
                                                 output("x.png"), QStringLiteral("--mode"),
                                                 QStringLiteral("fast")};
        QTest::newRow("bad lights")
            << QStringList{sample("torus"), QStringLiteral("-o"), output("x.png"),
                           QStringLiteral("--lights"), QStringLiteral("9")};
        QTest::newRow("aov not exr")
            << QStringList{sample("torus"), QStringLiteral("-o"), output("x.png"),
                           QStringLiteral("--aov"), output("a.png")};
        QTest::newRow("no output") << QStringList{sample("torus")};
        QTest::newRow("bad partition mode")
            << QStringList{sample("torus"), QStringLiteral("-o"), output("x.png"),
                           QStringLiteral("--partition-mode"), QStringLiteral("fine")};
        QTest::newRow("bad pixel tolerance")
            << QStringList{sample("torus"), QStringLiteral("-o"), output("x.png"),
                           QStringLiteral("--pixel-tolerance"), QStringLiteral("0")};
        QTest::newRow("bad trim mode")
            << QStringList{sample("trimmed_plate"), QStringLiteral("-o"), output("x.png"),
                           QStringLiteral("--trim-mode"), QStringLiteral("fuzzy")};
        QTest::newRow("bad trim budget")
            << QStringList{sample("trimmed_plate"), QStringLiteral("-o"), output("x.png"),
                           QStringLiteral("--trim-budget"), QStringLiteral("0")};
        QTest::newRow("bad samples")
            << QStringList{sample("trimmed_plate"), QStringLiteral("-o"), output("x.png"),
                           QStringLiteral("--samples"), QStringLiteral("17")};
        QTest::newRow("bad aa method") << QStringList{
            sample("trimmed_plate"),     QStringLiteral("-o"), output("x.png"),
            QStringLiteral("--samples"), QStringLiteral("4"),  QStringLiteral("--aa-method"),
            QStringLiteral("msaa")};
        QTest::newRow("progressive aliased")
            << QStringList{sample("trimmed_plate"), QStringLiteral("-o"), output("x.png"),
                           QStringLiteral("--progressive")};
        QTest::newRow("progressive msaa") << QStringList{sample("trimmed_plate"),
                                                         QStringLiteral("-o"),
                                                         output("x.png"),
                                                         QStringLiteral("--samples"),
                                                         QStringLiteral("4"),
                                                         QStringLiteral("--aa-method"),
                                                         QStringLiteral("coverage"),
                                                         QStringLiteral("--progressive")};
        QTest::newRow("bad zoom point")
            << QStringList{sample("trimmed_plate"), QStringLiteral("-o"), output("x.png"),
                           QStringLiteral("--zoom"), QStringLiteral("8@1.5,0.5")};
        QTest::newRow("bad zoom factor")
            << QStringList{sample("trimmed_plate"), QStringLiteral("-o"), output("x.png"),
                           QStringLiteral("--zoom"), QStringLiteral("0.5")};
        QTest::newRow("pass times untimed")
            << QStringList{sample("trimmed_plate"), QStringLiteral("-o"), output("x.png"),
                           QStringLiteral("--pass-times")};
    }
    void usageErrorsExitTwo() {
        QFETCH(QStringList, args);
        args.prepend(QStringLiteral("render"));
        const Run r = knotwork(args);
        QCOMPARE(r.code, 2);
        QVERIFY(!r.err.isEmpty());
        // The message names the option at fault.
        if (args.contains(QStringLiteral("--partition-mode")))
            QVERIFY2(r.err.contains(QStringLiteral("--partition-mode 'fine'")), qPrintable(r.err));
        if (args.contains(QStringLiteral("--pixel-tolerance")))
            QVERIFY2(r.err.contains(QStringLiteral("--pixel-tolerance '0'")), qPrintable(r.err));
        if (args.contains(QStringLiteral("--trim-mode")))
            QVERIFY2(r.err.contains(QStringLiteral("--trim-mode 'fuzzy'")), qPrintable(r.err));
        if (args.contains(QStringLiteral("--trim-budget")))
            QVERIFY2(r.err.contains(QStringLiteral("--trim-budget '0'")), qPrintable(r.err));
        if (args.contains(QStringLiteral("--progressive")))
            QVERIFY2(r.err.contains(QStringLiteral("--progressive needs --samples N > 1")),
                     qPrintable(r.err));
        else if (args.contains(QStringLiteral("--aa-method")))
            QVERIFY2(r.err.contains(QStringLiteral("--aa-method 'msaa' is not accumulate or "
                                                   "coverage")),
                     qPrintable(r.err));
        else if (args.contains(QStringLiteral("--samples")))
            QVERIFY2(r.err.contains(QStringLiteral("--samples '17'")), qPrintable(r.err));
        if (args.contains(QStringLiteral("--zoom")))
            QVERIFY2(r.err.contains(QStringLiteral("--zoom '")), qPrintable(r.err));
        if (args.contains(QStringLiteral("--pass-times")))
            QVERIFY2(r.err.contains(QStringLiteral("--pass-times needs --time-frames N")),
                     qPrintable(r.err));
    }

    void benchPrintsATable() {
        const Run r =
            knotwork({QStringLiteral("bench"), sample("bicubic"), QStringLiteral("--sizes"),
                      QStringLiteral("32,48"), QStringLiteral("--frames"), QStringLiteral("20")});
        QVERIFY2(r.code == 0, qPrintable(r.err));
        QVERIFY(r.out.contains(QStringLiteral("| bicubic.knot | 1 | 32x32 |")));
        QVERIFY(r.out.contains(QStringLiteral("| bicubic.knot | 1 | 48x48 |")));
        QVERIFY(r.err.contains(QStringLiteral("FPS")));
        QCOMPARE(knotwork({QStringLiteral("bench"), sample("bicubic"), QStringLiteral("--frames"),
                           QStringLiteral("5")})
                     .code,
                 2);
    }
};

QTEST_GUILESS_MAIN(TestCmdRender)
#include "tst_cmd_render.moc"
