// Byte scans of IGES, STEP and BREP files before OpenCASCADE reads them (cadprecheck.h).
#include "model/cad/cadprecheck.h"

#include "model/io/inputcheck.h"
#include "model/io/safetext.h"

#include <QFile>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace kw {
namespace {

bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}
bool isDigit(char c) {
    return c >= '0' && c <= '9';
}
bool isWordChar(char c) {
    return isDigit(c) || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
}

// The value of a numeric token (Fortran's D exponent accepted), or nullopt when `token` is not
// a whole number. Tokens longer than any real number are not numbers.
std::optional<double> numberValue(QByteArrayView token) {
    if (token.isEmpty() || token.size() > 400)
        return std::nullopt;
    char buffer[402];
    for (qsizetype k = 0; k < token.size(); ++k)
        buffer[k] = (token[k] == 'D' || token[k] == 'd') ? 'E' : token[k];
    buffer[token.size()] = '\0';
    char* end = nullptr;
    const double x = std::strtod(buffer, &end);
    if (end != buffer + token.size())
        return std::nullopt;
    return x;
}

bool absurd(double x) {
    return !std::isfinite(x) || std::fabs(x) > kMaxCadMagnitude;
}

QString absurdValue(long long line, QByteArrayView token) {
    return QStringLiteral("line %1: the value %2 is %3; values beyond %4 are refused before "
                          "OpenCASCADE reads the file")
        .arg(line)
        .arg(quoteInput(token, 40),
             std::isnan(*numberValue(token))   ? QStringLiteral("not a number")
             : std::isinf(*numberValue(token)) ? QStringLiteral("infinite")
                                               : QStringLiteral("out of range"),
             QStringLiteral("1e100 in magnitude"));
}

// STEP: one pass over the bytes. Outside strings ('' is a quote inside one) and comments
// (/* */): parentheses open and close lists, and each list counts its items as the starts of
// tokens after a separator (comma, white space or its opening parenthesis), so "1 2 3" and
// "1,2,3" are both three items. In the DATA section every number is checked.
QString stepProblem(QByteArrayView b) {
    std::vector<long long> items; // per open list: items so far
    std::vector<char> separated;  // per open list: the last significant byte was a separator
    bool inString = false, inComment = false, inData = false;
    long long line = 1;
    const qsizetype n = b.size();
    for (qsizetype k = 0; k < n; ++k) {
        const char c = b[k];
        if (c == '\n')
            ++line;
        if (inString) {
            inString = c != '\''; // '' closes and reopens: the same state after two quotes
            continue;
        }
        if (inComment) {
            if (c == '*' && k + 1 < n && b[k + 1] == '/') {
                inComment = false;
                ++k;
            }
            continue;
        }
        if (c == '/' && k + 1 < n && b[k + 1] == '*') {
            inComment = true; // separates like white space
            if (!separated.empty())
                separated.back() = 1;
            ++k;
            continue;
        }
        const auto startItem = [&]() -> bool {
            if (items.empty() || !separated.back())
                return true;
            separated.back() = 0;
            return ++items.back() <= kMaxStepListItems;
        };
        const QString tooLong =
            QStringLiteral("line %1: a list has more than %2 items; OpenCASCADE's STEP parser "
                           "takes quadratic time in the length of one list, so the file is "
                           "refused")
                .arg(line)
                .arg(kMaxStepListItems);
        if (isSpace(c) || c == ',') {
            if (!separated.empty())
                separated.back() = 1;
            continue;
        }
        if (c == '(') {
            if (!startItem())
                return tooLong;
            items.push_back(0);
            separated.push_back(1);
            continue;
        }
        if (c == ')') {
            if (!items.empty()) {
                items.pop_back();
                separated.pop_back();
            }
            continue;
        }
        if (c == ';') {
            items.clear();
            separated.clear();
            continue;
        }
        if (!startItem())
            return tooLong;
        if (c == '\'') {
            inString = true;
            continue;
        }
        // A word: DATA / ENDSEC switch the number check, entity names and enumerations
        // (.T.) are skipped, #12 is a reference, and a number is checked.
        qsizetype end = k;
        if (c == '#') {
            ++end;
            while (end < n && isDigit(b[end]))
                ++end;
        } else if (c == '.' && k + 1 < n && !isDigit(b[k + 1])) {
            ++end;
            while (end < n && b[end] != '.' && isWordChar(b[end]))
                ++end;
            if (end < n && b[end] == '.')
                ++end;
        } else if (isDigit(c) || c == '+' || c == '-' || c == '.') {
            while (end < n && (isDigit(b[end]) || b[end] == '.' || b[end] == '+' || b[end] == '-' ||
                               b[end] == 'E' || b[end] == 'e'))
                ++end;
            const QByteArrayView token = b.sliced(k, end - k);
            if (inData)
                if (const std::optional<double> x = numberValue(token); x && absurd(*x))
                    return absurdValue(line, token);
        } else if (isWordChar(c)) {
            while (end < n && (isWordChar(b[end]) || b[end] == '-'))
                ++end;
            const QByteArrayView word = b.sliced(k, end - k);
            if (word == "DATA")
                inData = true;
            else if (word == "ENDSEC")
                inData = false;
        } else {
            end = k + 1;
        }
        k = std::max(k, end - 1);
    }
    return {};
}

