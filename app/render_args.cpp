// Options and loading shared by the render and bench subcommands.
#include "app/render_args.h"

#include "app/commands.h"
#include "render/trim_grid.h"

#include <QCommandLineParser>
#include <QStringList>
#include <cmath>
#include <utility>

namespace kw::cli {

bool parseIntIn(const QString& text, int lo, int hi, int& value) {
    bool ok = false;
    const int v = text.trimmed().toInt(&ok);
    if (!ok || v < lo || v > hi)
        return false;
    value = v;
    return true;
}

bool parseImageSize(const QString& text, QSize& size) {
    const QStringList parts = text.toLower().split(QLatin1Char('x'));
    int w = 0, h = 0;
    if (parts.size() != 2 || !parseIntIn(parts[0], 1, 16384, w) ||
        !parseIntIn(parts[1], 1, 16384, h))
        return false;
    size = QSize(w, h);
    return true;
}

bool parsePartitions(const QString& text, int& nu, int& nv) {
    const QStringList parts = text.toLower().split(QLatin1Char('x'));
    if (parts.size() == 1)
        return parseIntIn(parts[0], kMinPartitions, kMaxPartitions, nu) &&
               parseIntIn(parts[0], kMinPartitions, kMaxPartitions, nv);
    return parts.size() == 2 && parseIntIn(parts[0], kMinPartitions, kMaxPartitions, nu) &&
           parseIntIn(parts[1], kMinPartitions, kMaxPartitions, nv);
}

QString modeName(RenderMode mode) {
    return mode == RenderMode::Exact ? QStringLiteral("exact") : QStringLiteral("tessellated");
}

QString shadingName(RenderOptions::Shading shading) {
    return shading == RenderOptions::Shading::ExactDepth ? QStringLiteral("exact-depth")
                                                         : QStringLiteral("prepass");
}

namespace {

/// "A,B,..." as exactly `count` finite numbers.
bool parseNumbers(const QString& text, int count, double* out) {
    const QStringList parts = text.split(QLatin1Char(','));
    if (parts.size() != count)
        return false;
    for (int k = 0; k < count; ++k) {
        bool ok = false;
        out[k] = parts[k].trimmed().toDouble(&ok);
        if (!ok || !std::isfinite(out[k]))
            return false;
    }
    return true;
}

bool parseNumberIn(const QString& text, double lo, double hi, double& value) {
    double x = 0.0;
    if (!parseNumbers(text, 1, &x) || x < lo || x > hi)
        return false;
    value = x;
    return true;
}

template <typename Fail>
bool readAnalysisOptions(const QCommandLineParser& parser, const RenderCliOptions& o,
                         const Fail& fail, AnalysisOptions& a) {
    const QString mode = parser.value(o.shading);
    if (mode == QLatin1String("isocurves")) {
        a.mode = AnalysisMode::Phong;
        a.isocurves = true;
    } else if (const std::optional<AnalysisMode> m = parseAnalysisMode(mode)) {
        a.mode = *m;
    } else {
        return fail(o.shading, analysisModeNames().join(QStringLiteral(", ")) +
                                   QStringLiteral(" or isocurves"));
    }
    a.isocurves = a.isocurves || parser.isSet(o.isocurves);
    a.principalDirections = parser.isSet(o.directions);
    int nu = 0, nv = 0;
    const QStringList iso = parser.value(o.isoLines).toLower().split(QLatin1Char('x'));
    if (iso.size() > 2 || !parseIntIn(iso[0], 0, 1000, nu) ||
        !parseIntIn(iso.value(iso.size() - 1), 0, 1000, nv))
        return fail(o.isoLines, QStringLiteral("N or NxM with 0..1000"));
    a.isoCount = glm::ivec2(nu, nv);
    if (parser.isSet(o.range)) {
        double r[2];
        if (!parseNumbers(parser.value(o.range), 2, r) || !(r[1] > r[0]))
            return fail(o.range, QStringLiteral("LOW,HIGH with LOW < HIGH"));
        a.range = ValueRange{r[0], r[1]};
    }
    if (parser.isSet(o.scale)) {
        a.scale = parseColourScale(parser.value(o.scale));
        if (!a.scale)
            return fail(o.scale, QStringLiteral("linear, symmetric or log"));
    }
    if (!parseNumberIn(parser.value(o.stripes), 0.5, 1000.0, a.stripeCount))
        return fail(o.stripes, QStringLiteral("a number in 0.5..1000"));
    if (!parseNumberIn(parser.value(o.stripeAngle), -360.0, 360.0, a.stripeAngleDegrees))
        return fail(o.stripeAngle, QStringLiteral("an angle in -360..360"));
    if (!parseNumberIn(parser.value(o.isophoteBands), 1.0, 1000.0, a.isophoteCount))
        return fail(o.isophoteBands, QStringLiteral("a number in 1..1000"));
    double pull[3];
    if (!parseNumbers(parser.value(o.pull), 3, pull) ||
        !(glm::length(glm::dvec3(pull[0], pull[1], pull[2])) > 0.0))
        return fail(o.pull, QStringLiteral("a non-zero vector X,Y,Z"));
    a.pullDirection = glm::dvec3(pull[0], pull[1], pull[2]);
    if (!parseNumberIn(parser.value(o.draftAngle), 0.0, 90.0, a.draftAngleDegrees))
        return fail(o.draftAngle, QStringLiteral("an angle in 0..90"));
    a.environmentMap = parser.value(o.envMap);
    return true;
}

} // namespace

Expected<SectionPlane> parseSectionPlane(const QString& text) {
    double v[6];
    if (!parseNumbers(text, 6, v))
        return Error(QStringLiteral("six numbers X,Y,Z,NX,NY,NZ"));
    const SectionPlane plane{glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5]), false};
    if (Status valid = checkSectionPlane(plane); !valid)
        return Error(QStringLiteral("a plane: ") +
                     valid.message().section(QStringLiteral("section plane's "), -1));
    return plane;
}

