#pragma once
/// \file
/// Internal to the motion policies: the check of the nominal track they share. Not part of the API.

#include <string>

#include "sss/core/error.hpp"

namespace sss::motion::detail {
/// Validates the nominal track every motion policy shares (start_m, heading_deg, speed_mps, altitude_m,
/// ping_interval_s), naming each field after `who`.
template <class Params> void validate_nominal_track(const Params& p, const std::string& who) {
    sss::require_finite(p.start_m.x, who + ".start_m.x");
    sss::require_finite(p.start_m.y, who + ".start_m.y");
    sss::require_finite(p.heading_deg, who + ".heading_deg");
    sss::require_non_negative(p.speed_mps, who + ".speed_mps");
    sss::require_positive(p.altitude_m, who + ".altitude_m");
    sss::require_positive(p.ping_interval_s, who + ".ping_interval_s");
}
} // namespace sss::motion::detail
