// The IGES numbering repair's quick check (model/cad/igesrepair.h): igesNumberingNeedsRepair
// answers as the full rebuild does, on the test files and on many damaged copies of them.
#include "model/cad/igesrepair.h"

#include <QFile>
#include <QRandomGenerator>
#include <QTest>

namespace {

QByteArray readData(const char* name) {
    QFile f(QStringLiteral(KW_TEST_DATA_DIR "/") + QLatin1String(name));
    if (!f.open(QIODevice::ReadOnly))
        qFatal("cannot read %s", name);
    return f.readAll();
}

bool sameAnswer(const QByteArray& file) {
    QString note;
    return kw::igesNumberingNeedsRepair(file) == kw::rebuildIgesNumbering(file, note).has_value();
}

// One damage of the kinds the repair looks at: a digit or space in a sequence, pointer or
// count column, a line cut short or removed, the Global section emptied, CRLF line ends.
QByteArray damaged(QByteArray file, QRandomGenerator& random) {
    QList<QByteArray> lines = file.split('\n');
    const int at = random.bounded(int(lines.size()));
    QByteArray& line = lines[at];
    switch (random.bounded(6)) {
    case 0:
    case 1: {
        static const int columns[] = {8, 12, 24, 28, 64, 70, 73, 76, 79};
        const int column = columns[random.bounded(int(std::size(columns)))];
        if (column < line.size())
            line[column] = random.bounded(3) == 0 ? ' ' : char('0' + random.bounded(10));
        break;
    }
    case 2:
        line.truncate(random.bounded(int(line.size()) + 1));
        break;
    case 3:
        lines.removeAt(at);
        break;
    case 4:
        for (QByteArray& l : lines)
            if (l.size() > 72 && l[72] == 'G')
                l.replace(0, 72, QByteArray(72, ' '));
        break;
    default:
        for (QByteArray& l : lines)
            l += '\r';
        break;
    }
    return lines.join('\n');
}

} // namespace

class TestIgesRepair : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void testFiles() {
        const QByteArray hammer = readData("hammer.iges");
        const QByteArray teapot = readData("teapot.igs");
        QVERIFY(!kw::igesNumberingNeedsRepair(hammer));
        QVERIFY(kw::igesNumberingNeedsRepair(teapot));
        QString note;
        QVERIFY(!kw::repairIgesNumbering(hammer, note));
        const auto fixed = kw::repairIgesNumbering(teapot, note);
        QVERIFY(fixed);
        QCOMPARE(*fixed, *kw::rebuildIgesNumbering(teapot, note));
        QVERIFY(!kw::igesNumberingNeedsRepair(*fixed)); // repaired once is consistent
        QVERIFY(sameAnswer(QByteArray()));
        QVERIFY(sameAnswer("not an IGES file\n"));
    }

    void damagedCopiesGetTheSameAnswer() {
        QRandomGenerator random(6);
        int repaired = 0, total = 0;
        for (const char* name : {"hammer.iges", "teapot.igs"}) {
            const QByteArray file = readData(name);
            for (int trial = 0; trial < 150; ++trial) {
                QByteArray bad = damaged(file, random);
                if (trial % 3 == 0)
                    bad = damaged(bad, random);
                QString note;
                const bool needs = kw::igesNumberingNeedsRepair(bad);
                QVERIFY2(needs == kw::rebuildIgesNumbering(bad, note).has_value(),
                         qPrintable(QStringLiteral("%1, trial %2").arg(name).arg(trial)));
                repaired += needs ? 1 : 0;
                ++total;
            }
        }
        // Both answers occur, so the comparison means something.
        QVERIFY(repaired > 0 && repaired < total);
    }
};

QTEST_GUILESS_MAIN(TestIgesRepair)
#include "tst_igesrepair.moc"
