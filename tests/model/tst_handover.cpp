// The CAD child's binary hand-over (model/cad/handover.h): everything written reads back equal,
// and a truncated, corrupt or foreign block is an error naming where, never a crash or an
// invalid scene; through importFile, a child that writes a bad block gives an error naming the
// file.
#include "model/cad/cadprocess.h"
#include "model/cad/handover.h"
#include "model/document/validation.h"
#include "model/io/knotfile.h"
#include "tests/support/expected_test_util.h"

#include <QFile>
#include <QRandomGenerator>
#include <QTemporaryDir>
#include <QTest>

namespace {

kw::ImportResult sample(const char* name) {
    auto scene = kw::readKnotFile(QStringLiteral(KW_SAMPLES_DIR "/") + QLatin1String(name));
    if (!scene)
        qFatal("%s", qPrintable(scene.message()));
    kw::ImportResult r;
    r.scene = std::move(*scene);
    for (size_t k = 0; k < r.scene.surfaces.size(); ++k)
        r.sourceFaces.push_back(int(3 * k + 1));
    r.report.facesImported = int(r.scene.surfaces.size());
    r.report.skipped = {QStringLiteral("face 2 (Fläche ∂Ω): degree 17 above 15")};
    r.report.warnings = {QStringLiteral("face 1: gap closed"), QString()};
    r.report.seconds = 0.125;
    return r;
}

void verifySame(const kw::ImportResult& a, const kw::ImportResult& b) {
    QVERIFY(a.scene == b.scene);
    QCOMPARE(a.sourceFaces, b.sourceFaces);
    QCOMPARE(a.report.facesImported, b.report.facesImported);
    QCOMPARE(a.report.skipped, b.report.skipped);
    QCOMPARE(a.report.warnings, b.report.warnings);
    QCOMPARE(a.report.seconds, b.report.seconds);
}

void put(QByteArray& block, qsizetype at, std::uint32_t v) {
    std::memcpy(block.data() + at, &v, sizeof(v));
}

} // namespace