int trimGridCapForImage(QSize size, double zoom) {
    const double side = double(std::max(size.width(), size.height())) * std::max(zoom, 1.0) /
                        kImagePixelsPerTrimTexel;
    int cap = kMinTrimGridSize;
    while (cap < kMaxTrimGridSide && cap < side)
        cap *= 2;
    return cap;
}

QString partitioningName(RenderOptions::Partitioning p) {
    return p == RenderOptions::Partitioning::Adaptive ? QStringLiteral("adaptive")
                                                      : QStringLiteral("uniform");
}

RenderCliOptions addRenderOptions(QCommandLineParser& parser, const QString& defaultPartitions,
                                  const QString& defaultPartitioning) {
    RenderCliOptions o{
        QCommandLineOption(QStringLiteral("mode"),
                           QStringLiteral("exact (default) or tessellated."),
                           QStringLiteral("MODE"), QStringLiteral("exact")),
        QCommandLineOption(QStringLiteral("partitions"),
                           defaultPartitions.isEmpty()
                               ? QStringLiteral("Partitions N or NxM for every surface (default: "
                                                "each surface's own).")
                               : QStringLiteral("Partitions N or NxM for every surface (default "
                                                "%1).")
                                     .arg(defaultPartitions),
                           QStringLiteral("N|NxM"), defaultPartitions),
        QCommandLineOption(
            QStringLiteral("partition-mode"),
            QStringLiteral("adaptive: per surface and view, the fewest partitions (at least the "
                           "surface's own or --partitions) that keep the base polygon within "
                           "--pixel-tolerance of the exact surface on screen, by a guaranteed "
                           "bound; uniform: the surface's own or --partitions, as the paper "
                           "(default %1).")
                .arg(defaultPartitioning),
            QStringLiteral("MODE"), defaultPartitioning),
        QCommandLineOption(QStringLiteral("pixel-tolerance"),
                           QStringLiteral("Adaptive partitions: screen distance in pixels, %1..%2 "
                                          "(default 0.5).")
                               .arg(kMinPixelTolerance)
                               .arg(kMaxPixelTolerance),
                           QStringLiteral("PX"), QStringLiteral("0.5")),
        QCommandLineOption(QStringLiteral("lights"),
                           QStringLiteral("Number of lights, 1..%1 (default 2).").arg(kMaxLights),
                           QStringLiteral("N"), QStringLiteral("2")),
        QCommandLineOption(QStringLiteral("depth"),
                           QStringLiteral("Exact mode visibility: prepass (default: depth pre-pass "
                                          "+ GL_EQUAL) or exact-depth (one pass writing "
                                          "gl_FragDepth)."),
                           QStringLiteral("WAY"), QStringLiteral("prepass")),
        QCommandLineOption(QStringLiteral("no-trims"),
                           QStringLiteral("Draw trimmed surfaces over their whole domains (trims "
                                          "are cut by default).")),
        QCommandLineOption(QStringLiteral("trim-mask-cap"),
                           QStringLiteral("Largest trim mask side in texels, %1..16384 (default "
                                          "%2); each mask follows its surface's size on screen "
                                          "up to this.")
                               .arg(kMinTrimMaskSize)
                               .arg(kDefaultTrimMaskCap),
                           QStringLiteral("N"), QString::number(kDefaultTrimMaskCap)),
        QCommandLineOption(QStringLiteral("trim-mode"),
                           QStringLiteral("exact (default: trim edges exact at any zoom, by each "
                                          "surface's trim grid) or mask (the paper's trim mask "
                                          "alone, accurate to its texels: --trim-mask-cap)."),
                           QStringLiteral("MODE"), QStringLiteral("exact")),
        QCommandLineOption(QStringLiteral("trim-budget"),
                           QStringLiteral("GPU memory for exact trims in MiB, 1..%1 (default %2); "
                                          "past it the trim grids get coarser: slower, never "
                                          "wrong, with a warning.")
                               .arg(kMaxTrimBudgetBytes >> 20)
                               .arg(kDefaultTrimBudgetBytes >> 20),
                           QStringLiteral("MIB"), QString::number(kDefaultTrimBudgetBytes >> 20)),
        QCommandLineOption(QStringLiteral("samples"),
                           QStringLiteral("Anti-aliasing: samples per pixel, 1..%1 (default 1, "
                                          "aliased); how, --aa-method.")
                               .arg(kMaxSamples),
                           QStringLiteral("N"), QStringLiteral("1")),
        QCommandLineOption(QStringLiteral("aa-method"),
                           QStringLiteral("With --samples N > 1: accumulate (default: N whole "
                                          "frames, each shifted by a sub-pixel offset, averaged; "
                                          "seams between faces stay closed) or coverage (N MSAA "
                                          "samples, trim edges covered by their exact distance; "
                                          "at most what the GPU allows)."),
                           QStringLiteral("METHOD"), QStringLiteral("accumulate")),
        QCommandLineOption(QStringLiteral("background"),
                           QStringLiteral("dark (default: flat dark grey) or light (a light "
                                          "grey-blue gradient, brighter at the top, as CAD "
                                          "viewers offer); default the project's."),
                           QStringLiteral("NAME"), QStringLiteral("dark")),
        QCommandLineOption(QStringLiteral("shading"),
                           QStringLiteral("Exact mode colouring: %1 (default), %2, or isocurves "
                                          "(phong with --isocurves).")
                               .arg(analysisModeNames().first(),
                                    analysisModeNames().mid(1).join(QStringLiteral(", "))),
                           QStringLiteral("MODE"), QStringLiteral("phong")),
        QCommandLineOption(QStringLiteral("isocurves"),
                           QStringLiteral("Overlay knot lines and iso-parameter lines on any "
                                          "--shading mode.")),
        QCommandLineOption(QStringLiteral("iso-lines"),
                           QStringLiteral("Iso-parameter lines per direction, N or NxM, 0..1000 "
                                          "(default 8): at i/(N+1) of each domain."),
                           QStringLiteral("N|NxM"), QStringLiteral("8")),
        QCommandLineOption(QStringLiteral("range"),
                           QStringLiteral("Colour maps: value range LOW,HIGH (default: the "
                                          "10th to 90th percentile of the area)."),
                           QStringLiteral("LOW,HIGH")),
        QCommandLineOption(QStringLiteral("scale"),
                           QStringLiteral("Colour maps: linear, symmetric (0 in the middle) or "
                                          "log (signed); default symmetric for gaussian and "
                                          "mean, linear otherwise."),
                           QStringLiteral("SCALE")),
        QCommandLineOption(QStringLiteral("stripes"),
                           QStringLiteral("Zebra: stripe pairs per 180 degrees of reflection, "
                                          "drawn to the nearest 0.5 (default 8)."),
                           QStringLiteral("N"), QStringLiteral("8")),
        QCommandLineOption(QStringLiteral("stripe-angle"),
                           QStringLiteral("Zebra: stripe direction in the view plane in degrees "
                                          "(0 horizontal, default 90 vertical)."),
                           QStringLiteral("DEG"), QStringLiteral("90")),
        QCommandLineOption(QStringLiteral("isophote-bands"),
                           QStringLiteral("Isophotes: bands across N.L (default 10)."),
                           QStringLiteral("N"), QStringLiteral("10")),
        QCommandLineOption(QStringLiteral("pull"),
                           QStringLiteral("Draft: pull direction X,Y,Z (default 0,0,1)."),
                           QStringLiteral("X,Y,Z"), QStringLiteral("0,0,1")),
        QCommandLineOption(QStringLiteral("draft-angle"),
                           QStringLiteral("Draft: threshold angle in degrees, 0..90 (default 3)."),
                           QStringLiteral("DEG"), QStringLiteral("3")),
        QCommandLineOption(QStringLiteral("env-map"),
                           QStringLiteral("Environment: equirectangular image (EXR, HDR, PNG, "
                                          "JPEG, TIFF...; default the bundled studio)."),
                           QStringLiteral("IMAGE")),
        QCommandLineOption(QStringLiteral("principal-directions"),
                           QStringLiteral("Overlay short marks of the principal curvature "
                                          "directions (k1 red, k2 blue) on any --shading mode."))};
    parser.addOptions({o.mode,    o.partitions, o.partitionMode, o.pixelTolerance, o.lights,
                       o.depth,   o.noTrims,    o.trimMaskCap,   o.trimMode,       o.trimBudget,
                       o.samples, o.aaMethod,   o.shading,       o.isocurves,      o.isoLines,
                       o.range,   o.scale,      o.stripes,       o.stripeAngle,    o.isophoteBands,
                       o.pull,    o.draftAngle, o.envMap,        o.directions});
    o.section = QCommandLineOption(
        QStringLiteral("section"),
        QStringLiteral("A section plane through X,Y,Z removing the side its normal NX,NY,NZ "
                       "points to, cut at each pixel's exact point; up to %1 (repeat the "
                       "option). Default the project's.")
            .arg(kMaxSectionPlanes),
        QStringLiteral("X,Y,Z,NX,NY,NZ"));
    o.noCaps = QCommandLineOption(QStringLiteral("no-caps"),
                                  QStringLiteral("With sections: no caps on cut closed solids."));
    parser.addOption(o.background);
    parser.addOption(o.section);
    parser.addOption(o.noCaps);
    o.noAnalytic = QCommandLineOption(
        QStringLiteral("no-analytic"),
        QStringLiteral("Shade faces that kept their source's analytic form (plane, cylinder, "
                       "cone, sphere, torus) by the Newton step onto their NURBS, not in closed "
                       "form: the same image, for comparing costs."));
    parser.addOption(o.noAnalytic);
    return o;
}

