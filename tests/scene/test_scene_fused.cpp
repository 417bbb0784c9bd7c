// The scene tests (test_scene.cpp) again, with multiply-adds fused (support/fused.hpp). No hit may rest on one
// computation rounding as another does: an object hierarchy that solved its nearest primitive again, with the
// distance found as the limit, would lose the hit wherever the second solution came out an ulp farther, and the
// scene would return the seabed behind the object (with GCC 12, three of the 4000 rays of the test over a height
// field, in double).
#define SSS_TEST_FUSED 1
#include "support/fused.hpp"

#include "test_scene.cpp"
