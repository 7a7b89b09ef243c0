// Shared by fuzz_step.cpp and fuzz_iges.cpp: the checks a CAD file passes in the reader's child
// process before OpenCASCADE sees it (model/cad/cadprecheck.h), and the message helpers every
// refusal goes through (model/io/safetext.h), on arbitrary bytes.
#pragma once

#include "fuzz_util.h"
#include "model/cad/cadprecheck.h"
#include "model/io/safetext.h"

namespace kw::fuzz {

/// True when `text` holds no control character (C0, DEL, C1): it prints as one line and cannot
/// steer a terminal.
inline bool printable(const QString& text) {
    for (const QChar c : text) {
        const char16_t u = c.unicode();
        if (u < 0x20 || u == 0x7f || (u >= 0x80 && u < 0xa0))
            return false;
    }
    return true;
}

/// Runs the pre-OCCT checks of `format` on `bytes`: the same answer twice; a refusal is one
/// printable line of at most 300 characters, "line N: ..." with N within the file; a file
/// whose head is refused is refused with the head's reason. Then the message helpers on the
/// same bytes: quotes are at most 80 characters and printable, OCCT placeholders are gone.
inline void checkCadPrecheck(CadFormat format, const std::uint8_t* data, size_t size) {
    const QByteArrayView bytes(reinterpret_cast<const char*>(data), qsizetype(size));
    const QString why = checkCadContent(format, bytes).message();
    KW_FUZZ_CHECK(why == checkCadContent(format, bytes).message(),
                  "the check is not deterministic");
    const QString head =
        checkCadHead(format, bytes.first(std::min<qsizetype>(size, 4096))).message();
    if (!head.isEmpty())
        KW_FUZZ_CHECK(why == head,
                      QStringLiteral("head refused (%1) but content: %2").arg(head, why));
    if (!why.isEmpty()) {
        KW_FUZZ_CHECK(why.size() <= 300, why);
        KW_FUZZ_CHECK(printable(why), why);
        KW_FUZZ_CHECK(why.startsWith(QLatin1String("line ")), why);
        bool ok = false;
        const long long line = why.mid(5, why.indexOf(QLatin1Char(':')) - 5).toLongLong(&ok);
        KW_FUZZ_CHECK(ok && line >= 1 && line <= bytes.count('\n') + 1, why);
    }
    const QString quote = quoteInput(bytes);
    KW_FUZZ_CHECK(quote.size() <= kMaxQuotedChars, quote);
    KW_FUZZ_CHECK(printable(quote), quote);
    const QString occt = occtMessageText(bytes);
    KW_FUZZ_CHECK(printable(occt), occt);
    KW_FUZZ_CHECK(!occt.contains(QLatin1String("%d")) && !occt.contains(QLatin1String("%s")), occt);
}

} // namespace kw::fuzz
