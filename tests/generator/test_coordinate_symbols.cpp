// The generator's coordinate symbols follow the layout (model/coordinates.hpp): q's symbols are named as the
// layout names its coordinates, in its order, and the rates likewise with "_dot" (the hub angle's: theta_dot).
#include <catch2/catch.hpp>

#include <string>

#include "coordinates.hpp"
#include "energy.hpp"

using namespace hubbeam;
using namespace hubbeam::gen;

TEST_CASE("coordinates: the generator's q and qd are the layout's coordinates in its order", "[coordinates]")
{
    for (const char* name : {"fem_nx4_ny4_torque_first", "bim_nx3_ny5_prescribed_first", "amm_nx0_ny4_torque_first",
                             "bsim_nx0_ny4_prescribed_first"}) {
        INFO(name);
        const VariantKey key = VariantKey::parse(name);
        const std::vector<std::string> names = coordinate_layout(key).names();
        const Symbols s(key);
        REQUIRE(s.q.size() == names.size());
        REQUIRE(s.qd.size() == names.size());
        for (std::size_t i = 0; i < names.size(); ++i) {
            CHECK(s.q[i].get_name() == names[i]);
            CHECK(s.qd[i].get_name() == names[i] + "_dot");
        }
    }
}
