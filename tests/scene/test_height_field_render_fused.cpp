// The rendering tests over height fields (test_height_field_render.cpp) again, with multiply-adds fused
// (support/fused.hpp): guided rays and columns narrowed to their rectangle give the plain lines to rounding.
#define SSS_TEST_FUSED 1
#include "support/fused.hpp"

#include "test_height_field_render.cpp"
