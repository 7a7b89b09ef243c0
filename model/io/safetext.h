// Text from a file or a library made safe to print on one line of a terminal or a status bar.
#pragma once

#include <QByteArrayView>
#include <QString>
#include <QStringView>

namespace kw {

/// The most characters of a file's own text that a message quotes (quoteInput).
constexpr qsizetype kMaxQuotedChars = 80;

/// `bytes` from a file, as a message quotes them: decoded as UTF-8 (an invalid sequence
/// becomes U+FFFD), control characters escaped (safeMessageText), and cut to `maxChars`
/// characters ending in "…" when longer. The caller adds the quotes.
QString quoteInput(QByteArrayView bytes, qsizetype maxChars = kMaxQuotedChars);

/// `text` with every control character escaped so that it prints as one line and cannot steer
/// a terminal: C0 controls, DEL and C1 controls as \xHH (ESC is \x1b), except that a newline
/// or tab is kept when `keepNewlines` is true. Nothing else changes.
QString safeMessageText(QStringView text, bool keepNewlines = false);

/// A message from OpenCASCADE with its unexpanded printf placeholders ("parameter %d",
/// "%s", "%.3f") dropped, its spaces collapsed and its control characters escaped.
QString occtMessageText(QByteArrayView message);

/// `text` cut to at most `maxChars` characters, ending in "…" when it was cut.
QString elided(QStringView text, qsizetype maxChars);

} // namespace kw
