// Parsing of render options for the render and bench subcommands.
#include "app/render_args.h"

#include "model/scene.h"

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

bool parseMode(const QString& text, RenderMode& mode) {
    if (text == QLatin1String("exact"))
        mode = RenderMode::Exact;
    else if (text == QLatin1String("tessellated"))
        mode = RenderMode::Tessellated;
    else
        return false;
    return true;
}

QString modeName(RenderMode mode) {
    return mode == RenderMode::Exact ? QStringLiteral("exact") : QStringLiteral("tessellated");
}

bool parseShading(const QString& text, RenderOptions::Shading& shading) {
    for (auto s : {RenderOptions::Shading::DepthPrepass, RenderOptions::Shading::ExactDepth})
        if (text == shadingName(s)) {
            shading = s;
            return true;
        }
    return false;
}

QString shadingName(RenderOptions::Shading shading) {
    switch (shading) {
    case RenderOptions::Shading::DepthPrepass:
        return QStringLiteral("prepass");
    case RenderOptions::Shading::ExactDepth:
        return QStringLiteral("exact-depth");
    }
    return {};
}

} // namespace kw::cli
