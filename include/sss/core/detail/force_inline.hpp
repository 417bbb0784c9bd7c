#pragma once
/// \file
/// Internal: SSS_FORCE_INLINE, for the few small functions of the tracers' inner loops that the compiler would
/// otherwise keep out of line (a call there passes the walk's state through memory, and the loads that follow
/// wait on its stores), the simulator's per-ray echo, and the wedge sweep, whose caller's per-ray callback must be
/// inlined into it. Plain `inline` where the compiler has no such hint.

#if defined(__GNUC__) || defined(__clang__)
#define SSS_FORCE_INLINE [[gnu::always_inline]] inline
#elif defined(_MSC_VER)
#define SSS_FORCE_INLINE __forceinline
#else
#define SSS_FORCE_INLINE inline
#endif
