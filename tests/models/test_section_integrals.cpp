// A profile variant's run-time section integrals (docs/model.md section 11.2) against the test's own quadrature: each
// distribution built here from the table's columns, H_ij by its own running integral, long double Gauss-Legendre with
// 30 points on pieces cut at the stations and at every k/n up to n = 12 (the bases' breaks), so exact for the
// polynomial bases and converged for AMM.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <tuple>
#include <utility>
#include <random>
#include <vector>

#include "../gauss_legendre.hpp"
#include "models/section_integrals.hpp"

using namespace hubbeam;
using generated::SectionFactor;
using generated::SectionIntegral;

namespace {

const std::vector<double> stations = {0.0, 0.13, 0.3, 0.55, 0.71, 1.0};

/// A blade's table at the stations: every column different and varying, a chord angle that turns by more than a
/// radian; and a pre-twist of more than a radian (a variant has one or the other; the integrals take both).
Parameters blade_table()
{
    Parameters p;
    p.twist = -2.8;  // a propeller's pre-twist, far beyond a series in twist xi
    p.stations = stations;
    for (double x : stations)
        p.profile.insert(p.profile.end(), {0.4 - 0.2 * x + 0.1 * x * x, 900.0 - 500.0 * x, 7e6 * (1.0 - 0.4 * x),
                                           300.0 + 200.0 * x * (1.0 - x), 50.0 - 20.0 * x, 0.8 - 2.1 * x,
                                           0.01 + 0.02 * x, 0.04 - 0.01 * x, 0.3 - 1.9 * x});
    // The centre of mass's (m d as large as m) and the tension centre's, in the order of SectionOffset.
    for (double x : stations) p.offsets.insert(p.offsets.end(), {2.0 - x, 0.1 + 0.3 * x});
    return p;
}

/// Distribution d at xi from the table's columns (model.md sections 11.2 and 12.4), linear between stations; or the
/// pre-twist's cos 2 twist xi and sin 2 twist xi.
long double distribution(const Parameters& p, int d, long double xi)
{
    if (d == static_cast<int>(SectionDistribution::cos_2twist)) return std::cos(2.0L * p.twist * xi);
    if (d == static_cast<int>(SectionDistribution::sin_2twist)) return std::sin(2.0L * p.twist * xi);
    std::size_t k = 0;
    while (k + 2 < p.stations.size() && xi > p.stations[k + 1]) ++k;
    const long double t = (xi - p.stations[k]) / (p.stations[k + 1] - p.stations[k]);
    const auto at = [&](std::size_t s) {
        const double* v = &p.profile[9 * s];  // m, EI, ES, EI_flap, GJ, twist, j_c, j_n, inertia_twist
        const long double c = std::cos(2.0L * v[5]), sn = std::sin(2.0L * v[5]);
        const long double ci = std::cos(2.0L * v[8]), si = std::sin(2.0L * v[8]);  // the inertia axes'
        // The mass's first moment towards the leading edge (the offset is towards the trailing edge), along the chord.
        const long double moment = -v[0] * p.offsets[2 * s];
        // The axial stiffness's first moment about the reference axis at the tension centre, likewise.
        const long double tension = -v[2] * p.offsets[2 * s + 1];
        // The mass's second moment about the reference axis.
        const long double second = v[0] * p.offsets[2 * s] * p.offsets[2 * s];
        const long double values[] = {v[0],
                                      v[1],
                                      v[2],
                                      v[3],
                                      v[4],
                                      v[6] + v[7],
                                      (v[1] - v[3]) / 2 * c,
                                      (v[1] - v[3]) / 2 * sn,
                                      (v[7] - v[6]) / 2 * ci,
                                      (v[7] - v[6]) / 2 * si,
                                      0.0L,
                                      0.0L,
                                      moment * std::cos(static_cast<long double>(v[5])),
                                      moment * std::sin(static_cast<long double>(v[5])),
                                      tension * std::cos(static_cast<long double>(v[5])),
                                      tension * std::sin(static_cast<long double>(v[5])),
                                      second,
                                      second * c,
                                      second * sn};
        static_assert(std::size(values) == section_distribution_count);
        return values[d];
    };
    return (1 - t) * at(k) + t * at(k + 1);
}

/// The oracle's pieces: the stations and every k/n, n <= 12, each cut to at most 1/40 (AMM's modes).
std::vector<long double> pieces()
{
    std::vector<long double> cuts(stations.begin(), stations.end());
    for (int n = 1; n <= 12; ++n)
        for (int k = 1; k < n; ++k) cuts.push_back(static_cast<long double>(k) / n);
    for (int k = 1; k < 40; ++k) cuts.push_back(k / 40.0L);
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end(), [](long double a, long double b) { return b - a < 1e-15L; }),
               cuts.end());
    return cuts;
}

