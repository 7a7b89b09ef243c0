// Rebuilds inconsistent IGES sequence numbers from the directory's parameter pointers.
#include "model/cad/igesrepair.h"

#include <QList>
#include <algorithm>
#include <vector>

namespace kw {
namespace {

QByteArray field(int value) {
    return QByteArray::number(value).rightJustified(8, ' ');
}

// QByteArray::mid for a view (Qt 6.4's QByteArrayView has none): columns [at, at + n) that exist.
QByteArrayView columns(QByteArrayView line, qsizetype at, qsizetype n) {
    return at >= line.size() ? QByteArrayView() : line.sliced(at, std::min(n, line.size() - at));
}

int readInt(QByteArrayView line, int column, bool& ok) {
    return columns(line, column, 8).trimmed().toInt(&ok);
}

// The sequence number of a record (columns 74-80) is `seq`.
bool hasSequence(QByteArrayView line, int seq) {
    bool ok = false;
    return columns(line, 73, 7).trimmed().toInt(&ok) == seq && ok;
}

} // namespace

bool igesNumberingNeedsRepair(QByteArrayView file) {
    // rebuildIgesNumbering's checks in its order, on views: lines shorter than 80 columns are
    // padded with spaces there, which reads the same as the missing columns here (a line
    // shorter than 73 has a space in column 73: not fixed-format).
    std::vector<QByteArrayView> s, g, d, p;
    p.reserve(size_t(file.size() / 81));
    for (qsizetype from = 0; from <= file.size();) {
        qsizetype eol = file.indexOf('\n', from);
        if (eol < 0)
            eol = file.size();
        QByteArrayView line = file.sliced(from, eol - from);
        from = eol + 1;
        if (line.endsWith('\r'))
            line.chop(1);
        if (line.trimmed().isEmpty())
            continue;
        if (line.size() < 73)
            return false;
        switch (line[72]) {
        case 'S':
            s.push_back(line);
            break;
        case 'G':
            g.push_back(line);
            break;
        case 'D':
            d.push_back(line);
            break;
        case 'P':
            p.push_back(line);
            break;
        case 'T':
            break;
        default:
            return false;
        }
    }
    if (d.empty() || d.size() % 2 != 0 || p.empty())
        return false;
    const int n = static_cast<int>(d.size() / 2);
    std::vector<int> start(n);
    for (int k = 0; k < n; ++k) {
        bool ok = false;
        start[k] = readInt(d[2 * k], 8, ok);
        if (!ok || start[k] < 1 || start[k] > qsizetype(p.size()) ||
            (k > 0 && start[k] <= start[k - 1]) || (k == 0 && start[k] != 1))
            return false;
    }
    for (size_t i = 0; i < s.size(); ++i)
        if (!hasSequence(s[i], int(i + 1)))
            return true;
    QByteArray global;
    for (QByteArrayView line : g)
        global += columns(line, 0, 72);
    if (!global.contains(';') && (global.trimmed() == "1H," || global.trimmed().isEmpty()))
        return true;
    for (size_t i = 0; i < g.size(); ++i)
        if (!hasSequence(g[i], int(i + 1)))
            return true;
    for (int k = 0; k < n; ++k) {
        const int count = (k + 1 < n ? start[k + 1] : static_cast<int>(p.size()) + 1) - start[k];
        bool ok = false;
        if (readInt(d[2 * k + 1], 24, ok) != count || !ok || !hasSequence(d[2 * k], 2 * k + 1) ||
            !hasSequence(d[2 * k + 1], 2 * k + 2))
            return true;
    }
    for (int k = 0; k < n; ++k) {
        const int end = k + 1 < n ? start[k + 1] : static_cast<int>(p.size()) + 1;
        for (int i = start[k]; i < end; ++i) {
            bool ok = false;
            if (readInt(p[size_t(i - 1)], 64, ok) != 2 * k + 1 || !ok ||
                !hasSequence(p[size_t(i - 1)], i))
                return true;
        }
    }
    return false;
}

std::optional<QByteArray> repairIgesNumbering(const QByteArray& file, QString& note) {
    if (!igesNumberingNeedsRepair(file))
        return std::nullopt;
    return rebuildIgesNumbering(file, note);
}

std::optional<QByteArray> rebuildIgesNumbering(const QByteArray& file, QString& note) {
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
