// Shared by the libFuzzer harnesses (tests/fuzz/*.cpp): a reader that turns fuzz bytes into
// bounded values, and a check that aborts, so libFuzzer keeps the input as a reproducer.
// Builds with clang (libFuzzer) and with gcc (replay_main.cpp), so no FuzzedDataProvider.
#pragma once

#include <QByteArray>
#include <QString>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

/// Aborts with the failed invariant and a message (QString or const char*).
#define KW_FUZZ_CHECK(cond, message)                                                               \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            std::fprintf(stderr, "fuzz invariant failed: %s\n  at %s:%d\n  %s\n", #cond, __FILE__, \
                         __LINE__, qPrintable(QString(message)));                                  \
            std::abort();                                                                          \
        }                                                                                          \
    } while (0)

namespace kw::fuzz {

/// Consumes the fuzz input front to back; past its end every value is the smallest allowed.
class Input {
public:
    Input(const std::uint8_t* data, size_t size) : m_data(data), m_size(size) {}

    bool empty() const { return m_pos >= m_size; }
    std::uint8_t byte() { return m_pos < m_size ? m_data[m_pos++] : 0; }
    // Each value is read in separate statements: the order in which the operands of | (or the
    // arguments of a call) are evaluated is unspecified, and gcc (the ctest replay) and clang
    // (libFuzzer) differ, so `byte() | byte() << 8` would replay another input than was found.
    // Harnesses therefore never read two values in one call's arguments either.
    std::uint16_t u16() {
        const std::uint16_t lo = byte();
        const std::uint16_t hi = byte();
        return std::uint16_t(lo | (hi << 8));
    }
    std::uint32_t u32() {
        const std::uint32_t lo = u16();
        const std::uint32_t hi = u16();
        return lo | (hi << 16);
    }
    bool flag() { return byte() & 1; }

    /// An integer in [lo, hi] (inclusive; lo <= hi).
    int integer(int lo, int hi) {
        const std::uint64_t span = std::uint64_t(std::int64_t(hi) - lo) + 1;
        const std::uint64_t raw = span <= 256 ? byte() : span <= 65536 ? u16() : u32();
        return int(std::int64_t(lo) + std::int64_t(raw % span));
    }

    /// A finite value in [lo, hi] on a grid of 65536 steps.
    double real(double lo, double hi) { return lo + (hi - lo) * (u16() / 65535.0); }

    /// Mostly real(lo, hi); one time in 16 a value that breaks naive code: NaN, infinities,
    /// huge, tiny, negative zero, or 64 raw bits.
    double wild(double lo, double hi) {
        if ((byte() & 15) != 0)
            return real(lo, hi);
        switch (byte() % 8) {
        case 0:
            return std::numeric_limits<double>::quiet_NaN();
        case 1:
            return std::numeric_limits<double>::infinity();
        case 2:
            return -std::numeric_limits<double>::infinity();
        case 3:
            return 1e308;
        case 4:
            return -1e300;
        case 5:
            return 1e-310;
        case 6:
            return -0.0;
        default: {
            const std::uint64_t lo = u32();
            const std::uint64_t hi = u32();
            const std::uint64_t bits = lo | (hi << 32);
            double d;
            std::memcpy(&d, &bits, sizeof d);
            return d;
        }
        }
    }

    /// The rest of the input as bytes.
    QByteArray rest() {
        const QByteArray out(reinterpret_cast<const char*>(m_data + m_pos),
                             qsizetype(m_size - m_pos));
        m_pos = m_size;
        return out;
    }

private:
    const std::uint8_t* m_data;
    size_t m_size;
    size_t m_pos = 0;
};

} // namespace kw::fuzz
