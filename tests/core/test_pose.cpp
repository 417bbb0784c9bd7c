// Attitude conventions: yaw clockwise from north, pitch bow up, roll starboard down; body FRD to world ENU.

#include <doctest/doctest.h>

#include <cmath>
#include <initializer_list>

#include <sss/core/constants.hpp>
#include <sss/core/pose.hpp>

namespace {
using v3 = sss::vec3<double>;
void check_vec(const v3& a, const v3& b) {
    CHECK(a.x == doctest::Approx(b.x).epsilon(1e-12).scale(1));
    CHECK(a.y == doctest::Approx(b.y).epsilon(1e-12).scale(1));
    CHECK(a.z == doctest::Approx(b.z).epsilon(1e-12).scale(1));
}
const double deg = sss::pi_v<double> / 180.0;
} // namespace

TEST_CASE("a level towfish heading north looks forward to north, starboard to east, down to down") {
    const auto R = sss::body_to_world_rotation(0.0, 0.0, 0.0);
    check_vec(R * v3{1, 0, 0}, {0, 1, 0});
    check_vec(R * v3{0, 1, 0}, {1, 0, 0});
    check_vec(R * v3{0, 0, 1}, {0, 0, -1});
}

TEST_CASE("heading 90 degrees points the bow east and starboard south") {
    const auto R = sss::body_to_world_rotation(0.0, 0.0, 90 * deg);
    check_vec(R * v3{1, 0, 0}, {1, 0, 0});
    check_vec(R * v3{0, 1, 0}, {0, -1, 0});
}

TEST_CASE("positive roll puts the starboard side down, positive pitch the bow up") {
    const auto roll = sss::body_to_world_rotation(30 * deg, 0.0, 0.0);
    CHECK((roll * v3{0, 1, 0}).z == doctest::Approx(-std::sin(30 * deg)));
    const auto pitch = sss::body_to_world_rotation(0.0, 10 * deg, 0.0);
    CHECK((pitch * v3{1, 0, 0}).z == doctest::Approx(std::sin(10 * deg)));
}

TEST_CASE("the rotation is orthonormal and right-handed for any attitude") {
    for (double r : {-1.0, 0.3}) for (double p : {-0.7, 0.2}) for (double y : {0.0, 2.5, -3.0}) {
        const auto R = sss::body_to_world_rotation(r, p, y);
        const auto I = glm::transpose(R) * R;
        for (int i = 0; i < 3; ++i) for (int j = 0; j < 3; ++j) CHECK(I[i][j] == doctest::Approx(i == j ? 1.0 : 0.0).scale(1));
        CHECK(glm::determinant(R) == doctest::Approx(1.0));
    }
}
