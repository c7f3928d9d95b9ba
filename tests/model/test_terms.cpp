// The registry of physics terms (model/terms.hpp): every term's suffix reads back to the term, every parameter
// beyond the paper's is owned by exactly one term, and a variant's name lists its terms in registry order.
#include <algorithm>
#include <catch2/catch.hpp>
#include <hubbeam/scene.hpp>
#include <string>
#include <vector>

#include "terms.hpp"

using namespace hubbeam;

namespace {

/// A profile's extras.
Extras with_profile()
{
    return {.tabulated = true};
}

/// Extras that carry every term a variant can carry together (a profile excludes a taper).
Extras every_term(bool profile)
{
    Extras e = profile ? with_profile() : Extras{};
    e.tip = e.gravity = e.damping = true;
    if (!profile) e.taper = Taper::depth;
    return e;
}

}  // namespace

TEST_CASE("each registered term's suffix reads back to that term alone", "[terms]")
{
    for (const TermInfo& t : terms()) {
        for (bool profile : {false, true}) {
            const Extras all = every_term(profile);
            if (!t.carried(all)) continue;
            const std::string suffix = t.suffix(all);
            Extras read;
            INFO(t.name << ": " << suffix);
            CHECK(t.read_suffix(suffix, read));
            CHECK(t.carried(read));
            CHECK(carried_terms(read) == std::vector<const TermInfo*>{&t});
            CHECK(t.suffix(read) == suffix);
            for (const TermInfo& other : terms()) {
                Extras none;
                if (&other != &t) CHECK_FALSE(other.read_suffix(suffix, none));
            }
        }
    }
}

TEST_CASE("every parameter beyond the paper's and the fields' is owned by exactly one term, with its scene keys",
          "[terms]")
{
    for (std::size_t q = 0; q < param_count; ++q) {
        int owners = 0;
        for (const TermInfo& t : terms())
            owners += static_cast<int>(std::count(t.params.begin(), t.params.end(), Param(q)));
        INFO(param_names[q]);
        const bool of_fields = std::find(field_params.begin(), field_params.end(), Param(q)) != field_params.end();
        CHECK(owners == (q < paper_param_count || of_fields ? 0 : 1));
    }
    for (const TermInfo& t : terms())
        for (const TermSceneKey& k : t.scene_keys) {
            INFO(t.name << ": " << k.table << "." << k.key);
            CHECK(std::find(t.params.begin(), t.params.end(), k.param) != t.params.end());
            CHECK(std::string(k.table) == t.scene_keys.front().table);  // one table per term
        }
}

TEST_CASE("a variant's name lists its terms in registry order and parses back", "[terms]")
{
    for (bool profile : {false, true}) {
        VariantKey key{.method = Method::amm, .nx = 2, .ny = 4, .order = Order::first, .drive = Drive::torque};
        key.extras = every_term(profile);
        std::string expected = "amm_nx2_ny4_torque_first";
        for (const TermInfo* t : carried_terms(key.extras)) expected += "_" + t->suffix(key.extras);
        CHECK(key.name() == expected);
        CHECK(key.name() == (profile ? "amm_nx2_ny4_torque_first_tip_gravity_damped_profile"
                                     : "amm_nx2_ny4_torque_first_tip_gravity_damped_depth"));
        CHECK(VariantKey::parse(key.name()) == key);
    }
    CHECK_THROWS(VariantKey::parse("amm_nx2_ny4_torque_first_gravity_tip"));
}

TEST_CASE("a scene carries a term selected by values exactly when one of its parameters is nonzero", "[terms]")
{
    for (const TermInfo& t : terms()) {
        if (!t.selected_by_values) continue;
        for (Param q : t.params) {
            Scene s;
            CHECK_FALSE(t.carried(s.key().extras));
            value(s.parameters, q) = 0.5;
            INFO(t.name << ", " << param_names[index(q)]);
            CHECK(carried_terms(s.key().extras) == std::vector<const TermInfo*>{&t});
        }
    }
}