/// A node of the oracle's rule on [0, 1]: 30 Gauss-Legendre points on each piece, x its place, w its weight.
struct Node {
    long double x, w;
    std::size_t piece;
};

/// Appends the rule's nodes on [a, b] (a piece or a part of one).
void add_nodes(long double a, long double b, std::size_t piece, std::vector<Node>& out)
{
    static const test::GaussRule g = test::gauss_legendre(30);  // on [-1, 1]
    for (std::size_t j = 0; j < g.x.size(); ++j) out.push_back({(a + b) / 2 + (b - a) / 2 * g.x[j], (b - a) / 2 * g.w[j], piece});
}

/// Every node of the rule, piece by piece from 0 to 1: every integral below sums at these nodes in this order.
const std::vector<Node>& nodes()
{
    static const std::vector<Node> all = [] {
        const std::vector<long double> cuts = pieces();
        std::vector<Node> out;
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k) add_nodes(cuts[k], cuts[k + 1], k, out);
        return out;
    }();
    return all;
}

/// int_0^xi f for xi at every node (H_ij's running integral): the whole pieces below the node's piece summed once,
/// then its piece cut at the node, by the same rule; the same terms in the same order as summing from 0 for each xi.
template <class F>
std::vector<long double> running_integral(const F& f)
{
    const std::vector<long double> cuts = pieces();
    std::vector<long double> whole(cuts.size(), 0.0L);  // whole[k]: over the pieces before cut k
    long double sum = 0.0L;
    for (const Node& n : nodes()) whole[n.piece + 1] = sum += n.w * f(n.x);
    std::vector<long double> out;
    for (const Node& n : nodes()) {
        std::vector<Node> part;
        add_nodes(cuts[n.piece], n.x, n.piece, part);
        long double sum = whole[n.piece];
        for (const Node& m : part) sum += m.w * f(m.x);
        out.push_back(sum);
    }
    return out;
}

/// A factor at every node, from the variant's bases: phi^(deriv), or H_ij(xi) = int_0^xi phi_i' phi_j'. Computed once
/// per basis and factor: the oracle meets the same nodes for every integral.
const std::vector<long double>& factor(const VariantKey& key, const SectionFactor& f)
{
    static std::map<std::tuple<int, int, int, int, int, int>, std::vector<long double>> known;
    const bool coupling = f.kind == generated::coupling_factor || f.kind == generated::flap_coupling_factor;
    const FieldBasis b = f.kind == generated::axial_factor ? key.axial_basis()
                         : f.kind == generated::twist_factor ? key.twist_basis()
                         : f.kind == generated::flap_factor || f.kind == generated::flap_coupling_factor
                             ? key.flap_basis()
                             : key.transverse_basis();
    const auto k = std::make_tuple(static_cast<int>(key.method), b.size(), f.kind, f.i, f.j, f.deriv);
    if (auto it = known.find(k); it != known.end()) return it->second;
    std::vector<long double>& out = known[k];
    if (coupling)
        out = running_integral([&](long double x) {
            return static_cast<long double>(b.at(f.i, static_cast<double>(x)).d1) * b.at(f.j, static_cast<double>(x)).d1;
        });
    else
        for (const Node& n : nodes()) {
            const Jet<double> j = b.at(f.i, static_cast<double>(n.x));
            out.push_back(f.deriv == 0 ? j.v : f.deriv == 1 ? j.d1 : j.d2);
        }
    return out;
}

/// Integrals of every distribution (or the tables' alone) and power 0 to 2 times products of each kind of factor the
/// energies meet.
std::vector<SectionIntegral> integrals(bool with_twist)
{
    using G = SectionFactor;
    const std::vector<std::vector<G>> products = {
        {},
        {{generated::axial_factor, 1, 0, 1}},
        {{generated::axial_factor, 0, 0, 0}, {generated::transverse_factor, 1, 0, 0}},
        {{generated::transverse_factor, 0, 0, 2}, {generated::transverse_factor, 2, 0, 2}},
        {{generated::flap_factor, 1, 0, 2}, {generated::transverse_factor, 1, 0, 2}},
        {{generated::twist_factor, 0, 0, 1}, {generated::twist_factor, 1, 0, 1}},
        {{generated::coupling_factor, 0, 2, 0}},
        {{generated::flap_coupling_factor, 1, 1, 0}, {generated::transverse_factor, 3, 0, 0}},
        {{generated::coupling_factor, 1, 3, 0}, {generated::flap_coupling_factor, 0, 1, 0}},
        {{generated::coupling_factor, 0, 0, 0}, {generated::coupling_factor, 1, 2, 0}, {generated::axial_factor, 1, 0, 1}},
    };
    std::vector<SectionIntegral> list;
    for (int d = 0; d < static_cast<int>(section_distribution_count); ++d) {
        if (!with_twist && !tabulated(static_cast<SectionDistribution>(d))) continue;
        for (int power = 0; power <= 2; ++power)
            for (const std::vector<G>& f : products) {
                SectionIntegral s{d, power, static_cast<int>(f.size()), {}};
                for (std::size_t i = 0; i < f.size(); ++i) s.factors[i] = f[i];
                list.push_back(s);
            }
    }
    return list;
}

}  // namespace

