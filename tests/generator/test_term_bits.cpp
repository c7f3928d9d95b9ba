// The terms' registry bits (model/terms.hpp) against what each term's energy module adds: the runtime decides a
// variant's structure from the bits (dissipates, potential_reads_angle), so each must say what the derived energies
// hold, term by term.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "energy.hpp"
#include "terms.hpp"

using namespace GiNaC;
using namespace hubbeam;
using namespace hubbeam::gen;

namespace {

/// What a term needs carried beside it: a blade table's offsets ride on its profile.
Extras companions(const TermInfo& t)
{
    Extras e;
    e.offsets = true;
    Extras base;
    if (t.carried(e)) base.tabulated = true;
    return base;
}

/// Extras carrying the term t alone, with its companions.
Extras alone(const TermInfo& t)
{
    Extras e = companions(t);
    if (e.tabulated) {
        e.offsets = true;
        std::vector<const TermInfo*> want = carried_terms(companions(t));
        want.push_back(&t);
        REQUIRE(carried_terms(e) == want);
        return e;
    }
    t.set(e, true);
    if (!t.carried(e)) {  // a term chosen by the scene's words: the taper's or the profile's
        e.taper = Taper::width;
        if (!t.carried(e)) {
            e.taper = Taper::uniform;
            e.tabulated = true;
        }
        if (!t.carried(e)) {  // the moving hub's, chosen by a [support] table
            e.tabulated = false;
            e.hub = true;
        }
    }
    REQUIRE(carried_terms(e) == std::vector<const TermInfo*>{&t});
    return e;
}

/// The energies of key with every parameter symbol a parameter and the drive, angle and state symbols variables.
struct Derived {
    Energies en;
    std::vector<symbol> parameters, variables;
    int sin_theta = -1, cos_theta = -1;
};
Derived derived(const VariantKey& key, const Symbols& s)
{
    Derived d;
    d.parameters = s.parameters();
    d.variables = {s.tau, s.theta_dot, s.theta_ddot, s.sin_theta, s.cos_theta};
    d.sin_theta = 3;
    d.cos_theta = 4;
    d.variables.insert(d.variables.end(), s.q.begin(), s.q.end());
    d.variables.insert(d.variables.end(), s.qd.begin(), s.qd.end());
    d.en = derive_energies(key, s, PolyReader(d.parameters, d.variables));
    return d;
}

}  // namespace

TEST_CASE("each term's registry bits say what its energies add: D, an angle in U, T and U", "[terms][energy]")
{
    // In the plane and on a blade (flapwise and twist fields), where the section's pitch, pre-twist and precone act:
    // in the plane the beam's T and U do not see them.
    for (const auto& [drive, blade] : {std::pair{Drive::prescribed, 0}, {Drive::torque, 0}, {Drive::prescribed, 2}}) {
        for (const TermInfo& t : terms()) {
            VariantKey key{.method = Method::fem,
                           .nx = 2,
                           .ny = 2,
                           .nz = blade,
                           .nt = blade,
                           .order = Order::first,
                           .drive = drive};
            key.extras = alone(t);
            if (!key.dof_problem().empty()) continue;  // a moving hub under a prescribed angle: refused
            INFO(t.name << ", " << key.name());
            const Symbols s(key);
            const Derived d = derived(key, s);
            // The same variant without the term, over the same symbols: what the term adds is the difference.
            VariantKey bare = key;
            bare.extras = companions(t);
            const Energies b = derive_energies(bare, s, PolyReader(d.parameters, d.variables));
            const auto differs = [&](const Poly& with, const Poly& without) {
                return !(to_ex(with, d.parameters, d.variables) - to_ex(without, d.parameters, d.variables))
                            .expand()
                            .is_zero();
            };
            CHECK(dissipates(key) == !d.en.D.is_zero());
            CHECK(((t.energies & adds_D) != 0) == !d.en.D.is_zero());
            // Under torque the angle is q[0] and sin_theta, cos_theta stand for functions of it: still read.
            const bool angle = d.en.U.has(d.sin_theta) || d.en.U.has(d.cos_theta);
            CHECK(potential_reads_angle(key) == angle);
            CHECK(((t.energies & reads_hub_angle) != 0) == angle);
            const bool kinetic_angle = d.en.T.has(d.sin_theta) || d.en.T.has(d.cos_theta);
            CHECK(((t.energies & kinetic_reads_angle) != 0) == kinetic_angle);
            CHECK(kernels_read_angle(key) == (angle || kinetic_angle));
            CHECK(reads_driven_angle(key) == ((angle || kinetic_angle) && drive == Drive::prescribed));
            CHECK(shaped_section(key) == ((t.energies & shapes_section) != 0 || shaped_section(bare)));
            if ((t.energies & shapes_section) == 0 && blade > 0) {
                CHECK(((t.energies & adds_T) != 0) == differs(d.en.T, b.T));
                CHECK(((t.energies & adds_U) != 0) == differs(d.en.U, b.U));
            }
        }
    }
}
