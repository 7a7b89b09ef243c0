// Quoting file contents and library messages safely (safetext.h).
#include "model/io/safetext.h"

#include <QRegularExpression>

namespace kw {

QString elided(QStringView text, qsizetype maxChars) {
    if (text.size() <= maxChars)
        return text.toString();
    qsizetype cut = std::max<qsizetype>(0, maxChars - 1);
    // Never split a surrogate pair: the half would print as a replacement character.
    if (cut > 0 && text[cut - 1].isHighSurrogate())
        --cut;
    return text.left(cut).toString() + QChar(0x2026);
}

QString safeMessageText(QStringView text, bool keepNewlines) {
    QString out;
    out.reserve(text.size());
    for (const QChar c : text) {
        const char16_t u = c.unicode();
        const bool control = u < 0x20 || u == 0x7f || (u >= 0x80 && u < 0xa0);
        if (!control || (keepNewlines && (u == '\n' || u == '\t'))) {
            out += c;
            continue;
        }
        static const char hex[] = "0123456789abcdef";
        out += QLatin1String("\\x");
        out += QLatin1Char(hex[(u >> 4) & 0xf]);
        out += QLatin1Char(hex[u & 0xf]);
    }
    return out;
}

QString quoteInput(QByteArrayView bytes, qsizetype maxChars) {
    // Decode no more than can be shown: a 3 MB token costs no more than an 80-byte one.
    const qsizetype take = std::min<qsizetype>(bytes.size(), maxChars * 4 + 4);
    const QString decoded = QString::fromUtf8(bytes.first(take)); // invalid UTF-8 -> U+FFFD
    // Escaped character by character, so that a cut never splits an escape or a surrogate
    // pair.
    QString out;
    for (qsizetype k = 0; k < decoded.size(); ++k) {
        const qsizetype width = decoded[k].isHighSurrogate() && k + 1 < decoded.size() ? 2 : 1;
        const QString piece = safeMessageText(QStringView(decoded).sliced(k, width));
        const bool last = k + width >= decoded.size() && take == bytes.size();
        if (out.size() + piece.size() > (last ? maxChars : maxChars - 1))
            return out + QChar(0x2026);
        out += piece;
        k += width - 1;
    }
    return take < bytes.size() ? out + QChar(0x2026) : out;
}

QString occtMessageText(QByteArrayView message) {
    QString text = QString::fromUtf8(message.first(std::min<qsizetype>(message.size(), 1000)));
    // OCCT's check messages keep their printf-style placeholders when no argument was given
    // ("Parameter n0.%d not an Integer"): drop them rather than print them.
    static const QRegularExpression counted(
        QStringLiteral("\\b(parameter|Parameter|entity|line|item) %[0-9]*[dis]"));
    text.replace(counted, QStringLiteral("a \\1"));
    static const QRegularExpression placeholder(
        QStringLiteral("%[-+ #0]*[0-9*]*(\\.[0-9*]+)?"
                       "(hh|h|ll|l|L|z|j|t)?[diouxXeEfgGcsp]"));
    // Until none is left: removing "%e" from "%%e" leaves a new "%" before what follows.
    while (text.contains(placeholder))
        text.remove(placeholder);
    text = safeMessageText(text.simplified());
    text.replace(QStringLiteral(" ."), QStringLiteral("."));
    return text;
}

} // namespace kw
