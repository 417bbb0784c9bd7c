// The wedge sweep's tests (test_grid_tracing_wedge.cpp) again, with multiply-adds fused (support/fused.hpp): every
// ray hits or misses as the single-ray tracer does, and its hit is the same to rounding.
#define SSS_TEST_FUSED 1
#include "support/fused.hpp"

#include "test_grid_tracing_wedge.cpp"
