// Section integrals by Gauss-Legendre on the common refinement of the stations and the bases' intervals.
#include "models/section_integrals.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>


namespace hubbeam {

namespace {

using generated::SectionFactor;
using generated::SectionIntegral;

/// The bases of a variant's four fields, by the factor kinds that name them.
struct Bases {
    FieldBasis axial, transverse, flap, twist;

    explicit Bases(const VariantKey& key)
        : axial(key.axial_basis()),
          transverse(key.transverse_basis()),
          flap(key.flap_basis()),
          twist(key.twist_basis())
    {
    }

    const FieldBasis& of(int kind) const
    {
        switch (kind) {
            case generated::axial_factor:
                return axial;
            case generated::transverse_factor:
            case generated::coupling_factor:
                return transverse;
            case generated::flap_factor:
            case generated::flap_coupling_factor:
                return flap;
            case generated::twist_factor:
                return twist;
        }
        throw std::invalid_argument("section integrals: unknown factor kind " + std::to_string(kind));
    }

    bool polynomial() const
    {
        const auto poly = [](const FieldBasis& b) { return b.size() == 0 || b.polynomial(); };
        return poly(axial) && poly(transverse) && poly(flap) && poly(twist);
    }
};

bool is_coupling(const SectionFactor& f)
{
    return f.kind == generated::coupling_factor || f.kind == generated::flap_coupling_factor;
}

/// The polynomial degree of a factor on one interval: H_ij integrates a product of two slopes.
int degree(const Bases& b, const SectionFactor& f)
{
    const int d = b.of(f.kind).degree();
    return is_coupling(f) ? 2 * d - 1 : std::max(0, d - f.deriv);
}

/// The cuts of [0, 1] on which every integrand is smooth (a polynomial, or analytic for AMM): the stations, where the
/// distributions have kinks, and the bases' intervals (AMM: equal panels narrow enough for its highest mode); and
/// `panels` equal ones, on each of which a pre-twist's 2 twist xi turns by at most 1 rad.
std::vector<double> cuts_of(const Bases& b, const std::vector<double>& stations, int panels)
{
    std::vector<double> cuts(stations.begin(), stations.end());
    cuts.insert(cuts.end(), {0.0, 1.0});
    for (int k = 1; k < panels; ++k) cuts.push_back(static_cast<double>(k) / panels);
    if (b.polynomial()) {
        for (const FieldBasis* f : {&b.axial, &b.transverse, &b.flap, &b.twist})
            for (int k = 1; f->size() > 0 && k < f->intervals(); ++k)
                cuts.push_back(static_cast<double>(k) / f->intervals());
    } else {
        const int panels = transcendental_panels(
            std::max({b.axial.size(), b.transverse.size(), b.flap.size(), b.twist.size()}));
        for (int k = 1; k < panels; ++k) cuts.push_back(static_cast<double>(k) / panels);
    }
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end(), [](double u, double v) { return v - u < 1e-14; }), cuts.end());
    cuts.back() = 1.0;
    return cuts;
}

/// A factor's values at the rule's nodes, and the nodes [first, last) outside which they are zero: a local basis's
/// support, where an integral's sum need only go (the stations make many nodes; a FEM function spans two elements).
struct Column {
    std::vector<double> v;
    std::size_t first = 0, last = 0;
};

