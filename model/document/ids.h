// Typed handles of a document's parts: surfaces, trim loops, and the B-rep edges and shells an
// import keeps (model/document/topology.h).
#pragma once

#include <QHashFunctions>
#include <compare>
#include <cstdint>

namespace kw {

/// Typed handle of a surface, unique within a document and stable across undo/redo.
struct SurfaceId {
    std::uint32_t value = 0;
    bool isValid() const { return value != 0; }
    auto operator<=>(const SurfaceId&) const = default;
};

/// Typed handle of a trim loop, unique within a document.
struct TrimLoopId {
    std::uint32_t value = 0;
    bool isValid() const { return value != 0; }
    auto operator<=>(const TrimLoopId&) const = default;
};

/// Typed handle of an edge that two trim curves share (SharedEdge), unique within a document.
/// The CAD import uses the edge's number in the source shape, so messages can name it.
struct EdgeId {
    std::uint32_t value = 0;
    bool isValid() const { return value != 0; }
    auto operator<=>(const EdgeId&) const = default;
};

/// Typed handle of a shell of faces (Shell), unique within a document; the shell's number in
/// the source shape.
struct ShellId {
    std::uint32_t value = 0;
    bool isValid() const { return value != 0; }
    auto operator<=>(const ShellId&) const = default;
};

inline size_t qHash(SurfaceId id, size_t seed = 0) noexcept {
    return ::qHash(id.value, seed);
}
inline size_t qHash(TrimLoopId id, size_t seed = 0) noexcept {
    return ::qHash(id.value, seed);
}
inline size_t qHash(EdgeId id, size_t seed = 0) noexcept {
    return ::qHash(id.value, seed);
}
inline size_t qHash(ShellId id, size_t seed = 0) noexcept {
    return ::qHash(id.value, seed);
}

} // namespace kw
