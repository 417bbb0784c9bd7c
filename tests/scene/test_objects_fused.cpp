// The scene tests (test_scene.cpp) again, with multiply-adds fused: the build compiles this file at -O3 with
// -ffp-contract=fast, and -mfma on x86. A compiler may then fuse the same expression differently where it is
// inlined into different code, so no hit may rest on one computation rounding as another does: an object hierarchy
// that solved its nearest primitive again, with the distance found as the limit, would lose the hit wherever the
// second solution came out an ulp farther, and the scene would return the seabed behind the object (with GCC 12,
// three of the 4000 rays of the test over a height field, in double). On an x86 processor without FMA this
// skips itself (exit code 77) before any test runs.

#include <cstdlib>

#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
namespace {
[[maybe_unused]] const bool fma_checked = [] {
    __builtin_cpu_init();
    if (!__builtin_cpu_supports("fma")) std::exit(77);
    return true;
}();
} // namespace
#endif

#include "test_scene.cpp"