/// The values of every factor at the rule's nodes, computed once per factor.
class FactorColumns {
public:
    /// coupling_points: the Gauss nodes of a piece that H_ij's integrand is interpolated through (more than its
    /// degree for the polynomial bases).
    FactorColumns(const Bases& b, const std::vector<double>& cuts, const std::vector<double>& nodes, int points,
                  int coupling_points)
        : b_(b), cuts_(cuts), points_(points), inner_(gauss_legendre(coupling_points)), nodes_(nodes)
    {
        // running_[g][r] = int_0^(t_g) l_r(t) dt: the Lagrange polynomial l_r of the inner nodes integrated from a
        // piece's start to its g-th node (both scaled to [0, 1]), by a Gauss rule exact for its degree.
        const QuadratureRule outer = gauss_legendre(points), exact = gauss_legendre(coupling_points);
        const std::vector<double>& t = inner_.nodes;
        running_.assign(static_cast<std::size_t>(points), std::vector<double>(t.size(), 0.0));
        for (std::size_t g = 0; g < outer.nodes.size(); ++g)
            for (std::size_t r = 0; r < t.size(); ++r)
                for (std::size_t s = 0; s < exact.nodes.size(); ++s) {
                    const double x = outer.nodes[g] * exact.nodes[s];
                    double l = 1.0;
                    for (std::size_t k = 0; k < t.size(); ++k)
                        if (k != r) l *= (x - t[k]) / (t[r] - t[k]);
                    running_[g][r] += outer.nodes[g] * exact.weights[s] * l;
                }
    }

    const Column& operator()(const SectionFactor& f)
    {
        const auto key = std::make_tuple(f.kind, f.i, is_coupling(f) ? f.j : 0, f.deriv);
        if (auto it = columns_.find(key); it != columns_.end()) return it->second;
        const FieldBasis& basis = b_.of(f.kind);
        if (f.i < 0 || f.i >= basis.size() || (is_coupling(f) && (f.j < 0 || f.j >= basis.size())) || f.deriv < 0 ||
            f.deriv > 2)
            throw std::invalid_argument("section integrals: a factor outside the variant's bases");
        std::vector<double> v(nodes_.size());
        if (!is_coupling(f)) {
            for (std::size_t q = 0; q < nodes_.size(); ++q) {
                const Jet<double> j = basis.at(f.i, nodes_[q]);
                v[q] = f.deriv == 0 ? j.v : f.deriv == 1 ? j.d1 : j.d2;
            }
        } else {
            coupling(basis, f, v);
        }
        Column c{std::move(v), 0, 0};
        while (c.first < c.v.size() && c.v[c.first] == 0.0) ++c.first;
        c.last = c.v.size();
        while (c.last > c.first && c.v[c.last - 1] == 0.0) --c.last;
        return columns_.emplace(key, std::move(c)).first->second;
    }

private:
    /// H_ij(xi) = int_0^xi phi_i' phi_j', piece by piece: its value at the piece's start plus the integral of the
    /// polynomial through phi_i' phi_j' at the piece's inner nodes, to each node (exact where the product is a
    /// polynomial of lower degree than their count; converged for AMM's smooth modes). Zero on the pieces before both
    /// slopes are nonzero, constant after: only the pieces where both are cost anything.
    void coupling(const FieldBasis& basis, const SectionFactor& f, std::vector<double>& v)
    {
        const int slope_kind =
            f.kind == generated::coupling_factor ? generated::transverse_factor : generated::flap_factor;
        const Column& a = (*this)({slope_kind, f.i, 0, 1});
        const Column& b = (*this)({slope_kind, f.j, 0, 1});
        const std::size_t P = static_cast<std::size_t>(points_);
        const std::size_t from = std::max(a.first, b.first) / P;
        const std::size_t to = std::max(from, (std::min(a.last, b.last) + P - 1) / P);  // pieces [from, to)
        std::vector<double> slopes(inner_.nodes.size());
        double whole = 0.0;
        for (std::size_t k = from; k < to; ++k) {
            const double lo = cuts_[k], h = cuts_[k + 1] - lo;
            for (std::size_t r = 0; r < slopes.size(); ++r) {
                const double x = lo + h * inner_.nodes[r];
                slopes[r] = basis.at(f.i, x).d1 * basis.at(f.j, x).d1;
            }
            for (std::size_t g = 0; g < P; ++g) {
                double part = 0.0;
                for (std::size_t r = 0; r < slopes.size(); ++r) part += running_[g][r] * slopes[r];
                v[k * P + g] = whole + h * part;
            }
            double full = 0.0;
            for (std::size_t r = 0; r < slopes.size(); ++r) full += inner_.weights[r] * slopes[r];
            whole += h * full;
        }
        for (std::size_t q = to * P; q < v.size(); ++q) v[q] = whole;
    }

