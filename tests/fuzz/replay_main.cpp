// Replays fuzz inputs through a harness without libFuzzer (the gcc build's regression tests):
//   fuzz_replay_NAME FILE_OR_DIR...   runs LLVMFuzzerTestOneInput on every file, recursively.
// A failed invariant aborts, so CTest reports the input; the last file tried is printed first.
#include <QDirIterator>
#include <QFile>
#include <QFileInfo>
#include <cstdint>
#include <cstdio>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size);

namespace {

int runFile(const QString& path) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly)) {
        std::fprintf(stderr, "%s: cannot open: %s\n", qPrintable(path),
                     qPrintable(f.errorString()));
        return 1;
    }
    const QByteArray bytes = f.readAll();
    std::fprintf(stderr, "replay %s\n", qPrintable(path));
    std::fflush(stderr);
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.constData()),
                           size_t(bytes.size()));
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s FILE_OR_DIR...\n", argv[0]);
        return 2;
    }
    int files = 0, failures = 0;
    for (int a = 1; a < argc; ++a) {
        const QString arg = QString::fromLocal8Bit(argv[a]);
        if (QFileInfo(arg).isDir()) {
            QDirIterator it(arg, QDir::Files, QDirIterator::Subdirectories);
            while (it.hasNext()) {
                const QString path = it.next();
                if (QFileInfo(path).fileName().startsWith(QLatin1Char('.')) ||
                    path.endsWith(QLatin1String(".md")))
                    continue; // README.md and dot files describe the corpus, they are not inputs
                failures += runFile(path);
                ++files;
            }
        } else {
            failures += runFile(arg);
            ++files;
        }
    }
    std::fprintf(stderr, "replayed %d input(s), %d unreadable\n", files, failures);
    return files == 0 || failures != 0 ? 1 : 0;
}