bool readRenderOptions(const QCommandLineParser& parser, const RenderCliOptions& o,
                       const QString& cmd, RenderOptions& options) {
    auto fail = [&](const QCommandLineOption& opt, const QString& expected) {
        printError(QStringLiteral("%1: --%2 '%3' is not %4")
                       .arg(cmd, opt.names().constFirst(), parser.value(opt), expected));
        return false;
    };
    const QString mode = parser.value(o.mode);
    if (mode == QLatin1String("exact"))
        options.mode = RenderMode::Exact;
    else if (mode == QLatin1String("tessellated"))
        options.mode = RenderMode::Tessellated;
    else
        return fail(o.mode, QStringLiteral("exact or tessellated"));
    if (!parser.value(o.partitions).isEmpty() &&
        !parsePartitions(parser.value(o.partitions), options.partitionsU, options.partitionsV))
        return fail(o.partitions,
                    QStringLiteral("N or NxM with %1..%2").arg(kMinPartitions).arg(kMaxPartitions));
    const QString partitioning = parser.value(o.partitionMode);
    if (partitioning == partitioningName(RenderOptions::Partitioning::Adaptive))
        options.partitioning = RenderOptions::Partitioning::Adaptive;
    else if (partitioning == partitioningName(RenderOptions::Partitioning::Uniform))
        options.partitioning = RenderOptions::Partitioning::Uniform;
    else
        return fail(o.partitionMode, QStringLiteral("adaptive or uniform"));
    bool toleranceOk = false;
    options.pixelTolerance = parser.value(o.pixelTolerance).toDouble(&toleranceOk);
    if (!toleranceOk || !(options.pixelTolerance >= kMinPixelTolerance) ||
        !(options.pixelTolerance <= kMaxPixelTolerance))
        return fail(
            o.pixelTolerance,
            QStringLiteral("a number in %1..%2").arg(kMinPixelTolerance).arg(kMaxPixelTolerance));
    if (!parseIntIn(parser.value(o.lights), 1, kMaxLights, options.lightCount))
        return fail(o.lights, QStringLiteral("in 1..%1").arg(kMaxLights));
    const QString depth = parser.value(o.depth);
    if (depth == shadingName(RenderOptions::Shading::DepthPrepass))
        options.shading = RenderOptions::Shading::DepthPrepass;
    else if (depth == shadingName(RenderOptions::Shading::ExactDepth))
        options.shading = RenderOptions::Shading::ExactDepth;
    else
        return fail(o.depth, QStringLiteral("prepass or exact-depth"));
    if (!readAnalysisOptions(parser, o, fail, options.analysis))
        return false;
    if (!parseIntIn(parser.value(o.trimMaskCap), kMinTrimMaskSize, 16384, options.trimMaskCap))
        return fail(o.trimMaskCap, QStringLiteral("in %1..16384").arg(kMinTrimMaskSize));
    options.trims = !parser.isSet(o.noTrims);
    const std::optional<RenderOptions::TrimMode> trimMode = trimModeNamed(parser.value(o.trimMode));
    if (!trimMode)
        return fail(o.trimMode, QStringLiteral("exact or mask"));
    options.trimMode = *trimMode;
    int budgetMiB = 0;
    if (!parseIntIn(parser.value(o.trimBudget), 1, int(kMaxTrimBudgetBytes >> 20), budgetMiB))
        return fail(o.trimBudget, QStringLiteral("in 1..%1").arg(kMaxTrimBudgetBytes >> 20));
    options.trimBudgetBytes = std::int64_t(budgetMiB) << 20;
    if (!parseIntIn(parser.value(o.samples), 1, kMaxSamples, options.samples))
        return fail(o.samples, QStringLiteral("in 1..%1").arg(kMaxSamples));
    const std::optional<RenderOptions::Antialiasing> aaMethod =
        antialiasingNamed(parser.value(o.aaMethod));
    if (!aaMethod)
        return fail(o.aaMethod, QStringLiteral("accumulate or coverage"));
    options.antialiasing = *aaMethod;
    if (!backgroundNamed(parser.value(o.background), options))
        return fail(o.background, QStringLiteral("dark or light"));
    const QStringList sections = parser.values(o.section);
    if (sections.size() > kMaxSectionPlanes) {
        printError(QStringLiteral("%1: --section given %2 times, at most %3")
                       .arg(cmd)
                       .arg(sections.size())
                       .arg(kMaxSectionPlanes));
        return false;
    }
    options.sections.clear();
    for (const QString& text : sections) {
        const Expected<SectionPlane> plane = parseSectionPlane(text);
        if (!plane) {
            printError(
                QStringLiteral("%1: --section '%2' is not %3").arg(cmd, text, plane.message()));
            return false;
        }
        options.sections.push_back(*plane);
    }
    options.sectionCaps = !parser.isSet(o.noCaps);
    options.analyticFaces = !parser.isSet(o.noAnalytic);
    options.polygonOverTrims = options.trims; // --no-trims shows the whole domains
    return readDevelopmentSwitches(cmd, options);
}

