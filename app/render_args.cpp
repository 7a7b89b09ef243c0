// Options and loading shared by the render and bench subcommands.
#include "app/render_args.h"

#include "app/commands.h"
#include "model/knotfile.h"

#include <QCommandLineParser>
#include <QStringList>

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

RenderCliOptions addRenderOptions(QCommandLineParser& parser, const QString& defaultPartitions) {
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
        QCommandLineOption(QStringLiteral("lights"),
                           QStringLiteral("Number of lights, 1..%1 (default 2).").arg(kMaxLights),
                           QStringLiteral("N"), QStringLiteral("2")),
        QCommandLineOption(QStringLiteral("shading"),
                           QStringLiteral("Exact mode: prepass (default: depth pre-pass + "
                                          "GL_EQUAL) or exact-depth (one pass writing "
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
                           QStringLiteral("N"), QString::number(kDefaultTrimMaskCap))};
    parser.addOptions({o.mode, o.partitions, o.lights, o.shading, o.noTrims, o.trimMaskCap});
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
    if (!parseIntIn(parser.value(o.lights), 1, kMaxLights, options.lightCount))
        return fail(o.lights, QStringLiteral("in 1..%1").arg(kMaxLights));
    const QString shading = parser.value(o.shading);
    if (shading == shadingName(RenderOptions::Shading::DepthPrepass))
        options.shading = RenderOptions::Shading::DepthPrepass;
    else if (shading == shadingName(RenderOptions::Shading::ExactDepth))
        options.shading = RenderOptions::Shading::ExactDepth;
    else
        return fail(o.shading, QStringLiteral("prepass or exact-depth"));
    if (!parseIntIn(parser.value(o.trimMaskCap), kMinTrimMaskSize, 16384, options.trimMaskCap))
        return fail(o.trimMaskCap, QStringLiteral("in %1..16384").arg(kMinTrimMaskSize));
    options.trims = !parser.isSet(o.noTrims);
    return true;
}

bool loadDocument(const QString& file, Document& doc) {
    QString error;
    const std::optional<Scene> scene = readKnotFile(file, &error);
    if (!scene) {
        printError(error);
        return false;
    }
    if (!doc.resetScene(*scene, &error)) {
        printError(QStringLiteral("%1: %2").arg(file, error));
        return false;
    }
    return true;
}

} // namespace kw::cli