// IGES: the parameter data section (column 73 'P') holds the numbers, in columns 1 to 64 of
// each record, delimited by ',' and ';' (the defaults; a file that declares others in its
// Global section is not scanned). Hollerith strings "nH..." are skipped by their count, also
// across records.
QString igesProblem(QByteArrayView b) {
    char parameterDelimiter = ',', recordDelimiter = ';';
    long long line = 0;
    qsizetype hollerith = 0; // characters of a Hollerith string still to skip
    QByteArray token;
    long long tokenLine = 0;
    bool globalSeen = false;
    const auto checkToken = [&]() -> QString {
        const QByteArray t = token.trimmed();
        token.clear();
        if (t.isEmpty())
            return {};
        if (const std::optional<double> x = numberValue(t); x && absurd(*x))
            return absurdValue(tokenLine, t);
        return {};
    };
    for (qsizetype start = 0; start < b.size();) {
        qsizetype eol = b.indexOf('\n', start);
        if (eol < 0)
            eol = b.size();
        QByteArrayView record = b.sliced(start, eol - start);
        start = eol + 1;
        ++line;
        if (record.endsWith('\r'))
            record.chop(1);
        if (record.size() < 73)
            continue;
        const char section = record[72];
        if (section == 'G' && !globalSeen) {
            globalSeen = true;
            // The first two parameters: "1Hx" declares a delimiter, an empty one keeps ','
            // or ';'.
            qsizetype pos = 0;
            if (record.startsWith("1H")) {
                parameterDelimiter = record[2];
                pos = 3;
            }
            if (pos < record.size() && record[pos] == parameterDelimiter &&
                record.sliced(pos + 1).startsWith("1H") && record.size() > pos + 3)
                recordDelimiter = record[pos + 3];
            continue;
        }
        if (section != 'P')
            continue;
        const QByteArrayView data = record.first(std::min<qsizetype>(64, record.size()));
        for (qsizetype k = 0; k < data.size(); ++k) {
            const char c = data[k];
            if (hollerith > 0) {
                --hollerith;
                continue;
            }
            if (c == parameterDelimiter || c == recordDelimiter) {
                if (QString why = checkToken(); !why.isEmpty())
                    return why;
                if (c == recordDelimiter)
                    break; // the rest of the record is the pointer fields' padding
                continue;
            }
            if ((c == 'H' || c == 'h') && !token.trimmed().isEmpty()) {
                bool ok = false;
                const long long count = token.trimmed().toLongLong(&ok);
                if (ok && count >= 0) {
                    hollerith = qsizetype(std::min<long long>(count, b.size()));
                    token.clear();
                    continue;
                }
            }
            if (token.isEmpty())
                tokenLine = line;
            if (token.size() < 1000)
                token += c;
        }
    }
    return checkToken();
}

