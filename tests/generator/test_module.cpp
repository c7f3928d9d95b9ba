// What the generator hands to the runtime's loader: the table row by field name with the interface version first,
// the interface header written beside an on-demand source, and the one reading order of state monomials.
#include <catch2/catch.hpp>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "generated_abi.h"
#include "monomial_order.hpp"
#include "structure.hpp"
#include "variant_source.hpp"

using namespace hubbeam;
using namespace hubbeam::gen;

TEST_CASE("the interface header a module is compiled with is model/generated_abi.h", "[module]")
{
    std::ifstream in(std::string(HUBBEAM_SOURCE_DIR) + "/model/generated_abi.h");
    REQUIRE(in);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(abi_header() == text);
}

TEST_CASE("a variant's row names its fields, the interface version first", "[module]")
{
    const VariantKey key = VariantKey::parse("amm_nx0_ny2_prescribed_zero");
    const std::string source = variant_source(key);
    const std::smatch::size_type none = 0;
    std::smatch row;
    REQUIRE(std::regex_search(source, row, std::regex("extern const Variant amm_nx0_ny2_prescribed_zero = \\{\\n"
                                                      "([^}]*)\\};")));
    const std::string fields = row[1];
    CHECK(fields.rfind("    .abi_version = " + std::to_string(generated::abi_version) + ",\n", 0) == none);
    CHECK(fields.find("    .name = \"amm_nx0_ny2_prescribed_zero\",\n") != std::string::npos);
    CHECK(fields.find("    .nq = 2,\n") != std::string::npos);
    // Every line sets one field by name: no value by position.
    const std::regex field("    \\.[a-z_]+ = [^\\n]+,\\n");
    CHECK(std::regex_replace(fields, field, "").empty());
    CHECK(module_entry_source(key.name()).find("hubbeam_variant()") != std::string::npos);
}

TEST_CASE("state monomials read by degree, then earlier variables' higher powers first", "[module]")
{
    // x^2 (2,0), x y (1,1), y^2 (0,2), x (1,0), y (0,1), 1 (0,0), shuffled.
    std::vector<Exponents> m = {{0, 2}, {1, 0}, {0, 0}, {1, 1}, {0, 1}, {2, 0}};
    sort_reading(m);
    CHECK(m == std::vector<Exponents>{{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}});
    // The term matrix lists Q's monomials in that order (the emitter's temporaries follow it too).
    Poly q0, q1;
    const Coefficient one{{Exponents{}, GiNaC::numeric(1)}};
    q0.add({0, 2}, one);
    q0.add({1, 0}, one);
    q1.add({2, 0}, one);
    q1.add({1, 0}, one);
    const TermMatrix t = term_matrix({q0, q1}, 0);
    std::vector<Exponents> order;
    for (const Poly& p : t.terms) order.push_back(p.terms().begin()->first);
    CHECK(order == std::vector<Exponents>{{1, 0}, {2, 0}, {0, 2}});
}
