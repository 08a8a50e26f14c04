// Catch2's runner, compiled only where the Catch2 package has no
// Catch2WithMain library (tests/CMakeLists.txt).
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
