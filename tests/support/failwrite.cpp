// An LD_PRELOAD library for tests: every write to a file under $KW_FAIL_WRITES_UNDER fails with
// ENOSPC ("No space left on device"), as on a full disk; other writes are untouched.
#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

namespace {

int targeted(int fd) {
    const char* prefix = getenv("KW_FAIL_WRITES_UNDER");
    if (!prefix || !*prefix)
        return 0;
    char link[64], path[4096];
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    const ssize_t n = readlink(link, path, sizeof path - 1);
    if (n <= 0)
        return 0;
    path[n] = '\0';
    return strncmp(path, prefix, strlen(prefix)) == 0;
}

} // namespace

typedef ssize_t (*write_fn)(int, const void*, size_t);
typedef ssize_t (*writev_fn)(int, const struct iovec*, int);
typedef ssize_t (*pwrite_fn)(int, const void*, size_t, off_t);
#define REAL(name, type)                                                                           \
    static type real_##name;                                                                       \
    if (!real_##name)                                                                              \
    real_##name = reinterpret_cast<type>(dlsym(RTLD_NEXT, #name))

extern "C" {

ssize_t write(int fd, const void* buffer, size_t count) {
    REAL(write, write_fn);
    if (count > 0 && targeted(fd)) {
        errno = ENOSPC;
        return -1;
    }
    return real_write(fd, buffer, count);
}

ssize_t writev(int fd, const struct iovec* iov, int n) {
    REAL(writev, writev_fn);
    if (n > 0 && targeted(fd)) {
        errno = ENOSPC;
        return -1;
    }
    return real_writev(fd, iov, n);
}

ssize_t pwrite64(int fd, const void* buffer, size_t count, off_t offset) {
    REAL(pwrite64, pwrite_fn);
    if (count > 0 && targeted(fd)) {
        errno = ENOSPC;
        return -1;
    }
    return real_pwrite64(fd, buffer, count, offset);
}

ssize_t pwrite(int fd, const void* buffer, size_t count, off_t offset) {
    return pwrite64(fd, buffer, count, offset);
}

// Writers that use stdio (OpenImageIO, libjpeg): glibc's own fwrite calls its internal write,
// which the wrappers above do not see.
size_t fwrite(const void* buffer, size_t size, size_t count, FILE* stream) {
    using fwrite_fn = size_t (*)(const void*, size_t, size_t, FILE*);
    static fwrite_fn real_fwrite;
    if (!real_fwrite)
        real_fwrite = reinterpret_cast<fwrite_fn>(dlsym(RTLD_NEXT, "fwrite"));
    if (size > 0 && count > 0 && targeted(fileno(stream))) {
        errno = ENOSPC;
        return 0;
    }
    return real_fwrite(buffer, size, count, stream);
}

} // extern "C"
