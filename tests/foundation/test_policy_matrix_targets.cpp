// The scattering policies for objects (hard_target, and by_material over Jackson's seabed and hard targets) render a
// flat seabed within 0.2 dB RMS (1 dB worst) of the independent oracle at the library's default ray density, in
// float and double, each with every propagation, beam and motion policy at least once (sss_test::target_matrix).

#include "support/policy_matrix_check.hpp"

TEST_CASE_TEMPLATE_DEFINE("flat seabed render with a target scattering model matches the quadrature oracle within "
                          "0.2 dB RMS",
                          Combo, target_matrix_id) {
    sss_test::check_against_oracle<Combo>();
}

TEST_CASE_TEMPLATE_APPLY(target_matrix_id, sss_test::target_matrix<double>);
TEST_CASE_TEMPLATE_APPLY(target_matrix_id, sss_test::target_matrix<float>);