    const Bases& b_;
    const std::vector<double>& cuts_;
    int points_;
    QuadratureRule inner_;
    std::vector<std::vector<double>> running_;
    const std::vector<double>& nodes_;
    std::map<std::tuple<int, int, int, int>, Column> columns_;
};

}  // namespace

std::vector<double> section_distribution(const VariantKey& key, const Parameters& p, SectionDistribution d)
{
    const std::size_t n = p.stations.size(), w = profile_value_count(key.out_of_plane());
    if (!tabulated(d)) throw std::logic_error("section integrals: the pre-twist's distributions are no table's");
    if (n == 0 || p.profile.size() != n * w)
        throw std::invalid_argument("section integrals: the profile holds " + std::to_string(p.profile.size()) +
                                    " values for " + std::to_string(n) + " stations, the variant " + key.name() +
                                    " needs " + std::to_string(w) + " per station");
    if (w < max_profile_value_count && d > SectionDistribution::ES)
        throw std::invalid_argument("section integrals: a planar profile has no distribution " +
                                    std::string(section_distribution_names[static_cast<std::size_t>(d)]));
    const bool offset = d >= SectionDistribution::mass_offset_cos;
    if (offset && p.offsets.size() != n * section_offset_count)
        throw std::invalid_argument("section integrals: the variant " + key.name() + " reads " +
                                    std::to_string(section_offset_count) + " section offsets per station, the " +
                                    "parameters hold " + std::to_string(p.offsets.size()) + " for " +
                                    std::to_string(n) + " stations");
    std::vector<double> out(n);
    for (std::size_t k = 0; k < n; ++k) {
        const auto v = [&](ProfileValue j) { return p.profile[w * k + static_cast<std::size_t>(j)]; };
        // The mass's first moment about the reference axis, towards the leading edge (the offset is towards the
        // trailing edge), along the chord turned by the station's angle and the pitch, which the variant reads here
        // rather than in its coefficients: cos and sin of the angle itself, not of twice it (docs/model.md 12.5).
        // The tension centre's offset weighs the axial stiffness alike (docs/model.md 12.6).
        const auto chord_angle = [&] { return (key.extras.pitch ? p.pitch : 0.0) + v(ProfileValue::twist); };
        const auto moment = [&](SectionOffset which, ProfileValue weight, bool sine) {
            const std::size_t at = section_offset_count * k + static_cast<std::size_t>(which);
            const double first = -v(weight) * p.offsets[at];
            const double angle = chord_angle();
            return first * (sine ? std::sin(angle) : std::cos(angle));
        };
        // The offset mass's second moment, m d^2, alone and turned by twice the chord's angle with the pitch: the
        // square of the chord's direction carries the second harmonics of the angle (docs/model.md 12.5).
        const auto second_moment = [&](int harmonic) {
            const double d = p.offsets[section_offset_count * k + static_cast<std::size_t>(SectionOffset::mass)];
            const double angle = 2.0 * chord_angle();
            const double md2 = v(ProfileValue::m) * d * d;
            return harmonic == 0 ? md2 : harmonic == 1 ? md2 * std::cos(angle) : md2 * std::sin(angle);
        };
        // The deviators turned by twice the tabulated angle of their axes: the chord's for the stiffness, the
        // principal inertia axes' for the mass moments (docs/model.md section 12.4).
        const auto turned = [&](double deviator, ProfileValue axes, bool sine) {
            const double angle = 2.0 * v(axes);
            return deviator * (sine ? std::sin(angle) : std::cos(angle));
        };
        // Read only for a blade's distributions: a planar profile holds 3 values a station.
        const auto stiffness = [&] { return (v(ProfileValue::EI) - v(ProfileValue::EI_flap)) / 2.0; };
        const auto inertia = [&] { return (v(ProfileValue::j_n) - v(ProfileValue::j_c)) / 2.0; };
        using D = SectionDistribution;
        switch (d) {
            case D::m: out[k] = v(ProfileValue::m); break;
            case D::EI: out[k] = v(ProfileValue::EI); break;
            case D::ES: out[k] = v(ProfileValue::ES); break;
            case D::EI_flap: out[k] = v(ProfileValue::EI_flap); break;
            case D::GJ: out[k] = v(ProfileValue::GJ); break;
            case D::j_p: out[k] = v(ProfileValue::j_c) + v(ProfileValue::j_n); break;
            case D::EI_cos: out[k] = turned(stiffness(), ProfileValue::twist, false); break;
            case D::EI_sin: out[k] = turned(stiffness(), ProfileValue::twist, true); break;
            case D::j_cos: out[k] = turned(inertia(), ProfileValue::inertia_twist, false); break;
            case D::j_sin: out[k] = turned(inertia(), ProfileValue::inertia_twist, true); break;
            case D::mass_offset_cos: out[k] = moment(SectionOffset::mass, ProfileValue::m, false); break;
            case D::mass_offset_sin: out[k] = moment(SectionOffset::mass, ProfileValue::m, true); break;
            case D::tension_offset_cos: out[k] = moment(SectionOffset::tension, ProfileValue::ES, false); break;
            case D::tension_offset_sin: out[k] = moment(SectionOffset::tension, ProfileValue::ES, true); break;
            case D::mass_offset2: out[k] = second_moment(0); break;
            case D::mass_offset2_cos: out[k] = second_moment(1); break;
            case D::mass_offset2_sin: out[k] = second_moment(2); break;
            default: break;
        }
    }
    return out;
}

