// Refusing what no reader should open: devices, FIFOs, directories, oversized files and files
// that are plainly not of their format (inputcheck.h).
#include "model/io/inputcheck.h"

#include "model/io/safetext.h"

#include <QFile>
#include <cerrno>
#include <sys/stat.h>

namespace kw {
namespace {

QString kindOf(mode_t mode) {
    if (S_ISDIR(mode))
        return QStringLiteral("a directory");
    if (S_ISFIFO(mode))
        return QStringLiteral("a FIFO (named pipe)");
    if (S_ISCHR(mode))
        return QStringLiteral("a character device");
    if (S_ISBLK(mode))
        return QStringLiteral("a block device");
    if (S_ISSOCK(mode))
        return QStringLiteral("a socket");
    return QStringLiteral("not a regular file");
}

QString byteCount(qint64 bytes) {
    if (bytes >= (1LL << 30) && bytes % (1LL << 30) == 0)
        return QStringLiteral("%1 GiB").arg(bytes >> 30);
    if (bytes >= (1LL << 20) && bytes % (1LL << 20) == 0)
        return QStringLiteral("%1 MiB").arg(bytes >> 20);
    return QStringLiteral("%1 bytes").arg(bytes);
}

} // namespace

static QString regularFileReason(const QString& path, qint64 maxBytes, const QString& formatName) {
    const QByteArray native = QFile::encodeName(path);
    struct stat target {};
    if (::stat(native.constData(), &target) != 0) {
        const int err = errno;
        struct stat link {};
        if (::lstat(native.constData(), &link) == 0 && S_ISLNK(link.st_mode))
            return QStringLiteral("a symbolic link to nothing (%1)").arg(qt_error_string(err));
        return err == ENOENT ? QStringLiteral("no such file") : qt_error_string(err);
    }
    if (!S_ISREG(target.st_mode)) {
        struct stat link {};
        const bool isLink = ::lstat(native.constData(), &link) == 0 && S_ISLNK(link.st_mode);
        return QStringLiteral("not a regular file: it is %1%2")
            .arg(isLink ? QStringLiteral("a symbolic link to ") : QString(),
                 kindOf(target.st_mode));
    }
    if (maxBytes >= 0 && target.st_size > maxBytes)
        return QStringLiteral("the file is %1 bytes, more than the %2 limit%3")
            .arg(qint64(target.st_size))
            .arg(byteCount(maxBytes),
                 formatName.isEmpty() ? QString() : QStringLiteral(" of %1 files").arg(formatName));
    return {};
}

Status checkRegularFile(const QString& path, qint64 maxBytes, const QString& formatName) {
    if (const QString why = regularFileReason(path, maxBytes, formatName); !why.isEmpty())
        return Error(why);
    return ok();
}

QByteArray fileHead(const QString& path, qsizetype count) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly | QIODevice::Unbuffered))
        return {};
    return f.read(count);
}

static QString knotHeadReason(const QByteArray& head) {
    qsizetype k = head.startsWith("\xEF\xBB\xBF") ? 3 : 0;
    while (k < head.size() &&
           (head[k] == ' ' || head[k] == '\t' || head[k] == '\n' || head[k] == '\r'))
        ++k;
    if (k == head.size())
        return head.isEmpty()
                   ? QStringLiteral("$: not valid JSON: the file is empty")
                   : QStringLiteral("$: not valid JSON: the file holds only white space");
    if (head[k] == '{')
        return {};
    const QString found =
        quoteInput(QByteArrayView(head).sliced(k, std::min<qsizetype>(16, head.size() - k)), 16);
    if (head[k] == '[')
        return QStringLiteral("$: expected an object at the top level, found '%1' at byte %2")
            .arg(found)
            .arg(k);
    return QStringLiteral("$: not valid JSON: a .knot file is a JSON object starting with '{', "
                          "found '%1' at byte %2")
        .arg(found)
        .arg(k);
}

Status checkKnotHead(const QByteArray& head) {
    if (const QString why = knotHeadReason(head); !why.isEmpty())
        return Error(why);
    return ok();
}

static QString objHeadReason(const QByteArray& head) {
    int line = 1;
    for (qsizetype k = 0; k < head.size(); ++k) {
        const unsigned char c = static_cast<unsigned char>(head[k]);
        if (c == '\n')
            ++line;
        if ((c < 0x20 && c != '\n' && c != '\r' && c != '\t' && c != '\f' && c != '\v') ||
            c == 0x7f)
            return QStringLiteral("line %1: not an OBJ file: control byte \\x%2 in the first %3 "
                                  "bytes (OBJ is text)")
                .arg(line)
                .arg(int(c), 2, 16, QLatin1Char('0'))
                .arg(head.size());
    }
    // The first statement: a comment, or a keyword of letters, digits and '_' (v, vt, cstype,
    // mtllib, c_interp, ...) followed by white space or the end of the line.
    line = 1;
    qsizetype k = head.startsWith("\xEF\xBB\xBF") ? 3 : 0;
    for (;;) {
        while (k < head.size() &&
               (head[k] == ' ' || head[k] == '\t' || head[k] == '\r' || head[k] == '\f' ||
                head[k] == '\v' || head[k] == '\n' || head[k] == '\\'))
            line += head[k++] == '\n' ? 1 : 0;
        if (k >= head.size() || head[k] != '#')
            break;
        while (k < head.size() && head[k] != '\n')
            ++k;
    }
    if (k >= head.size())
        return {}; // only comments so far: the parser decides
    qsizetype end = k;
    while (end < head.size() &&
           ((uchar(head[end]) < 0x80 && QChar::isLetterOrNumber(uchar(head[end]))) ||
            head[end] == '_'))
        ++end;
    const bool keyword = end > k && QChar::isLetter(uchar(head[k])) &&
                         (end == head.size() || head[end] == ' ' || head[end] == '\t' ||
                          head[end] == '\r' || head[end] == '\n');
    if (keyword)
        return {};
    qsizetype eol = head.indexOf('\n', k);
    if (eol < 0)
        eol = head.size();
    return QStringLiteral("line %1: not an OBJ file: a statement starts with a keyword, found "
                          "'%2'")
        .arg(line)
        .arg(quoteInput(QByteArrayView(head).sliced(k, std::min<qsizetype>(eol - k, 40)), 40));
}

Status checkObjHead(const QByteArray& head) {
    if (const QString why = objHeadReason(head); !why.isEmpty())
        return Error(why);
    return ok();
}

} // namespace kw
