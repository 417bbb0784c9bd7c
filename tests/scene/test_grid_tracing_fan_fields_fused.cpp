// The fan sweep's tests (test_grid_tracing_fan_fields.cpp) again, with multiply-adds fused (support/fused.hpp): the
// root on a segment, evaluated again after the sweep, must not lose a hit where it rounds otherwise.
#define SSS_TEST_FUSED 1
#include "support/fused.hpp"

#include "test_grid_tracing_fan_fields.cpp"
