# sss_target_options(<target>): the compile settings of sss's own targets (tests, header checks,
# benchmarks, examples). Consumers of sss::sss never see these flags.
#   -Wall -Wextra -Wpedantic -Wconversion always; -Werror with SSS_WERROR; -march=native with SSS_NATIVE.
# With -march=native the compiler may fuse a*b+c into one rounding (GCC and Clang do by default where the machine
# has FMA), and fuse the same expression differently where it is inlined into different code. The tests check that
# different paths give the same hits and lines bit for bit (a column at once against one ray at a time, a walk guided
# by a neighbour against a plain one), which needs each expression rounded the same way everywhere: SSS_NATIVE keeps
# multiply-adds unfused (-ffp-contract=off).

function(sss_target_options target)
    target_link_libraries(${target} PRIVATE sss::sss)
    set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
    if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
        target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wconversion)
        if(SSS_WERROR)
            target_compile_options(${target} PRIVATE -Werror)
        endif()
        if(SSS_NATIVE)
            target_compile_options(${target} PRIVATE -march=native -ffp-contract=off)
        endif()
    elseif(MSVC)
        target_compile_options(${target} PRIVATE /W4 /permissive-)
        if(SSS_WERROR)
            target_compile_options(${target} PRIVATE /WX)
        endif()
    endif()
endfunction()

# sss_sanitize(<target>): AddressSanitizer + UBSan when SSS_SANITIZE is on (tests only). Every report is fatal
# (-fno-sanitize-recover=all), so a test that trips a sanitizer fails rather than printing and passing.
# Pair it with a light optimisation, e.g. -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-Og: with both
# sanitizers -Og compiles in about 60 % of -O1's time and the tests run about 15 % slower, a shorter build and run.
# SSS_SANITIZE_SKIP names UBSan checks to leave out (-fno-sanitize=..., comma-separated). CI's sanitizer build
# (Meson's, README) leaves out alignment, null and vptr: about a quarter of the sanitizer build's compile time (10 to 45 % a file; vptr instruments every
# member access of the standard library's and doctest's polymorphic classes), for little here: sss declares no
# virtual function, reads file bytes as unsigned char (a mapped height field is mapped from offset 0, aligned), and a
# null pointer dereferenced is a fault AddressSanitizer reports (a reference bound to null, or a member function
# called through one, is what goes unseen). The fuzz targets (tests/fuzz/run.sh) keep every check.
function(sss_sanitize target)
    if(SSS_SANITIZE)
        target_compile_options(${target} PRIVATE
            -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
        if(NOT SSS_SANITIZE_SKIP STREQUAL "")
            string(REPLACE ";" "," skip "${SSS_SANITIZE_SKIP}")
            target_compile_options(${target} PRIVATE "-fno-sanitize=${skip}")
        endif()
        target_link_options(${target} PRIVATE -fsanitize=address,undefined -fno-sanitize-recover=all)
    endif()
endfunction()