namespace {

/// Which kinds of distribution the list integrates: a table's (linear between stations), the pre-twist's (cos and sin
/// of 2 twist xi). Throws std::invalid_argument for an entry no variant writes.
std::pair<bool, bool> kinds_of(const SectionIntegral* list, int count)
{
    bool table = false, twist = false;
    for (int n = 0; n < count; ++n) {
        const int d = list[n].distribution;
        if (d < 0 || d >= static_cast<int>(section_distribution_count))
            throw std::invalid_argument("section integrals: unknown distribution " + std::to_string(d));
        if (list[n].count < 0 || list[n].count > generated::max_section_factors)
            throw std::invalid_argument("section integrals: an integral of " + std::to_string(list[n].count) +
                                        " factors");
        (tabulated(static_cast<SectionDistribution>(d)) ? table : twist) = true;
    }
    return {table, twist};
}

/// The rule's points per interval and the slope products' interpolation points. Polynomial bases: enough points for
/// the integrands' highest degree (the distribution is linear there), so that the rule is exact; AMM: the points that
/// converge its modes on a panel.
std::pair<int, int> rule_points(const Bases& b, const SectionIntegral* list, int count, bool twist)
{
    if (!b.polynomial()) return {transcendental_points, transcendental_points};
    int highest = 0, slopes = 0;
    for (int n = 0; n < count; ++n) {
        const SectionIntegral& s = list[n];
        int d = 1 + s.power;
        for (int f = 0; f < s.count; ++f) {
            d += degree(b, s.factors[f]);
            if (is_coupling(s.factors[f])) slopes = std::max(slopes, 2 * b.of(s.factors[f].kind).degree() - 2);
        }
        highest = std::max(highest, d);
    }
    // 2 points - 1 >= highest; the coupling's points interpolate phi_i' phi_j' of degree `slopes` exactly.
    return {highest / 2 + 1 + (twist ? 8 : 0), slopes + 1};
}

/// Distribution `which` at the rule's nodes: a table's linear on each interval, which lies between two stations; the
/// pre-twist's cos or sin of 2 twist xi.
std::vector<double> at_nodes(const VariantKey& key, const Parameters& p, SectionDistribution which,
                             const std::vector<double>& nodes, const std::vector<double>& stations)
{
    std::vector<double> out(nodes.size());
    if (!tabulated(which)) {
        for (std::size_t q = 0; q < out.size(); ++q) {
            const double angle = 2.0 * p.twist * nodes[q];
            out[q] = which == SectionDistribution::cos_2twist ? std::cos(angle) : std::sin(angle);
        }
        return out;
    }
    const std::vector<double> v = section_distribution(key, p, which);
    std::size_t k = 0;
    for (std::size_t q = 0; q < out.size(); ++q) {
        const double x = nodes[q];
        while (k + 2 < stations.size() && x > stations[k + 1]) ++k;
        const double t = (x - stations[k]) / (stations[k + 1] - stations[k]);
        out[q] = (1.0 - t) * v[k] + t * v[k + 1];
    }
    return out;
}

}  // namespace

