// A variant's name (model/variant.hpp): one name per key, so a zero count of the flapwise or twist field, which
// name() leaves out, is refused where a name spells it.
#include <catch2/catch.hpp>
#include <stdexcept>
#include <string>

#include "variant.hpp"

using namespace hubbeam;

TEST_CASE("a variant name with a zero nz or nt is refused: name() never writes one", "[variant]")
{
    for (const char* spelled : {"fem_nx0_ny8_nz0_torque_first", "fem_nx0_ny8_nt0_torque_first",
                                "fem_nx2_ny8_nz4_nt0_prescribed_first", "fem_nx2_ny8_nz0_nt2_prescribed_first"}) {
        INFO(spelled);
        // The key the spelling would stand for already has a name, without the zero count: accepting this one
        // would give that key two names (and two cache files, two table rows).
        std::string without = spelled;
        for (const char* zero : {"_nz0", "_nt0"})
            if (const auto at = without.find(zero); at != std::string::npos) without.erase(at, 4);
        const VariantKey key = VariantKey::parse(without);
        CHECK(key.name() == without);
        CHECK(key.name() != spelled);
        const std::string zero = std::string(spelled).find("_nz0") != std::string::npos ? "'nz0'" : "'nt0'";
        CHECK_THROWS_WITH(VariantKey::parse(spelled), Catch::Contains(zero + ": a zero count is left out of the name"));
    }
    // A nonzero count is read where it appears.
    const VariantKey blade = VariantKey::parse("fem_nx2_ny8_nz4_nt2_prescribed_first");
    CHECK(blade.nz == 4);
    CHECK(blade.nt == 2);
    CHECK(blade.name() == "fem_nx2_ny8_nz4_nt2_prescribed_first");
}