// BREP: white-space separated words; every word that is a number (strtod's "inf" and "nan"
// included) is checked.
QString brepProblem(QByteArrayView b) {
    long long line = 1;
    const qsizetype n = b.size();
    for (qsizetype k = 0; k < n;) {
        if (isSpace(b[k])) {
            line += b[k] == '\n' ? 1 : 0;
            ++k;
            continue;
        }
        qsizetype end = k;
        while (end < n && !isSpace(b[end]))
            ++end;
        const QByteArrayView word = b.sliced(k, end - k);
        const char c = word[0];
        if (isDigit(c) || c == '+' || c == '-' || c == '.' || c == 'i' || c == 'I' || c == 'n' ||
            c == 'N')
            if (const std::optional<double> x = numberValue(word); x && absurd(*x))
                return absurdValue(line, word);
        k = end;
    }
    return {};
}

QString quoted(QByteArrayView head) {
    qsizetype eol = head.indexOf('\n');
    if (eol < 0)
        eol = head.size();
    return quoteInput(head.first(std::min<qsizetype>(eol, 40)), 40);
}

} // namespace

static QString cadHeadReason(CadFormat format, QByteArrayView head) {
    qsizetype k = head.startsWith("\xEF\xBB\xBF") ? 3 : 0;
    switch (format) {
    case CadFormat::Iges: {
        qsizetype eol = head.indexOf('\n');
        if (eol < 0)
            eol = head.size();
        QByteArrayView first = head.first(eol);
        if (first.endsWith('\r'))
            first.chop(1);
        if (first.size() >= 73 && first.size() <= 82 && first[72] == 'S')
            return {};
        return QStringLiteral("line 1: not an IGES file: its first record must be 80 columns "
                              "with 'S' in column 73, found '%1'")
            .arg(quoted(head));
    }
    case CadFormat::Step: {
        while (k < head.size() && isSpace(head[k]))
            ++k;
        if (head.sliced(k).startsWith("ISO-10303-21;"))
            return {};
        return QStringLiteral("line 1: not a STEP file: it must start with 'ISO-10303-21;', "
                              "found '%1'")
            .arg(quoted(head.sliced(k)));
    }
    case CadFormat::Brep: {
        while (k < head.size() && isSpace(head[k]))
            ++k;
        const QByteArrayView rest = head.sliced(k);
        if (rest.startsWith("DBRep_DrawableShape") || rest.startsWith("CASCADE Topology"))
            return {};
        return QStringLiteral("line 1: not a BREP file: it must start with "
                              "'DBRep_DrawableShape' or 'CASCADE Topology', found '%1'")
            .arg(quoted(rest));
    }
    default:
        return {};
    }
}

Status checkCadHead(CadFormat format, QByteArrayView head) {
    if (const QString why = cadHeadReason(format, head); !why.isEmpty())
        return Error(why);
    return ok();
}

static QString cadContentReason(CadFormat format, QByteArrayView bytes) {
    if (QString why = cadHeadReason(format, bytes.first(std::min<qsizetype>(bytes.size(), 4096)));
        !why.isEmpty())
        return why;
    switch (format) {
    case CadFormat::Step:
        return stepProblem(bytes);
    case CadFormat::Iges:
        return igesProblem(bytes);
    case CadFormat::Brep:
        return brepProblem(bytes);
    default:
        return {};
    }
}

Status checkCadContent(CadFormat format, QByteArrayView bytes) {
    if (const QString why = cadContentReason(format, bytes); !why.isEmpty())
        return Error(why);
    return ok();
}

static QString cadFileReason(const QString& path, CadFormat format) {
    if (QString why = checkRegularFile(path).message(); !why.isEmpty())
        return why;
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly))
        return QStringLiteral("cannot open: %1").arg(file.errorString());
    if (file.size() == 0)
        return QStringLiteral("the file is empty");
    const uchar* bytes = file.map(0, file.size());
    if (!bytes)
        return QStringLiteral("cannot read: %1").arg(file.errorString());
    return cadContentReason(format,
                            QByteArrayView(reinterpret_cast<const char*>(bytes), file.size()));
}

Status checkCadFile(const QString& path, CadFormat format) {
    if (const QString why = cadFileReason(path, format); !why.isEmpty())
        return Error(why);
    return ok();
}

} // namespace kw
