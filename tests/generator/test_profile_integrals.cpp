// A tabulated profile's hat functions in the generator's integrals (docs/model.md section 11.2): exact rationals for
// the polynomial bases, split at the stations; AMM's composite rule with the stations as panel boundaries, against
// a reference rule of the test's own with many more points per piece.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "../gauss_legendre.hpp"
#include "integrals.hpp"
#include "variant.hpp"

using namespace GiNaC;
using namespace hubbeam;
using namespace hubbeam::gen;

namespace {

using K = Factor::Kind;
/// Stations off every piece boundary of the bases below.
const std::vector<numeric> stations = {0, numeric(3, 10), numeric(11, 20), 1};

}  // namespace

TEST_CASE("hat functions integrate exactly, split at the stations", "[integrals][profile]")
{
    for (Method method : {Method::fem, Method::bim, Method::bsim}) {
        const int ny = 4;
        ShapeIntegrals in({method, Field::axial, 4}, {method, Field::transverse, ny}, stations);
        // int_0^1 N_k = (x_{k+1} - x_{k-1}) / 2 (one-sided at the ends), int_0^1 xi N_k its first moment.
        for (std::size_t k = 0; k < stations.size(); ++k) {
            const numeric lo = k == 0 ? stations[0] : stations[k - 1], hi = k + 1 == stations.size() ? stations[k] : stations[k + 1];
            const numeric& c = stations[k];
            INFO(hubbeam::to_string(method) << " station " << k);
            CHECK(in.integrate({{K::hat, static_cast<int>(k), 0, 0}}, 0) == (hi - lo) / 2);
            CHECK(in.integrate({{K::hat, static_cast<int>(k), 0, 0}}, 1) == ((c - lo) * (lo + 2 * c) + (hi - c) * (2 * c + hi)) / 6);
        }
        // The hats interpolate 1 and xi exactly: sum_k N_k f = f and sum_k x_k N_k f = xi f, for products of pieces
        // that change degree at other places than the stations.
        for (int j = 0; j < ny; ++j)
            for (const std::vector<Factor>& f : {std::vector<Factor>{{K::transverse, j, 0, 2}, {K::transverse, j, 0, 2}},
                                                 std::vector<Factor>{{K::transverse, j, 0, 0}, {K::axial, j, 0, 1}}}) {
                numeric ones = 0, moment = 0;
                for (std::size_t k = 0; k < stations.size(); ++k) {
                    std::vector<Factor> with = f;
                    with.push_back({K::hat, static_cast<int>(k), 0, 0});
                    const numeric v = in.integrate(with, 0);
                    ones += v;
                    moment += stations[k] * v;
                }
                INFO(hubbeam::to_string(method) << " j " << j);
                CHECK(ones == in.integrate(f, 0));
                CHECK(moment == in.integrate(f, 1));
            }
        // At the tip only the last station's hat is 1.
        CHECK(in.at_tip({{K::hat, 3, 0, 0}}) == 1);
        CHECK(in.at_tip({{K::hat, 2, 0, 0}}) == 0);
    }
}

TEST_CASE("AMM: hat-weighted integrals converge to round-off with the stations as panel boundaries", "[integrals][profile]")
{
    const int ny = 6;
    const FieldBasis transverse{Method::amm, Field::transverse, ny};
    ShapeIntegrals in({Method::amm, Field::axial, 0}, transverse, stations);
    // The reference: 60-point Gauss-Legendre on 40 equal parts of every station interval.
    const test::GaussRule rule = test::gauss_legendre(60);
    const auto hat = [](std::size_t k, double xi) {
        const auto x = [](std::size_t i) { return stations[i].to_double(); };
        if (k > 0 && xi >= x(k - 1) && xi <= x(k)) return (xi - x(k - 1)) / (x(k) - x(k - 1));
        if (k + 1 < stations.size() && xi >= x(k) && xi <= x(k + 1)) return (x(k + 1) - xi) / (x(k + 1) - x(k));
        return 0.0;
    };
    for (std::size_t k = 0; k < stations.size(); ++k)
        for (int i = 0; i < ny; ++i)
            for (int j = i; j < ny; ++j) {
                long double reference = 0.0L, size = 0.0L;
                for (std::size_t s = 0; s + 1 < stations.size(); ++s)
                    for (int part = 0; part < 40; ++part) {
                        const double a = stations[s].to_double(), b = stations[s + 1].to_double();
                        const double lo = a + (b - a) * part / 40, hi = a + (b - a) * (part + 1) / 40;
                        for (std::size_t g = 0; g < rule.x.size(); ++g) {
                            const double xi = 0.5 * (lo + hi) + 0.5 * (hi - lo) * rule.x[g];
                            const double term = 0.5 * (hi - lo) * rule.w[g] * hat(k, xi) * transverse.at(i, xi).d2 * transverse.at(j, xi).d2;
                            reference += term;
                            size += std::abs(term);
                        }
                    }
                const double got = in.integrate({{K::hat, static_cast<int>(k), 0, 0}, {K::transverse, i, 0, 2}, {K::transverse, j, 0, 2}}, 0)
                                       .to_double();
                INFO("station " << k << " i " << i << " j " << j << ": " << got << " against " << static_cast<double>(reference));
                CHECK(std::abs(got - static_cast<double>(reference)) < 1e-12 * static_cast<double>(size));
            }
}
