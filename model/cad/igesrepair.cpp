// Rebuilds inconsistent IGES sequence numbers from the directory's parameter pointers.
#include "model/cad/igesrepair.h"

#include <QList>
#include <vector>

namespace kw {
namespace {

QByteArray field(int value) {
    return QByteArray::number(value).rightJustified(8, ' ');
}

int readInt(const QByteArray& line, int column, bool& ok) {
    return line.mid(column, 8).trimmed().toInt(&ok);
}

} // namespace

std::optional<QByteArray> repairIgesNumbering(const QByteArray& file, QString& note) {
    QList<QByteArray> s, g, d, p;
    for (QByteArray line : file.split('\n')) {
        if (line.endsWith('\r'))
            line.chop(1);
        if (line.trimmed().isEmpty())
            continue;
        if (line.size() < 80)
            line = line.leftJustified(80, ' ');
        switch (line[72]) {
        case 'S':
            s << line;
            break;
        case 'G':
            g << line;
            break;
        case 'D':
            d << line;
            break;
        case 'P':
            p << line;
            break;
        case 'T':
            break;
        default:
            return std::nullopt; // not fixed-format IGES: leave it to the reader
        }
    }
    if (d.isEmpty() || d.size() % 2 != 0 || p.isEmpty())
        return std::nullopt;
    const int n = static_cast<int>(d.size() / 2);
    std::vector<int> start(n);
    for (int k = 0; k < n; ++k) {
        bool ok = false;
        start[k] = readInt(d[2 * k], 8, ok);
        if (!ok || start[k] < 1 || start[k] > p.size() || (k > 0 && start[k] <= start[k - 1]) ||
            (k == 0 && start[k] != 1))
            return std::nullopt; // the directory itself is inconsistent: nothing to rebuild from
    }
    bool changed = false;
    QByteArray out;
    // Sequence numbers may be zero-padded or not; only their values matter.
    auto put = [&](QByteArray line, char section, int seq) {
        QByteArray tail = QByteArray(1, section) + QByteArray::number(seq).rightJustified(7, ' ');
        bool ok = false;
        if (line.mid(73, 7).trimmed().toInt(&ok) != seq || !ok)
            changed = true;
        line.replace(72, 8, tail);
        out += line.left(80) + '\n';
    };
    for (int i = 0; i < s.size(); ++i)
        put(s[i], 'S', i + 1);
    // A Global section that stops after the parameter delimiter leaves the record delimiter
    // undefined (OCCT then misreads every ';'): complete it with the default delimiters, model
    // scale 1 and millimetres (OCCT's own unit), so coordinates are read as written instead of
    // being scaled from the default unit, inches.
    QByteArray global;
    for (const QByteArray& line : g)
        global += line.left(72);
    if (!global.contains(';') && (global.trimmed() == "1H," || global.trimmed().isEmpty())) {
        g = {QByteArray("1H,,1H;,,,,,,,,,,,1.0,2,2HMM;").leftJustified(80, ' ')};
        changed = true;
    }
    for (int i = 0; i < g.size(); ++i)
        put(g[i], 'G', i + 1);
    for (int k = 0; k < n; ++k) {
        const int count = (k + 1 < n ? start[k + 1] : static_cast<int>(p.size()) + 1) - start[k];
        QByteArray second = d[2 * k + 1];
        bool ok = false;
        if (readInt(second, 24, ok) != count || !ok) {
            second.replace(24, 8, field(count));
            changed = true;
        }
        put(d[2 * k], 'D', 2 * k + 1);
        put(second, 'D', 2 * k + 2);
    }
    for (int k = 0; k < n; ++k) {
        const int end = k + 1 < n ? start[k + 1] : static_cast<int>(p.size()) + 1;
        for (int i = start[k]; i < end; ++i) {
            QByteArray line = p[i - 1];
            bool ok = false;
            if (readInt(line, 64, ok) != 2 * k + 1 || !ok) {
                line.replace(64, 8, field(2 * k + 1));
                changed = true;
            }
            put(line, 'P', i);
        }
    }
    if (!changed)
        return std::nullopt;
    QByteArray t = "S" + QByteArray::number(s.size()).rightJustified(7, ' ') + "G" +
                   QByteArray::number(g.size()).rightJustified(7, ' ') + "D" +
                   QByteArray::number(d.size()).rightJustified(7, ' ') + "P" +
                   QByteArray::number(p.size()).rightJustified(7, ' ');
    out += t.leftJustified(72, ' ') + "T      1\n";
    note = QStringLiteral("inconsistent IGES numbering (sequence numbers, parameter back-pointers "
                          "or line counts) rebuilt from the directory's parameter pointers, and "
                          "an incomplete Global section completed (coordinates as written), "
                          "before reading (%1 entities)")
               .arg(n);
    return out;
}

} // namespace kw
