// The translation unit that carries the tests' precompiled header (tests/CMakeLists.txt, SSS_TEST_PCH): the
// header is compiled with this target's flags, and every test program reuses it.
