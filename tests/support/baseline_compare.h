// Baseline images for the GL tests: a frame compared with tests/baselines/NAME.png through
// OpenImageIO under a stated tolerance. A missing baseline fails; KW_UPDATE_BASELINES=1 writes
// the baseline instead of comparing. On a mismatch NAME.actual.png and NAME.diff.png (the
// difference times 8) are written to KW_TEST_OUTPUT_DIR.
#pragma once

#include "expected_test_util.h"
#include "render/image_writer.h"
#include "render_test_util.h"

#include <OpenImageIO/imagebufalgo.h>
#include <QDir>
#include <QFileInfo>
#include <QImage>
#include <QTest>

namespace kwtest {

/// A pixel fails when any channel differs by more than failThreshold (0..1); the image fails
/// when more than maxFailedFraction of its pixels do or the mean error exceeds maxMeanError.
struct BaselineTolerance {
    float failThreshold = 0.05f;
    double maxFailedFraction = 0.002;
    double maxMeanError = 0.004;
};

inline QString baselinePath(const QString& name) {
    return QStringLiteral(KW_SOURCE_DIR "/tests/baselines/") + name + QStringLiteral(".png");
}

/// Compares `img` with baselinePath(name) (QVERIFY: call it last in a test function).
inline void checkBaseline(const QImage& img, const QString& name, const BaselineTolerance& tol) {
    QString error;
    const QString expected = baselinePath(name);
    if (qEnvironmentVariableIntValue("KW_UPDATE_BASELINES") == 1) {
        QDir().mkpath(QFileInfo(expected).absolutePath());
        KW_VERIFY_OK(kw::writeColorImage(img, expected));
        qInfo("wrote %s", qPrintable(expected));
        return;
    }
    QVERIFY2(QFileInfo::exists(expected),
             qPrintable(QStringLiteral("missing baseline %1 (generate with KW_UPDATE_BASELINES=1)")
                            .arg(expected)));
    const QString actualPath = outputDir().filePath(name + QStringLiteral(".actual.png"));
    const QString diffPath = outputDir().filePath(name + QStringLiteral(".diff.png"));
    KW_VERIFY_OK(kw::writeColorImage(img, actualPath));
    OIIO::ImageBuf actual(actualPath.toStdString()), base(expected.toStdString());
    QVERIFY2(actual.read() && base.read(), "could not read the images back");
    QCOMPARE(actual.spec().width, base.spec().width);
    QCOMPARE(actual.spec().height, base.spec().height);
    const OIIO::ImageBufAlgo::CompareResults r =
        OIIO::ImageBufAlgo::compare(actual, base, tol.failThreshold, tol.failThreshold * 0.5f);
    const double failed = double(r.nfail) / double(actual.spec().width * actual.spec().height);
    qInfo("%s: mean error %.5f, max %.4f, %lld pixel(s) over %.2f (%.3f%%)", qPrintable(name),
          r.meanerror, r.maxerror, (long long)r.nfail, tol.failThreshold, 100.0 * failed);
    const bool ok = failed <= tol.maxFailedFraction && r.meanerror <= tol.maxMeanError;
    if (ok) {
        QFile::remove(actualPath);
    } else {
        OIIO::ImageBuf diff = OIIO::ImageBufAlgo::absdiff(actual, base);
        diff = OIIO::ImageBufAlgo::mul(diff, 8.0f);
        diff.write(diffPath.toStdString());
    }
    QVERIFY2(ok, qPrintable(QStringLiteral("%1 differs from %2; see %3 and %4")
                                .arg(name, expected, actualPath, diffPath)));
}

} // namespace kwtest
