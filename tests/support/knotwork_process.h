// Runs the built `knotwork` binary for the tests of its subcommands (path: KW_KNOTWORK_BIN).
#pragma once

#include <QProcess>
#include <QProcessEnvironment>
#include <QString>
#include <QStringList>

struct Run {
    int code = -1; ///< exit code; -1 when the process crashed or did not finish in time
    QString out, err;
};

/// Runs knotwork with `args` in `env` and waits up to `timeoutMs` for it to finish.
inline Run knotwork(const QStringList& args,
                    const QProcessEnvironment& env = QProcessEnvironment::systemEnvironment(),
                    int timeoutMs = 300000) {
    QProcess p;
    p.setProcessEnvironment(env);
    p.start(QStringLiteral(KW_KNOTWORK_BIN), args);
    const bool finished = p.waitForFinished(timeoutMs);
    Run r;
    r.code = finished && p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1;
    r.out = QString::fromUtf8(p.readAllStandardOutput());
    r.err = QString::fromUtf8(p.readAllStandardError());
    return r;
}

/// The system environment with `name` set to `value`.
inline QProcessEnvironment environmentWith(const QString& name, const QString& value) {
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.insert(name, value);
    return env;
}
