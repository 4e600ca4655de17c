#include <catch2/catch.hpp>
TEST_CASE("vmas placeholder") { CHECK(true); }
