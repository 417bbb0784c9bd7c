// The composite objects' tests (test_object.cpp) again, with multiply-adds fused (support/fused.hpp).
#define SSS_TEST_FUSED 1
#include "support/fused.hpp"

#include "test_object.cpp"
