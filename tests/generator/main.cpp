// Catch2's main for the generator tests, in its own translation unit so that both compile in parallel.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
