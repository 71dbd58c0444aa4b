#pragma once
// 64-bit FNV-1a (Fowler, Noll, Vo): a hash of bytes that is the same on every run and machine of
// one byte order. It names a sweep's results and truth files (sweep/tasks.h), keys a virtual
// map's cached pages (core/virtual_maps.h) and a map kept with history (render::historyKeyOf).
#include <cstddef>
#include <cstdint>

namespace penumbra {

inline constexpr uint64_t kFnv1aOffset = 14695981039346656037ull;
inline constexpr uint64_t kFnv1aPrime = 1099511628211ull;

// `hash` with `bytes` bytes at `data` added; start from kFnv1aOffset.
inline uint64_t fnv1a(const void* data, size_t bytes, uint64_t hash = kFnv1aOffset) {
    for (size_t i = 0; i < bytes; ++i) {
        hash ^= static_cast<const unsigned char*>(data)[i];
        hash *= kFnv1aPrime;
    }
    return hash;
}

} // namespace penumbra