std::vector<double> section_integrals(const VariantKey& key, const SectionIntegral* list, int count,
                                      const Parameters& p)
{
    if (count == 0) return {};
    const auto [table, twist] = kinds_of(list, count);
    if (const std::string why = stations_problem(p.stations); table && !why.empty())
        throw std::invalid_argument("section integrals: " + why);
    const Bases b(key);
    const std::vector<double> stations = table ? p.stations : std::vector<double>{};
    // cos 2 twist xi and sin 2 twist xi turn by at most 1 rad on each piece: with 8 points more than the polynomial
    // part needs, what the rule misses of them is below 1e-20 of the integrand (Gauss's remainder for h omega <= 1).
    const int twist_panels = twist ? std::max(1, static_cast<int>(std::ceil(2.0 * std::abs(p.twist)))) : 1;
    const std::vector<double> cuts = cuts_of(b, stations, twist_panels);
    const auto [points, coupling_points] = rule_points(b, list, count, twist);
    const QuadratureRule rule = composite_gauss_legendre(cuts, points);
    FactorColumns columns(b, cuts, rule.nodes, points, coupling_points);
    // Each distribution at the nodes, and the weights times xi^power, once each.
    std::map<int, std::vector<double>> distributions, weighted;
    const auto distribution = [&](int d) -> const std::vector<double>& {
        if (auto it = distributions.find(d); it != distributions.end()) return it->second;
        const auto which = static_cast<SectionDistribution>(d);
        return distributions.emplace(d, at_nodes(key, p, which, rule.nodes, stations)).first->second;
    };
    const auto weights = [&](int power) -> const std::vector<double>& {
        if (auto it = weighted.find(power); it != weighted.end()) return it->second;
        std::vector<double> w(rule.nodes.size());
        for (std::size_t q = 0; q < w.size(); ++q) w[q] = rule.weights[q] * std::pow(rule.nodes[q], power);
        return weighted.emplace(power, std::move(w)).first->second;
    };
    std::vector<double> out(static_cast<std::size_t>(count));
    for (int n = 0; n < count; ++n) {
        const SectionIntegral& s = list[n];
        const std::vector<double>& d = distribution(s.distribution);
        const std::vector<double>& w = weights(s.power);
        std::array<const std::vector<double>*, generated::max_section_factors> factors{};
        std::size_t first = 0, last = rule.nodes.size();
        for (int f = 0; f < s.count; ++f) {
            const Column& c = columns(s.factors[f]);
            factors[static_cast<std::size_t>(f)] = &c.v;
            first = std::max(first, c.first);
            last = std::min(last, c.last);
        }
        double sum = 0.0;
        for (std::size_t q = first; q < last; ++q) {
            double v = w[q] * d[q];
            for (int f = 0; f < s.count; ++f) v *= (*factors[static_cast<std::size_t>(f)])[q];
            sum += v;
        }
        out[static_cast<std::size_t>(n)] = sum;
    }
    return out;
}

}  // namespace hubbeam
