// GL test: a part exported as STEP and read back draws as the original did. The AOVs of both,
// with the same camera, name the same surface (ids mapped by control points) at every covered
// pixel and the same point within 1e-6 of the model's diagonal.
#include "model/cad/cadexport.h"
#include "model/cad/cadimport.h"
#include "model/nurbs/nurbs_shapes.h"
#include "render_test_util.h"
#include "tests/support/expected_test_util.h"

#include <QGuiApplication>
#include <QHash>

using namespace kw;

namespace {

// The surface of `after` with the same control point counts and the closest points.
QHash<std::uint32_t, std::uint32_t> mapIds(const Scene& before, const Scene& after) {
    QHash<std::uint32_t, std::uint32_t> map;
    std::vector<bool> used(after.surfaces.size(), false);
    for (const Surface& a : before.surfaces) {
        double best = INFINITY;
        int pick = -1;
        for (size_t k = 0; k < after.surfaces.size(); ++k) {
            const NurbsSurface &g = a.geometry, &h = after.surfaces[k].geometry;
            if (used[k] || g.countU != h.countU || g.countV != h.countV)
                continue;
            double d = 0.0;
            for (size_t i = 0; i < g.points.size(); ++i)
                d = std::max(d, glm::length(g.points[i] - h.points[i]));
            if (d < best) {
                best = d;
                pick = int(k);
            }
        }
        if (pick >= 0) {
            used[size_t(pick)] = true;
            map.insert(a.id.value, after.surfaces[size_t(pick)].id.value);
        }
    }
    return map;
}

Scene created(const QString& kind) {
    Scene s;
    Surface x;
    x.id = SurfaceId{1};
    x.name = kind;
    x.geometry = kind == QLatin1String("sphere") ? makeSphere({0, 0, 0}, 2.0)
                                                 : makeTorus({1, 2, 3}, 3.0, 1.0);
    s.surfaces = {x};
    s.nextId = 2;
    return s;
}

} // namespace

class TestRenderExchange : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

    AovBuffer render(const Scene& scene, const Camera& camera) {
        Document doc;
        if (const Status reset = doc.resetScene(scene); !reset) {
            qWarning("%s", qPrintable(reset.message()));
            return m_renderer->aov();
        }
        if (const Status drawn = m_renderer->render(doc, camera, RenderOptions{}); !drawn)
            qWarning("%s", qPrintable(drawn.message()));
        return m_renderer->aov();
    }

private Q_SLOTS:
    void initTestCase() {
        auto made = kwtest::offscreenRenderer(QSize(200, 150), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }

    void sameAovAfterRoundTrip_data() {
        QTest::addColumn<QString>("source");
        for (const char* s : {"sphere", "torus", "screw.step", "Pump_Nut.brep", "hammer.iges"})
            QTest::newRow(s) << QString::fromLatin1(s);
    }
    void sameAovAfterRoundTrip() {
        QFETCH(QString, source);
        Scene before;
        if (source.contains(QLatin1Char('.'))) {
            const auto r = importFile(QStringLiteral(KW_TEST_DATA_DIR "/") + source);
            QVERIFY2(r, qPrintable(r.message()));
            before = r->scene;
        } else {
            before = created(source);
        }
        const QString path = kwtest::outputDir().filePath(
            QStringLiteral("exchange_") +
            QString(source).replace(QLatin1Char('.'), QLatin1Char('_')) + QStringLiteral(".step"));
        ExportReport report;
        KW_VERIFY_OK(exportCadFile(before, path, {}, report));
        const auto after = importFile(path);
        QVERIFY2(after, qPrintable(after.message()));
        const QHash<std::uint32_t, std::uint32_t> ids = mapIds(before, after->scene);
        QCOMPARE(ids.size(), qsizetype(before.surfaces.size()));

        const Camera camera = fitCamera(before, 200.0 / 150.0);
        const AovBuffer a = render(before, camera), b = render(after->scene, camera);
        glm::dvec3 lo, hi;
        sceneBounds(before, lo, hi);
        const double diagonal = glm::length(hi - lo);
        int covered = 0, differ = 0, far = 0;
        double worst = 0.0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x) {
                const float *p = a.pixel(x, y), *q = b.pixel(x, y);
                if (p[0] < 0 && q[0] < 0)
                    continue;
                ++covered;
                if (p[0] < 0 || q[0] < 0 || ids.value(std::uint32_t(p[0])) != std::uint32_t(q[0])) {
                    ++differ;
                    continue;
                }
                const double d =
                    glm::length(glm::vec3(p[3], p[4], p[5]) - glm::vec3(q[3], q[4], q[5]));
                worst = std::max(worst, d);
                far += d > 1e-6 * diagonal ? 1 : 0;
            }
        qInfo("%s: %d covered pixels, %d differ, largest point difference %.3g of the diagonal, "
              "%d beyond 1e-6",
              qPrintable(source), covered, differ, worst / diagonal, far);
        QVERIFY(covered > 1000);
        // Pixels whose centre lies on a trim's edge may fall either side: the trims are the same
        // curves, read back through the file's p-curves (docs/EXCHANGE.md, Limits).
        QVERIFY2(differ <= covered / 200, qPrintable(QString::number(differ)));
        // The same point to 1e-6 of the diagonal on every pixel, except on screw.step: one of
        // its edges has sides 3e-4 apart with p-curves out of step, and SameParameter gives
        // one face an approximated trim there; the exact pass starts from the trimmed base
        // polygon and stops within its own tolerance, so 1.5 % of its pixels land up to 2e-6
        // of the diagonal away (docs/EXCHANGE.md, Limits).
        const bool screw = source == QLatin1String("screw.step");
        QVERIFY2(far <= (screw ? covered / 40 : 0), qPrintable(QString::number(far)));
        QVERIFY2(worst <= (screw ? 5e-6 : 1e-6) * diagonal,
                 qPrintable(QString::number(worst / diagonal)));
    }
};

QTEST_MAIN(TestRenderExchange)
#include "tst_render_exchange.moc"
