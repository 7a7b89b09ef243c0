// One pass over a .knot file's bytes that refuses absurd sizes before the JSON is parsed.
#include "model/io/knotfile_prescan.h"

#include "model/document/validation.h"

#include <QLocale>
#include <cmath>
#include <optional>
#include <vector>

namespace kw {

namespace {

constexpr int kMaxDepth = 64;

struct Level {
    bool object = false;
    long long count = 0; ///< elements of an array so far
    QByteArray key;      ///< member being read in an object
    double countU = -1, countV = -1;
};

QString pathOf(const std::vector<Level>& stack) {
    QString path = QStringLiteral("$");
    for (size_t i = 0; i < stack.size(); ++i) {
        const Level& l = stack[i];
        const bool inner = i + 1 < stack.size();
        if (l.object && !l.key.isEmpty())
            path += QLatin1Char('.') + QString::fromUtf8(l.key);
        else if (!l.object && (inner || l.count > 0))
            path += QStringLiteral("[%1]").arg(std::max(0LL, l.count - 1));
    }
    return path;
}

struct KnotPrescanError {
    QString path;   ///< JSON path of the offending member
    QString reason; ///< as the reader would word it
};

std::optional<KnotPrescanError> firstTooLarge(const QByteArray& json) {
    std::vector<Level> stack;
    long long numbers = 0;
    const char* p = json.constData();
    const char* const end = p + json.size();
    bool expectKey = false; // inside an object, before ':' of a member
    // A value starts: counts one array element; returns an error when the array is too long.
    auto beginValue = [&]() -> std::optional<KnotPrescanError> {
        if (stack.empty() || stack.back().object)
            return std::nullopt;
        Level& a = stack.back();
        ++a.count;
        const bool surfaces = stack.size() == 2 && stack[0].key == "surfaces";
        const long long limit = surfaces ? kMaxSurfaces : kMaxControlPoints;
        if (a.count > limit) {
            a.count = 0; // the path names the array itself
            return KnotPrescanError{
                pathOf(stack),
                surfaces ? QStringLiteral("more than %1 surfaces, the limit").arg(kMaxSurfaces)
                         : QStringLiteral("an array of more than %1 "
                                          "elements, more than any limit "
                                          "allows")
                               .arg(kMaxControlPoints)};
        }
        return std::nullopt;
    };
    while (p < end) {
        const char c = *p;
        if (c == ' ' || c == '\n' || c == '\r' || c == '\t' || c == ',' || c == ':') {
            if (c == ',' && !stack.empty() && stack.back().object)
                expectKey = true;
            ++p;
            continue;
        }
        if (c == '"') {
            const char* s = ++p;
            while (p < end && *p != '"')
                p += (*p == '\\') ? 2 : 1;
            if (p >= end)
                return std::nullopt;
            const QByteArray text(s, p - s);
            ++p;
            if (expectKey && !stack.empty() && stack.back().object) {
                stack.back().key = text;
                expectKey = false;
            } else if (auto e = beginValue()) {
                return e;
            }
            continue;
        }
        if (c == '{' || c == '[') {
            if (auto e = beginValue())
                return e;
            if (stack.size() >= size_t(kMaxDepth))
                return KnotPrescanError{
                    pathOf(stack),
                    QStringLiteral("nested more than %1 levels deep").arg(kMaxDepth)};
            Level level;
            level.object = c == '{';
            stack.push_back(level);
            expectKey = c == '{';
            ++p;
            continue;
        }
        if (c == '}' || c == ']') {
            if (stack.empty())
                return std::nullopt;
            stack.pop_back();
            expectKey = false;
            ++p;
            continue;
        }
        // A literal: number, true, false or null.
        const char* s = p;
        while (p < end && *p != ',' && *p != ']' && *p != '}' && *p != ' ' && *p != '\n' &&
               *p != '\r' && *p != '\t' && *p != ':')
            ++p;
        if (auto e = beginValue())
            return e;
        const bool number = (*s >= '0' && *s <= '9') || *s == '-';
        if (!number)
            continue;
        if (++numbers > kMaxKnotNumbers)
            return KnotPrescanError{pathOf(stack),
                                    QStringLiteral("the file holds more than %1 numbers, the "
                                                   "limit of one .knot file")
                                        .arg(kMaxKnotNumbers)};
        if (!stack.empty() && stack.back().object) {
            Level& o = stack.back();
            const bool u = o.key == "countU", v = o.key == "countV";
            if (u || v) {
                bool ok = false;
                const double x = QByteArray(s, p - s).toDouble(&ok);
                (u ? o.countU : o.countV) = ok ? x : -1;
                if (o.countU >= 1 && o.countV >= 1 && o.countU * o.countV > kMaxControlPoints) {
                    const QString path = pathOf(stack);
                    const QString at =
                        path.left(path.lastIndexOf(QLatin1Char('.'))) + QStringLiteral(".countV");
                    return KnotPrescanError{
                        at, QStringLiteral("countU %1 x countV %2 = %3 control points, more "
                                           "than the limit %4")
                                .arg(QString::number(o.countU, 'g', 17),
                                     QString::number(o.countV, 'g', 17),
                                     QString::number(o.countU * o.countV, 'g', 17))
                                .arg(kMaxControlPoints)};
                }
            }
        }
    }
    return std::nullopt;
}

} // namespace

Status prescanKnotJson(const QByteArray& json) {
    if (const auto tooLarge = firstTooLarge(json))
        return Error(tooLarge->reason, QString(), tooLarge->path);
    return ok();
}

} // namespace kw