TEST_CASE("section integrals: exact for the polynomial bases and converged for AMM, on irregular stations",
          "[profile][section_integrals]")
{
    const Parameters p = blade_table();
    // Each distribution at every node of the rule, once for every section.
    static const std::vector<std::vector<long double>> distributions = [&p] {
        std::vector<std::vector<long double>> out(section_distribution_count);
        for (std::size_t d = 0; d < out.size(); ++d)
            for (const Node& node : nodes()) out[d].push_back(distribution(p, static_cast<int>(d), node.x));
        return out;
    }();
    // With the pre-twist's distributions the rule takes more points: the tables' alone must be exact with fewer.
    // Ny = Nz = 10 for the local bases as well: their first functions' H_ij is constant beyond their support.
    const std::pair<Method, int> bases[] = {{Method::amm, 4}, {Method::fem, 4}, {Method::bim, 4},
                                            {Method::bsim, 4}, {Method::fem, 10}, {Method::bsim, 10}};
    for (bool with_twist : {true, false})
    for (const auto& [method, n] : bases) {
        const VariantKey key{.method = method, .nx = 3, .ny = n, .nz = n, .nt = 3, .extras = {.tabulated = true, .offsets = true}};
        const std::vector<SectionIntegral> list = integrals(with_twist);
        SECTION(key.name() + (with_twist ? " with a pre-twist" : ""))
        {
            const std::vector<double> got = section_integrals(key, list.data(), static_cast<int>(list.size()), p);
            REQUIRE(got.size() == list.size());
            for (std::size_t n = 0; n < list.size(); ++n) {
                const SectionIntegral& s = list[n];
                const std::vector<long double>* factors[generated::max_section_factors] = {};
                for (int f = 0; f < s.count; ++f) factors[f] = &factor(key, s.factors[f]);
                // Against the integral of |integrand|: round-off is relative to the terms summed, not to a sum that
                // cancels.
                long double want = 0.0L, size = 0.0L;
                for (std::size_t i = 0; i < nodes().size(); ++i) {
                    const Node& node = nodes()[i];
                    long double v = std::pow(node.x, s.power) * distributions[static_cast<std::size_t>(s.distribution)][i];
                    for (int f = 0; f < s.count; ++f) v *= (*factors[f])[i];
                    want += node.w * v;
                    size += node.w * std::abs(v);
                }
                INFO("integral " << n << ": distribution " << s.distribution << ", power " << s.power << ", "
                                 << s.count << " factors: " << got[n] << " against " << static_cast<double>(want));
                INFO("off by " << std::abs(got[n] - static_cast<double>(want)) / static_cast<double>(size) << " of "
                               << static_cast<double>(size));
                // 5e-13: a product of two coupling functions H_ij, each a running integral by its own rule, carries
                // round-off of 5e-14 to 1.3e-13 of its size for the 14 distributions that are largest near the root
                // (FEM Ny = 10), up to 3.6e-13 for the tension centre's sine, which grows towards the tip, where the
                // H_ij are largest, and changes sign on the way.
                CHECK(std::abs(got[n] - static_cast<double>(want)) <= 5e-13 * static_cast<double>(size));
            }
        }
    }
}

TEST_CASE("section integrals: a planar table has m, EI and ES only, and a table must fit the variant",
          "[profile][section_integrals]")
{
    Parameters p;
    p.stations = {0.0, 0.5, 1.0};
    p.profile = {1.0, 2.0, 3.0, 1.0, 2.0, 3.0, 1.0, 2.0, 3.0};
    const VariantKey planar{.method = Method::fem, .nx = 0, .ny = 2, .extras = {.tabulated = true}};
    const SectionIntegral mass{0, 1, 0, {}}, twist{static_cast<int>(SectionDistribution::GJ), 0, 0, {}};
    // int_0^1 xi m = 1/2 for a constant m = 1.
    CHECK(section_integrals(planar, &mass, 1, p).at(0) == Approx(0.5).epsilon(1e-15));
    CHECK_THROWS_WITH(section_integrals(planar, &twist, 1, p), Catch::Contains("a planar profile has no distribution GJ"));
    p.profile.pop_back();
    CHECK_THROWS_WITH(section_integrals(planar, &mass, 1, p), Catch::Contains("holds 8 values for 3 stations"));
    p.stations = {0.0, 0.6, 0.5};
    CHECK_THROWS_WITH(section_integrals(planar, &mass, 1, p), Catch::Contains("the stations must"));
}
