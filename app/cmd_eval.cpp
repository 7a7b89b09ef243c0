// knotwork eval FILE --surface ID --uv U,V [--json]: point, partials and unit normal at (u, v).
#include "app/commands.h"
#include "model/io/knotfile.h"

#include <QCommandLineParser>
#include <QJsonArray>
#include <QJsonDocument>
#include <cmath>

namespace kw::cli {

namespace {

/// Parses "U,V" into two finite numbers; false when malformed.
bool parseUv(const QString& text, double& u, double& v) {
    const QStringList parts = text.split(QLatin1Char(','));
    if (parts.size() != 2)
        return false;
    bool okU = false, okV = false;
    u = parts[0].trimmed().toDouble(&okU);
    v = parts[1].trimmed().toDouble(&okV);
    return okU && okV && std::isfinite(u) && std::isfinite(v);
}

/// The surface whose id is `key` (a decimal number) or, failing that, whose name is `key`.
/// nullptr with *error set when there is none or the name is ambiguous.
const Surface* findSurface(const Scene& scene, const QString& key, QString* error) {
    bool isNumber = false;
    const uint id = key.toUInt(&isNumber);
    if (isNumber)
        for (const Surface& s : scene.surfaces)
            if (s.id.value == id)
                return &s;
    const Surface* found = nullptr;
    QStringList ids;
    for (const Surface& s : scene.surfaces)
        if (s.name == key) {
            found = found ? found : &s;
            ids << QString::number(s.id.value);
        }
    if (ids.size() > 1) {
        *error = QStringLiteral("surface name \"%1\" is ambiguous (ids %2); give the id")
                     .arg(key, ids.join(QStringLiteral(", ")));
        return nullptr;
    }
    if (!found)
        *error = QStringLiteral("no surface has the id or name \"%1\"").arg(key);
    return found;
}

QString vecText(const glm::dvec3& p) {
    return QStringLiteral("%1 %2 %3")
        .arg(fullPrecision(p.x), fullPrecision(p.y), fullPrecision(p.z));
}

QString vecJson(const glm::dvec3& p) {
    return QStringLiteral("[%1, %2, %3]")
        .arg(fullPrecision(p.x), fullPrecision(p.y), fullPrecision(p.z));
}

/// A JSON string literal, escaped by QJsonDocument.
QString jsonString(const QString& text) {
    const QByteArray a = QJsonDocument(QJsonArray{text}).toJson(QJsonDocument::Compact);
    return QString::fromUtf8(a.mid(1, a.size() - 2)); // strip the [ ]
}

QString domainText(const Interval& d) {
    return QStringLiteral("[%1, %2]").arg(fullPrecision(d.first), fullPrecision(d.last));
}

} // namespace

int runEval(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral(
        "Evaluate one surface at (u, v): the point S, the partials dS/du and dS/dv and the unit "
        "normal (kw::surfaceFrame), printed with 17 significant digits."));
    const QCommandLineOption surfaceOpt(QStringLiteral("surface"),
                                        QStringLiteral("The surface's id or name."),
                                        QStringLiteral("ID"));
    const QCommandLineOption uvOpt(QStringLiteral("uv"),
                                   QStringLiteral("Parameters inside the surface's domain."),
                                   QStringLiteral("U,V"));
    const QCommandLineOption json(QStringLiteral("json"), QStringLiteral("Print JSON."));
    parser.addOptions({surfaceOpt, uvOpt, json});
    parser.addPositionalArgument(QStringLiteral("FILE"), QStringLiteral("A .knot project."));
    if (const int code = parseOrExit(parser, args); code >= 0)
        return code;
    const QString me = args.value(0);
    const QStringList files = parser.positionalArguments();
    if (files.size() != 1) {
        printError(
            QStringLiteral("%1: expected one FILE, got %2 (see --help)").arg(me).arg(files.size()));
        return kExitUsage;
    }
    if (!parser.isSet(surfaceOpt) || !parser.isSet(uvOpt)) {
        printError(
            QStringLiteral("%1: --surface ID and --uv U,V are required (see --help)").arg(me));
        return kExitUsage;
    }
    double u = 0.0, v = 0.0;
    if (!parseUv(parser.value(uvOpt), u, v)) {
        printError(QStringLiteral("%1: --uv expects two finite numbers 'U,V', got '%2'")
                       .arg(me, parser.value(uvOpt)));
        return kExitUsage;
    }

    const QString file = files[0];
    QString error;
    const Expected<Scene> scene = readKnotFile(file);
    if (!scene) {
        printError(scene.message());
        return kExitBadInput;
    }
    const Surface* surface = findSurface(*scene, parser.value(surfaceOpt), &error);
    if (!surface) {
        printError(QStringLiteral("%1: %2").arg(file, error));
        return kExitBadInput;
    }
    const NurbsSurface& g = surface->geometry;
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    const QString who =
        QStringLiteral("surface %1 \"%2\"").arg(surface->id.value).arg(surface->name);
    if (!(u >= du.first && u <= du.last) || !(v >= dv.first && v <= dv.last)) {
        printError(
            QStringLiteral("%1: %2: (u, v) = (%3, %4) is outside the domain u in %5, v in %6")
                .arg(file, who, fullPrecision(u), fullPrecision(v), domainText(du),
                     domainText(dv)));
        return kExitBadInput;
    }

    const SurfaceFrame f = surfaceFrame(g, u, v);
    if (parser.isSet(json)) {
        // Numbers by hand so that every one has 17 significant digits.
        QString out = QStringLiteral("{\"file\": %1, \"surface\": %2, \"name\": %3,\n")
                          .arg(jsonString(file))
                          .arg(surface->id.value)
                          .arg(jsonString(surface->name));
        out += QStringLiteral(" \"u\": %1, \"v\": %2,\n").arg(fullPrecision(u), fullPrecision(v));
        out += QStringLiteral(" \"point\": %1,\n \"du\": %2,\n \"dv\": %3,\n \"normal\": %4}\n")
                   .arg(vecJson(f.point), vecJson(f.du), vecJson(f.dv), vecJson(f.normal));
        printOut(out);
    } else {
        printOut(
            QStringLiteral("%1 at (u, v) = (%2, %3)\npoint  %4\ndu     %5\ndv     %6\nnormal %7\n")
                .arg(who, fullPrecision(u), fullPrecision(v), vecText(f.point), vecText(f.du),
                     vecText(f.dv), vecText(f.normal)));
    }
    return kExitOk;
}

} // namespace kw::cli
