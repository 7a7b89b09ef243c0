// Helpers shared by every subcommand of the knotwork executables (see app/commands.h).
#include "app/commands.h"
#include "model/io/safetext.h"

#include <QCommandLineParser>
#include <cstdio>

namespace kw::cli {

void printError(const QString& line) {
    // The last guard for text from files and libraries: no byte that steers the terminal.
    std::fprintf(stderr, "%s\n", safeMessageText(line, true).toLocal8Bit().constData());
    std::fflush(stderr);
}

void printOut(const QString& text) {
    std::fputs(text.toUtf8().constData(), stdout);
    std::fflush(stdout);
}

int parseOrExit(QCommandLineParser& parser, const QStringList& args) {
    const QCommandLineOption help = parser.addHelpOption();
    if (!parser.parse(args)) {
        printError(QStringLiteral("%1: %2 (see --help)").arg(args.value(0), parser.errorText()));
        return kExitUsage;
    }
    if (parser.isSet(help) || parser.isSet(QStringLiteral("help-all"))) {
        // Qt names the binary's full path in the usage line; show the subcommand instead.
        QString text = parser.helpText();
        const qsizetype eol = text.indexOf(QLatin1Char('\n'));
        const QString usage = text.left(eol);
        text = QStringLiteral("Usage: %1%2")
                   .arg(args.value(0), usage.mid(usage.indexOf(QLatin1Char(' '), 7))) +
               text.mid(eol);
        printOut(text);
        return kExitOk;
    }
    return -1;
}

QString fullPrecision(double value) {
    // C's printf, not QString::asprintf, which drops the sign of -0.0.
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", value);
    return QString::fromLatin1(buf);
}

void printImportRemarks(const QString& file, const ImportReport& report) {
    if (report.facesSkipped() > 0)
        printError(QStringLiteral("%1: %2 face(s) skipped, %3 imported")
                       .arg(file)
                       .arg(report.facesSkipped())
                       .arg(report.facesImported));
    for (const QString& s : report.skipped)
        printError(QStringLiteral("%1: skipped: %2").arg(file, s));
    for (const QString& w : report.warnings)
        printError(QStringLiteral("%1: warning: %2").arg(file, w));
}

} // namespace kw::cli
