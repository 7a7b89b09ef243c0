// GL test: 'knotwork render' end to end (image, AOV EXR channels, error exits) and 'bench'.
#include "knotwork_process.h"

#include <OpenImageIO/imageio.h>
#include <QDir>
#include <QProcess>
#include <QTest>

namespace {

QString sample(const char* name) {
    return QStringLiteral(KW_SAMPLES_DIR "/%1.knot").arg(QString::fromLatin1(name));
}

QString output(const char* name) {
    QDir(QStringLiteral(KW_TEST_OUTPUT_DIR)).mkpath(QStringLiteral("."));
    return QStringLiteral(KW_TEST_OUTPUT_DIR "/%1").arg(QString::fromLatin1(name));
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

    void badInputExitsOneNamingTheFile() {
        const Run r = knotwork({QStringLiteral("render"), QStringLiteral("/nonexistent/x.knot"),
                                QStringLiteral("-o"), output("x.png")});
        QCOMPARE(r.code, 1);
        QVERIFY2(r.err.contains(QStringLiteral("/nonexistent/x.knot")), qPrintable(r.err));
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
        QTest::newRow("bad zoom point")
            << QStringList{sample("trimmed_plate"), QStringLiteral("-o"), output("x.png"),
                           QStringLiteral("--zoom"), QStringLiteral("8@1.5,0.5")};
        QTest::newRow("bad zoom factor")
            << QStringList{sample("trimmed_plate"), QStringLiteral("-o"), output("x.png"),
                           QStringLiteral("--zoom"), QStringLiteral("0.5")};
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
        if (args.contains(QStringLiteral("--samples")))
            QVERIFY2(r.err.contains(QStringLiteral("--samples '17'")), qPrintable(r.err));
        if (args.contains(QStringLiteral("--zoom")))
            QVERIFY2(r.err.contains(QStringLiteral("--zoom '")), qPrintable(r.err));
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
