// Checks made before a reader opens a file: only a regular file is read, its size is within the
// reader's budget, and its first bytes look like the format its name claims.
#pragma once

#include "model/error.h"

#include <QByteArray>
#include <QString>

namespace kw {

/// Largest OBJ file read (its text is held in memory while it is parsed).
constexpr qint64 kMaxObjFileBytes = 1LL << 30;

/// ok() when `path` names a regular file (a symbolic link is followed) of at most `maxBytes`
/// bytes (no limit when maxBytes < 0). Otherwise an Error, no path in it: "no such file",
/// "not a regular file: it is a directory" (a FIFO (named pipe), a character device, a block
/// device, a socket; "a symbolic link to a character device" when the name is a link), or
/// "the file is N bytes, more than the LIMIT limit of FORMAT files". Decided by stat(2) alone:
/// nothing is opened, so a FIFO or a device never blocks and /dev/zero is never read.
Status checkRegularFile(const QString& path, qint64 maxBytes = -1,
                        const QString& formatName = QString());

/// Up to `count` bytes from the start of `path` (empty when it cannot be read).
QByteArray fileHead(const QString& path, qsizetype count);

/// How much of a file's start the sniffers below look at.
constexpr qsizetype kSniffBytes = 4096;

/// ok() when `head` (a file's first bytes) can start a .knot file: optional UTF-8 byte-order
/// mark and white space, then '{'. Otherwise an Error worded as the .knot reader words its
/// errors ("$: not valid JSON: ...", naming the byte offset).
Status checkKnotHead(const QByteArray& head);
/// ok() when `head` can start an OBJ file: text (no NUL or other control byte but white
/// space) whose first statement is a comment or an OBJ keyword. Otherwise an Error with the
/// line and a short safe quote of what is there.
Status checkObjHead(const QByteArray& head);

} // namespace kw
