#pragma once
/// \file
/// Internal to scattering/sediments.hpp: how a sediment's name is normalised before it is looked up.
/// Not part of the API.

#include <cctype>
#include <string>
#include <string_view>

namespace sss::detail {
/// Lower case, with spaces, hyphens and slashes read as underscores ("Medium Sand" -> "medium_sand").
inline std::string normalise_sediment_name(std::string_view name) {
    std::string out;
    out.reserve(name.size());
    for (char ch : name) {
        const auto u = static_cast<unsigned char>(ch);
        out += (ch == ' ' || ch == '-' || ch == '/') ? '_' : static_cast<char>(std::tolower(u));
    }
    return out;
}
} // namespace sss::detail
