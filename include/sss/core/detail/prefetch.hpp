#pragma once
/// \file
/// Internal: a portable cache prefetch hint for the tracers' inner loops.

namespace sss::detail {

/// A hint to bring the cache line holding p closer (nothing where the compiler has no such hint).
inline void prefetch(const void* p) noexcept {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p);
#else
    (void)p;
#endif
}

} // namespace sss::detail