bool readDevelopmentSwitches(const QString& cmd, RenderOptions& options) {
    const auto off = [](const char* name, const char* value = "0") {
        return qEnvironmentVariable(name) == QLatin1String(value);
    };
    // Same pixels, different cost: the trimmed-cell split (## Trims), closed solids' back
    // faces skipped, affine surfaces without the Newton step, the multi-draw, the deferred pass.
    options.splitCellsByTrims = !off("KW_TRIM_CELL_SPLIT");
    options.splitCellsBySections = !off("KW_SECTION_CELL_SPLIT"); // ## Section planes
    options.skipBackFaces = !off("KW_BACK_FACES", "1");
    options.affineWithoutNewton = !off("KW_AFFINE");
    options.multiDraw = !off("KW_MULTI_DRAW");
    options.deferredPass = options.deferredPass && !off("KW_DEFERRED");
    // The edge skirts and their silhouette fins (## Edges): cracks and cost.
    options.edgeSkirts = !off("KW_EDGE_SKIRTS");
    options.silhouetteFins = !off("KW_FINS");
    // Base polygons of every cell, not only those in view (## Close-up): memory and cost.
    options.polygonsInView = !off("KW_POLYGONS_IN_VIEW");
    // Thresholds of the per-cell gather and of the deferred pass's forward surfaces.
    for (const auto& [name, value] :
         {std::pair{"KW_GATHER_MIN_CELL_PX", &options.gatherMinCellPixels},
          std::pair{"KW_DEFER_MAX_CELL_PX", &options.deferMaxCellPixels},
          std::pair{"KW_COVER_MIN_CELLS", &options.coverMinCells}}) {
        if (!qEnvironmentVariableIsSet(name))
            continue;
        bool ok = false;
        const double v = qEnvironmentVariable(name).toDouble(&ok);
        if (!ok || !(v >= 0.0)) {
            printError(QStringLiteral("%1: %2 '%3' is not a number >= 0")
                           .arg(cmd, QLatin1String(name), qEnvironmentVariable(name)));
            return false;
        }
        *value = v;
    }
    return true;
}

} // namespace kw::cli
