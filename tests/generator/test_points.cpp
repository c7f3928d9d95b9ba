// Order full's quadrature points: the rule integrates the foreshortening terms' integrands (products of H(x) with
// H(x) and with the shape functions) exactly for the polynomial bases and to round-off for AMM, against the
// integrals stage (exact rationals, or its far finer composite rule).
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

#include "integrals.hpp"
#include "points.hpp"

using namespace hubbeam;
using namespace hubbeam::gen;

TEST_CASE("points: the rule integrates order full's integrands exactly (polynomial) or to round-off (AMM)", "[points]")
{
    using K = Factor::Kind;
    for (const char* name : {"fem_nx2_ny4_torque_full", "bim_nx3_ny5_torque_full", "bsim_nx3_ny6_prescribed_full",
                             "amm_nx0_ny8_torque_full", "amm_nx4_ny16_torque_full"}) {
        const VariantKey key = VariantKey::parse(name);
        SECTION(name)
        {
            const FieldBasis axial = key.axial_basis(), transverse = key.transverse_basis();
            ShapeIntegrals integrals(axial, transverse);
            const PointRule rule = point_rule(key);
            CHECK(rule.exact == transverse.polynomial());
            std::vector<std::vector<double>> H;
            for (double xi : rule.xi) H.push_back(coupling_at(transverse, xi));
            const int n = key.ny, top = n - 1, next = n - 2;
            const auto h = [&](std::size_t g, int i, int j) { return H[g][static_cast<std::size_t>(i * n + j)]; };
            // The heaviest terms: u_x2^2 (two H), u_x1 u_x2 (axial times H), u_y u_x2_dot (two shapes times H), for the
            // highest modes, whose products oscillate fastest.
            struct Case {
                std::vector<Factor> factors;
                std::function<double(std::size_t)> at;
            };
            std::vector<Case> cases = {
                {{{K::coupling, top, top, 0}, {K::coupling, top, top, 0}}, [&](std::size_t g) { return h(g, top, top) * h(g, top, top); }},
                {{{K::coupling, next, top, 0}, {K::coupling, top, next, 0}}, [&](std::size_t g) { return h(g, next, top) * h(g, top, next); }},
                {{{K::transverse, top, 0, 0}, {K::transverse, next, 0, 0}, {K::coupling, top, top, 0}},
                 [&](std::size_t g) { return transverse.at(top, rule.xi[g]).v * transverse.at(next, rule.xi[g]).v * h(g, top, top); }},
            };
            if (key.nx > 0)
                cases.push_back({{{K::axial, key.nx - 1, 0, 0}, {K::coupling, top, top, 0}},
                                 [&](std::size_t g) { return axial.at(key.nx - 1, rule.xi[g]).v * h(g, top, top); }});
            for (const Case& c : cases) {
                double sum = 0.0, magnitude = 0.0;
                for (std::size_t g = 0; g < rule.xi.size(); ++g) {
                    sum += rule.weight[g] * c.at(g);
                    magnitude += rule.weight[g] * std::abs(c.at(g));
                }
                const double reference = integrals.integrate(c.factors, 0).to_double();
                INFO(name << ": " << rule.xi.size() << " points, sum " << sum << ", reference " << reference);
                CHECK(std::abs(sum - reference) < 1e-13 * magnitude);
            }
        }
    }
}
