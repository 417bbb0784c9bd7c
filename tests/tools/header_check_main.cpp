// Entry point of the header self-containment check. Also checks that sss/version.hpp agrees with the
// version the build system declares (project(... VERSION) / project(..., version:)), passed in as
// SSS_PROJECT_VERSION.
#include <string_view>

#if defined(SSS_PROJECT_VERSION) && __has_include(<sss/version.hpp>)
#include <sss/version.hpp>
static_assert(std::string_view(sss::version_string) == std::string_view(SSS_PROJECT_VERSION),
              "sss/version.hpp and the build system's project version differ");
#endif

int main() { return 0; }