class TestHandover : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void everyFieldReadsBackEqual_data() {
        QTest::addColumn<QString>("name");
        for (const char* n : {"bicubic.knot", "teapot.knot", "trimmed_plate.knot",
                              "star_island.knot", "sphere.knot", "torus.knot"})
            QTest::newRow(n) << QString::fromLatin1(n);
    }
    void everyFieldReadsBackEqual() {
        QFETCH(QString, name);
        kw::ImportResult r = sample(qPrintable(name));
        QVERIFY(!r.scene.surfaces.empty());
        // Every field away from its default, and doubles that text would round.
        kw::Surface& s = r.scene.surfaces.front();
        s.hidden = true;
        s.partitionsU = 7;
        s.partitionsV = 3;
        s.material = kw::Material{{0.1, 0.2, 1.0 / 3.0}, 0.01, 0.5, 0.9, 12.5};
        s.name = QStringLiteral("Ünïcode ∑ name");
        s.geometry.points.front().x = 0.1 + 0.2;
        r.scene.lights.push_back(kw::Light{kw::Light::Kind::Point,
                                           {1, 2, 3},
                                           {0.1, 0.1, 0.1},
                                           {0.3, 0.2, 0.1},
                                           {1e-300, 0, 999.75}});
        r.scene.camera = kw::Camera{{1, 2, 3}, {0, 0.5, 0}, {0, 1, 0}, 42.0, true};
        r.scene.display = kw::DisplaySettings{};
        r.scene.display.partitionMode = QStringLiteral("uniform");
        r.scene.display.pixelTolerance = 2.25;
        r.scene.display.background = QStringLiteral("light");
        r.scene.display.sections = {kw::SectionPlane{{0.1, 0.2, 0.3}, {0, 1, 1e-9}, true},
                                    kw::SectionPlane{{-1, 0, 0}, {1, 0, 0}, false}};
        r.scene.display.sectionCaps = false;
        r.scene.display.pullDirection = {0.25, -1.0, 0.5};
        r.scene.display.draftAngleDegrees = 7.5;
        KW_VERIFY_OK(kw::checkScene(r.scene));
        const auto back = kw::decodeImportHandover(kw::encodeImportHandover(r));
        QVERIFY2(back, qPrintable(back.message()));
        verifySame(r, *back);
    }

    void everyTruncationIsAnError() {
        const QByteArray block = kw::encodeImportHandover(sample("trimmed_plate.knot"));
        for (qsizetype n = 0; n < block.size(); ++n) {
            const auto r = kw::decodeImportHandover(block.left(n));
            QVERIFY2(!r, qPrintable(QString::number(n)));
            const QString why = r.message();
            QVERIFY2(why.contains(QLatin1String(" at byte ")) && why.contains(QLatin1String(": ")),
                     qPrintable(why));
        }
    }

    void corruptBlocksAreErrorsOrValidScenes() {
        // Any byte changed: decoding stops with a reason, or gives a scene the rule accepts.
        const QByteArray block = kw::encodeImportHandover(sample("star_island.knot"));
        QRandomGenerator random(15);
        int refused = 0;
        for (int trial = 0; trial < 3000; ++trial) {
            QByteArray bad = block;
            for (int k = 0, n = 1 + trial % 4; k < n; ++k)
                bad[random.bounded(int(bad.size()))] = char(random.bounded(256));
            const auto r = kw::decodeImportHandover(bad);
            if (r)
                KW_VERIFY_OK(kw::checkScene(r->scene));
            else
                QVERIFY(!r.message().isEmpty());
            refused += r ? 0 : 1;
        }
        QVERIFY(refused > 0);
    }

    void namedFaults() {
        const QByteArray good = kw::encodeImportHandover(sample("bicubic.knot"));
        QString why;
        const auto refused = [&why](const QByteArray& block) {
            const auto r = kw::decodeImportHandover(block);
            why = r.message();
            return !r;
        };
        QByteArray bad = good;
        bad[0] = 'X';
        const auto header = kw::decodeImportHandover(bad);
        QVERIFY(!header);
        QCOMPARE(header.message(),
                 QStringLiteral("header at byte 8: not a Knotwork import hand-over"));
        QCOMPARE(header.error().location, QStringLiteral("byte 8"));
        bad = good;
        put(bad, 8, 99);
        QVERIFY(refused(bad));
        QVERIFY2(why.contains(QLatin1String("version 99")), qPrintable(why));
        bad = good;
        put(bad, 16, 0xffffffffu); // the surface count
        QVERIFY(refused(bad));
        QVERIFY2(why.startsWith(QLatin1String("surface count at byte 20: a count of 4294967295")),
                 qPrintable(why));
        QVERIFY(refused(good + "x"));
        QVERIFY2(why.contains(QLatin1String("1 bytes follow it")), qPrintable(why));
        // Well-formed, but not a valid scene: the rule of every reader refuses it.
        kw::ImportResult invalid = sample("bicubic.knot");
        invalid.scene.surfaces.front().geometry.degreeU = 40;
        QVERIFY(refused(kw::encodeImportHandover(invalid)));
        QVERIFY2(why.startsWith(QLatin1String("the scene is not valid: ")), qPrintable(why));
        kw::ImportResult faces = sample("bicubic.knot");
        faces.sourceFaces.pop_back();
        QVERIFY(refused(kw::encodeImportHandover(faces)));
        QVERIFY2(why.contains(QLatin1String("source faces for")), qPrintable(why));
    }

    void badBlockFromTheChildNamesTheFile() {
        // A "reader" that exits 0 after writing a corrupt hand-over into its folder ($3).
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const QString script = dir.filePath(QStringLiteral("reader.sh"));
        QFile f(script);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("#!/bin/sh\nprintf 'KWIMPORT' > \"$3/import.kwi\"\n");
        f.close();
        QVERIFY(f.setPermissions(f.permissions() | QFileDevice::ExeOwner));
        kw::setCadReaderExecutable(script);
        const QString part = QStringLiteral(KW_TEST_DATA_DIR "/hammer.iges");
        const auto r = kw::importFile(part);
        kw::setCadReaderExecutable({});
        QVERIFY(!r);
        const QString error = r.message();
#ifdef KW_HAVE_OCCT
        QCOMPARE(error, part + QStringLiteral(": the IGES reader gave no readable result: header "
                                              "at byte 8: the block is truncated"));
#endif
    }
};

QTEST_GUILESS_MAIN(TestHandover)
#include "tst_handover.moc"
