// The object hierarchy's tests (test_object_set.cpp) again, with multiply-adds fused (support/fused.hpp): it finds
// every hit the brute-force search finds, at the same distance to rounding.
#define SSS_TEST_FUSED 1
#include "support/fused.hpp"

#include "test_object_set.cpp"
