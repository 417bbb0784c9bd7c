# Provides the target glm::glm. GLM's own package config is used when it exists (Debian's
# libglm-dev ships one in /usr/share/cmake/glm); otherwise the header directory is looked up
# and wrapped in an imported target. Sets sss_GLM_FOUND.
# Used both by sss's CMakeLists.txt and by the installed sssConfig.cmake.

set(sss_GLM_FOUND FALSE)
if(NOT TARGET glm::glm)
    find_package(glm CONFIG QUIET)
endif()
if(NOT TARGET glm::glm)
    find_path(SSS_GLM_INCLUDE_DIR NAMES glm/glm.hpp
              DOC "Directory containing glm/glm.hpp")
    if(SSS_GLM_INCLUDE_DIR)
        add_library(glm::glm INTERFACE IMPORTED)
        set_target_properties(glm::glm PROPERTIES
            INTERFACE_INCLUDE_DIRECTORIES "${SSS_GLM_INCLUDE_DIR}")
    endif()
endif()
if(TARGET glm::glm)
    set(sss_GLM_FOUND TRUE)
elseif(NOT sss_GLM_OPTIONAL)
    message(FATAL_ERROR "sss needs GLM (https://github.com/g-truc/glm): install it "
                        "(Debian/Ubuntu: libglm-dev) or set SSS_GLM_INCLUDE_DIR.")
endif()
