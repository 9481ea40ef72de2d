// One Catch2 main shared by every test executable of the suite.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
