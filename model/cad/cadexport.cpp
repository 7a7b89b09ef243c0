// CAD export's report and options (the writing itself: occtexport.cpp in the child,
// exportCadFile in cadprocess.cpp for the parent).
#include "model/cad/cadexport.h"

#include <cmath>

namespace kw {

QString ExportReport::summary() const {
    QString out = QStringLiteral("%1 face(s) written: %2 solid(s), %3 open shell(s), %4 loose "
                                 "face(s), %5 free edge(s), %6 s (OpenCASCADE's writer %7 s)\n")
                      .arg(faces)
                      .arg(solids)
                      .arg(openShells)
                      .arg(looseFaces)
                      .arg(freeEdges)
                      .arg(seconds, 0, 'f', 3)
                      .arg(writerSeconds, 0, 'f', 3);
    for (const QString& w : warnings)
        out += QStringLiteral("warning: ") + w + QLatin1Char('\n');
    return out;
}

QByteArray ExportReport::toText() const {
    QByteArray out = "counts " + QByteArray::number(faces) + ' ' + QByteArray::number(solids) +
                     ' ' + QByteArray::number(openShells) + ' ' + QByteArray::number(looseFaces) +
                     ' ' + QByteArray::number(freeEdges) + ' ' +
                     QByteArray::number(seconds, 'g', 17) + ' ' +
                     QByteArray::number(writerSeconds, 'g', 17) + '\n';
    for (QString w : warnings)
        out += "warning " + w.replace(QLatin1Char('\n'), QLatin1Char(' ')).toUtf8() + '\n';
    return out;
}

bool ExportReport::fromText(const QByteArray& text) {
    *this = ExportReport{};
    const QList<QByteArray> lines = text.split('\n');
    if (lines.isEmpty() || !lines.front().startsWith("counts "))
        return false;
    const QList<QByteArray> c = lines.front().split(' ');
    if (c.size() != 8)
        return false;
    bool ok[7] = {};
    faces = c[1].toInt(&ok[0]);
    solids = c[2].toInt(&ok[1]);
    openShells = c[3].toInt(&ok[2]);
    looseFaces = c[4].toInt(&ok[3]);
    freeEdges = c[5].toInt(&ok[4]);
    seconds = c[6].toDouble(&ok[5]);
    writerSeconds = c[7].toDouble(&ok[6]);
    for (bool b : ok)
        if (!b)
            return false;
    for (qsizetype k = 1; k < lines.size(); ++k) {
        if (lines[k].isEmpty())
            continue;
        if (!lines[k].startsWith("warning "))
            return false;
        warnings << QString::fromUtf8(lines[k].mid(8));
    }
    return true;
}

static QString exportOptionsReason(const ExportOptions& options) {
    if (options.stepSchema != QLatin1String("ap203") &&
        options.stepSchema != QLatin1String("ap214") &&
        options.stepSchema != QLatin1String("ap242"))
        return QStringLiteral("unknown STEP schema '%1' (expected ap203, ap214 or ap242)")
            .arg(options.stepSchema);
    if (!(options.tolerance >= 0.0) || !std::isfinite(options.tolerance))
        return QStringLiteral("the tolerance must be a finite number >= 0");
    return {};
}

Status checkExportOptions(const ExportOptions& options) {
    if (const QString why = exportOptionsReason(options); !why.isEmpty())
        return Error(why);
    return ok();
}

} // namespace kw
