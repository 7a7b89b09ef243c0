// knotwork: entry point; dispatches to the editor or a command-line tool.
#include <QCommandLineParser>
#include <QCoreApplication>
#include <QTextStream>

int main(int argc, char** argv) {
    QCoreApplication app(argc, argv);
    QCoreApplication::setApplicationName(QStringLiteral("knotwork"));
    QCoreApplication::setApplicationVersion(QStringLiteral(KW_VERSION));
    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral("Knotwork NURBS surface editor"));
    parser.addHelpOption();
    parser.addVersionOption();
    parser.process(app);
    return 0;
}
