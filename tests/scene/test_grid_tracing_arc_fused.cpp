// The arc walk's tests (test_grid_tracing_arc.cpp) again, with multiply-adds fused (support/fused.hpp): a walk
// started anywhere the arc is above finds the same crossing, to rounding.
#define SSS_TEST_FUSED 1
#include "support/fused.hpp"

#include "test_grid_tracing_arc.cpp"
