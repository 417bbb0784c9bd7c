// Every combination of shipped policies with straight propagation, in float and double, renders a flat seabed within
// 0.2 dB RMS (1 dB worst) of the independent oracle at the library's default ray density.

#include "support/policy_matrix_check.hpp"

TEST_CASE_TEMPLATE_DEFINE("flat seabed render matches the quadrature oracle within 0.2 dB RMS", Combo, policy_matrix_id) {
    sss_test::check_against_oracle<Combo>();
}

using matrix_double = sss_test::policy_matrix_with<double, sss::propagation::straight<double>>;
using matrix_float = sss_test::policy_matrix_with<float, sss::propagation::straight<float>>;
TEST_CASE_TEMPLATE_APPLY(policy_matrix_id, matrix_double);
TEST_CASE_TEMPLATE_APPLY(policy_matrix_id, matrix_float);
