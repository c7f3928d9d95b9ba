// Catch2's main for both test programs (hubbeam_tests, generator_tests), in its own translation unit so that
// test files recompile quickly.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
