// The readers of comma-separated option values (runtime/include/hubbeam/option_lists.hpp) shared by run --fields-at,
// modes, linearize and the benchmarks: numbers in any decimal form, methods, and DOF counts up to what a variant takes.
#include <catch2/catch.hpp>

#include <cmath>
#include <hubbeam/option_lists.hpp>
#include <string>
#include <vector>

#include "modes.hpp"

using namespace hubbeam;

TEST_CASE("a number in an option list may be written in any decimal form - zero is zero however written", "[options]")
{
    // The forms seq, printf and numpy write: "0.0" must mean what "0" means.
    for (const char* zero : {"0", "0.0", "0.", ".0", "0e0", "0.0e+00", "-0", "-0.0", "+0", "000"}) {
        INFO(zero);
        double v = 1.0;
        REQUIRE(parse_non_negative(zero, v));
        CHECK(v == 0.0);
        CHECK_FALSE(std::signbit(v));  // printed as 0, not -0
        CHECK_FALSE(parse_positive(zero, v));
    }
    for (const auto& [text, value] : std::vector<std::pair<const char*, double>>{
             {"4", 4.0}, {"4.5", 4.5}, {"+2.5", 2.5}, {"1e-3", 1e-3}, {"2.5E1", 25.0}, {"12.", 12.0}}) {
        INFO(text);
        double v = 0.0;
        REQUIRE(parse_positive(text, v));
        CHECK(v == value);
    }
    // Not numbers, not finite, not the whole item, or negative: refused.
    for (const char* bad : {"", " 4", "4 ", "4x", "x", "-0.5", "-1e-300", "inf", "-inf", "nan", "1e400", "0x10", "+",
                            "+-1", "--1", "1,2", "e3", "."}) {
        INFO('"' << bad << '"');
        double v = 0.0;
        CHECK_FALSE(parse_non_negative(bad, v));
    }
}

TEST_CASE("modes and linearize take spin rates written 0.0 as 0, also as the start of a range", "[options]")
{
    CHECK(parse_spin_rates("--omega", "0.0,4") == std::vector<double>{0.0, 4.0});
    CHECK(parse_spin_rates("--omega", "0e0") == std::vector<double>{0.0});
    CHECK(parse_spin_rates("--omega", "-0,0,0.0") == std::vector<double>{0.0});  // one rate, not three
    CHECK(parse_spin_rates("--omega", "0.0:1.0:0.5") == std::vector<double>{0.0, 0.5, 1.0});
    CHECK_THROWS_WITH(parse_spin_rates("--omega", "0.0,-1"),
                      "--omega: expected a comma-separated list of spin rates >= 0 (rad/s) or ranges FIRST:LAST:STEP, "
                      "got -1");
    CHECK_THROWS_AS(parse_spin_rates("--omega", "0:1:0.0"), ModesOptionError);  // a step must be > 0
}

TEST_CASE("method lists read every method word, each once, and name a bad one", "[options]")
{
    CHECK(parse_method_list<OptionError>("--methods", "bim,amm,bim") == std::vector<Method>{Method::bim, Method::amm});
    std::vector<Method> all;
    for (const std::string& w : words<Method>()) {
        Method m{};
        REQUIRE(parse(w, m));
        all.push_back(m);
    }
    std::string every;
    for (const std::string& w : words<Method>()) every += (every.empty() ? "" : ",") + w;
    CHECK(parse_method_list<OptionError>("--methods", every) == all);
    CHECK_THROWS_WITH(parse_method_list<OptionError>("--methods", "amm,,fem"),
                      "--methods: expected a comma-separated list of amm, fem, bim, bsim, got an empty item");
    CHECK_THROWS_AS(parse_method_list<ModesOptionError>("--methods", "AMM"), ModesOptionError);
}

TEST_CASE("a DOF list takes exactly the counts some variant can take, whatever the command", "[options]")
{
    // The limit is the variants' own: a count is worth reading when some method (and spline basis) accepts it as
    // Ny, and no method accepts a count above the list's limit.
    int largest_accepted = 0;
    for (int n = 1; n <= 200; ++n)
        for (const std::string& w : words<Method>())
            for (SplineBasis spline : {SplineBasis::paper, SplineBasis::open}) {
                VariantKey k;
                REQUIRE(parse(w, k.method));
                k.ny = n;
                k.nx = 0;
                k.spline = spline;
                if (k.dof_problem().empty()) largest_accepted = std::max(largest_accepted, n);
            }
    CHECK(largest_dof_count() == largest_accepted);
    const std::string top = std::to_string(largest_accepted);
    CHECK(parse_dof_list<OptionError>("--ny", "4,8," + top + ",4", 1) == std::vector<int>{4, 8, largest_accepted});
    CHECK(parse_dof_list<OptionError>("--nx", "0", 0) == std::vector<int>{0});
    CHECK_THROWS_WITH(parse_dof_list<OptionError>("--ny", std::to_string(largest_accepted + 1), 1),
                      "--ny: expected a comma-separated list of integers from 1 to " + top + ", got " +
                          std::to_string(largest_accepted + 1));
    CHECK_THROWS_WITH(parse_dof_list<OptionError>("--nx", "4.0", 0, "ny"),
                      "--nx: expected a comma-separated list of integers from 0 to " + top + " or ny, got 4.0");
    CHECK_THROWS_AS(parse_dof_list<OptionError>("--ny", "0", 1), OptionError);
}
