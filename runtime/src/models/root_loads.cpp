// Root loads by force summation (docs/model.md section 13.3): d'Alembert's inertial forces and the weight on the
// blade, summed with their moments about the root, the blade's accelerations from the model's own qdd.
#include "models/root_loads.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <hubbeam/fields.hpp>
#include "models/rotor_model.hpp"
#include "models/section_integrals.hpp"
#include "profile.hpp"

namespace hubbeam {

namespace {

/// A field's coordinates' first index in q, -1 when the variant has none.
int first_of(const CoordinateLayout& c, FieldKind kind)
{
    const CoordinateField* f = c.find(kind);
    return f != nullptr && f->count > 0 ? f->first : -1;
}

/// sum_i row[i] c[i]; 0 without coordinates.
double dot(const std::vector<double>& row, const double* c)
{
    double s = 0.0;
    if (c != nullptr)
        for (std::size_t i = 0; i < row.size(); ++i) s += row[i] * c[i];
    return s;
}

/// The cuts of [0, 1] on which every integrand is one smooth piece: every basis's intervals (AMM: panels narrow
/// enough for its highest mode), a profile's stations, and panels on which a pre-twist turns by at most 1 rad.
std::vector<double> cuts_of(const VariantKey& key, const Parameters& p)
{
    std::vector<double> cuts(p.stations.begin(), p.stations.end());
    cuts.insert(cuts.end(), {0.0, 1.0});
    const FieldBasis bases[] = {key.axial_basis(), key.transverse_basis(), key.flap_basis(), key.twist_basis()};
    int sizes = 0;
    for (const FieldBasis& b : bases) {
        sizes = std::max(sizes, b.size());
        for (int k = 1; b.polynomial() && b.size() > 0 && k < b.intervals(); ++k)
            cuts.push_back(static_cast<double>(k) / b.intervals());
    }
    const int panels = std::max(key.method == Method::amm ? transcendental_panels(sizes) : 1,
                                1 + static_cast<int>(std::ceil(2.0 * std::abs(p.twist))));
    for (int k = 1; k < panels; ++k) cuts.push_back(static_cast<double>(k) / panels);
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end(), [](double u, double v) { return v - u < 1e-14; }), cuts.end());
    cuts.back() = 1.0;
    return cuts;
}

/// Gauss points per panel: the moment's integrand m d x a is of degree 4 D - 1 in the pieces' degree D (the
/// foreshortening in both the arm and the acceleration), 2 D points integrate it exactly; AMM's to round-off.
int points_of(const VariantKey& key)
{
    if (key.method == Method::amm) return transcendental_points;
    int degree = 1;
    for (const FieldBasis& b : {key.axial_basis(), key.transverse_basis(), key.flap_basis(), key.twist_basis()})
        if (b.size() > 0) degree = std::max(degree, b.degree());
    return 2 * degree + 2;
}

/// The values (deriv 0) or slopes d/dx (deriv 1) of a basis at xi, as a row.
std::vector<double> row_of(const FieldBasis& b, double xi, int deriv, double L)
{
    std::vector<double> r(static_cast<std::size_t>(b.size()));
    for (int i = 0; i < b.size(); ++i) {
        const Jet<double> j = b.at(i, xi);
        r[static_cast<std::size_t>(i)] = deriv == 0 ? j.v : j.d1 / L;
    }
    return r;
}

}  // namespace

BladeLoads::Node BladeLoads::node_at(const BeamFields& section, double xi, double weight) const
{
    Node n;
    n.x = xi * p_.L;
    n.weight = weight;
    n.m = p_.stations.empty() ? p_.rho * p_.S * section.area_ratio(n.x)
                              : profile_value(p_.stations, p_.profile, ProfileValue::m, xi);
    if (key_.nt > 0) {  // the section's rotary inertia (docs/model.md section 12): only with the twist's coordinates
        // The deviator's components linear between stations, as the model's distributions are (docs/model.md 12.4),
        // not its angle: then the loads and the equations of motion see one section.
        std::complex<double> inertia_axes;  // the deviator turned by the inertia axes' angle, without the pitch
        if (inertia_.empty()) {
            const double j_c = p_.rho * p_.I_flap * section.flap_moment_ratio(n.x);
            const double j_n = p_.rho * p_.I * section.moment_ratio(n.x);
            n.j_p = j_c + j_n;
            inertia_axes = (j_n - j_c) / 2.0 * std::polar(1.0, 2.0 * p_.twist * xi);  // polar's length must be >= 0
        } else {
            n.j_p = linear_between(p_.stations, inertia_, 0, xi);
            inertia_axes = {linear_between(p_.stations, inertia_, 1, xi), linear_between(p_.stations, inertia_, 2, xi)};
        }
        n.j_dev = inertia_axes * std::polar(1.0, 2.0 * p_.pitch);
    }
    n.axial = row_of(key_.axial_basis(), xi, 0, p_.L);
    n.inplane = row_of(key_.transverse_basis(), xi, 0, p_.L);
    n.flap = row_of(key_.flap_basis(), xi, 0, p_.L);
    n.twist = row_of(key_.twist_basis(), xi, 0, p_.L);
    n.inplane_slope = row_of(key_.transverse_basis(), xi, 1, p_.L);
    n.flap_slope = row_of(key_.flap_basis(), xi, 1, p_.L);
    return n;
}

BladeLoads::BladeLoads(const VariantKey& key, const Parameters& p)
    : key_(key), p_(p), torque_(key.drive == Drive::torque), foreshortened_(key.order != Order::zero)
{
    const CoordinateLayout c = coordinate_layout(key);
    hub_x_ = first_of(c, FieldKind::hub_x);
    hub_y_ = first_of(c, FieldKind::hub_y);
    axial_ = first_of(c, FieldKind::axial);
    inplane_ = first_of(c, FieldKind::inplane);
    flap_ = first_of(c, FieldKind::flap);
    twist_ = first_of(c, FieldKind::twist);
    const std::vector<double> cuts = cuts_of(key, p);
    const QuadratureRule g = gauss_legendre(points_of(key));
    const FieldBasis inplane = key.transverse_basis(), flap = key.flap_basis();
    const BeamFields section(key, p);  // a taper's ratios
    if (key.nt > 0 && !p.stations.empty()) {
        using D = SectionDistribution;
        const std::vector<double> j_p = section_distribution(key, p, D::j_p);
        const std::vector<double> j_cos = section_distribution(key, p, D::j_cos);
        const std::vector<double> j_sin = section_distribution(key, p, D::j_sin);
        for (std::size_t k = 0; k < p.stations.size(); ++k)
            inertia_.insert(inertia_.end(), {j_p[k], j_cos[k], j_sin[k]});
    }
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double lo = cuts[k], width = cuts[k + 1] - lo;
        const std::size_t panel_first = nodes_.size();
        for (std::size_t j = 0; j < g.nodes.size(); ++j) {
            Node n = node_at(section, lo + width * g.nodes[j], p.L * width * g.weights[j]);
            n.panel_first = panel_first;
            // [lo, xi] by the same rule: the foreshortening's integrand is one polynomial piece there.
            const double part = width * g.nodes[j];
            for (std::size_t s = 0; s < g.nodes.size(); ++s) {
                const double xi = lo + part * g.nodes[s];
                n.inner_weights.push_back(p.L * part * g.weights[s]);
                n.inner_inplane.push_back(row_of(inplane, xi, 1, p.L));
                n.inner_flap.push_back(row_of(flap, xi, 1, p.L));
            }
            nodes_.push_back(std::move(n));
        }
    }
    tip_ = node_at(section, 1.0, 0.0);
    tip_.panel_first = nodes_.size();
}

void BladeLoads::section_inertia(const Node& n, double dx, double w, double dw, const double* phi, double cb, double sb,
                                 double* M)
{
    // The section's angular momentum per length h (docs/model.md section 12: angular velocity theta_dot k + phi_dot e1,
    // principal axes along the chord turned by psi = beta + phi) in (e1, e2, e3), and the rates of its components.
    // The deviator at psi = beta + phi, its value at beta turned by 2 phi: dev e^(2 i psi), with dev = (j_n - j_c) / 2,
    // so that j_c sin^2 psi + j_n cos^2 psi = j_p / 2 + re and (j_c - j_n) sin 2 psi = -2 im.
    const std::complex<double> deviator = n.j_dev * std::polar(1.0, 2.0 * phi[0]);
    const double re = deviator.real(), im = deviator.imag(), jp = n.j_p;
    const double h1 = jp * (phi[1] + w * sb), h2 = -w * cb * im, h3 = w * cb * (jp / 2.0 + re);
    const double r1 = jp * (phi[2] + dw * sb), r2 = -cb * (dw * im + 2.0 * w * phi[1] * re),
                 r3 = cb * (dw * (jp / 2.0 + re) - 2.0 * w * phi[1] * im);
    // dh/dt in the frame turning at theta_dot k = theta_dot (sb e1 + cb e3): the rates plus theta_dot k x h.
    const double D1 = r1 - w * cb * h2, D2 = r2 + w * (cb * h1 - sb * h3), D3 = r3 + w * sb * h2;
    // The blade on the hub takes -dh/dt, in (i_b, j_b, k).
    M[0] -= dx * (cb * D1 - sb * D3);
    M[1] -= dx * D2;
    M[2] -= dx * (sb * D1 + cb * D3);
}

namespace {

/// The first coordinate of a field in v, or null where the variant has no such field.
const double* at(const double* v, int first)
{
    return first >= 0 ? v + first : nullptr;
}

}  // namespace

std::array<double, 3> BladeLoads::slope_products(const std::vector<double>& y_row, const std::vector<double>& z_row,
                                                 const double* const state[3]) const
{
    double s[3], r[3];
    for (int d = 0; d < 3; ++d) s[d] = dot(y_row, at(state[d], inplane_)), r[d] = dot(z_row, at(state[d], flap_));
    return {s[0] * s[0] + r[0] * r[0], s[0] * s[1] + r[0] * r[1], s[1] * s[1] + s[0] * s[2] + r[1] * r[1] + r[0] * r[2]};
}

std::vector<std::array<double, 3>> BladeLoads::shortening_sums(const double* const state[3]) const
{
    std::vector<std::array<double, 3>> before(nodes_.size() + 1, {0.0, 0.0, 0.0});
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
        const std::array<double, 3> gn = slope_products(nodes_[n].inplane_slope, nodes_[n].flap_slope, state);
        for (int d = 0; d < 3; ++d) before[n + 1][static_cast<std::size_t>(d)] = before[n][d] + nodes_[n].weight * gn[d];
    }
    return before;
}

std::array<double, 3> BladeLoads::shortening(const Node& n, const std::vector<std::array<double, 3>>& before,
                                             const double* const state[3]) const
{
    if (!foreshortened_) return {0.0, 0.0, 0.0};
    std::array<double, 3> sum = before[n.panel_first];
    for (std::size_t s = 0; s < n.inner_weights.size(); ++s) {
        const std::array<double, 3> gs = slope_products(n.inner_inplane[s], n.inner_flap[s], state);
        for (std::size_t d = 0; d < 3; ++d) sum[d] += n.inner_weights[s] * gs[d];
    }
    return {-0.5 * sum[0], -sum[1], -sum[2]};
}

RootLoads BladeLoads::operator()(const HubInput& u, const double* q, const double* qd, const double* qdd) const
{
    // The drive at the blade's azimuth, and the hub's acceleration in the blade's frame (i_b, j_b, k).
    const double psi = torque_ ? q[0] : u.theta, w = torque_ ? qd[0] : u.theta_dot, dw = torque_ ? qdd[0] : u.theta_ddot;
    const double cp = std::cos(psi), sp = std::sin(psi);
    const double hx = hub_x_ >= 0 ? qdd[hub_x_] : 0.0, hy = hub_y_ >= 0 ? qdd[hub_y_] : 0.0;
    const double hub_i = hx * cp + hy * sp, hub_j = -hx * sp + hy * cp;
    // Gravity along -J (in the plane) or -k (the spin axis), in the blade's frame.
    const double g_i = -p_.g * sp, g_j = -p_.g * cp, g_k = -p_.g_axis;
    const double cb = std::cos(p_.precone), sb = std::sin(p_.precone);
    const double* state[] = {q, qd, qdd};
    const std::vector<std::array<double, 3>> before = shortening_sums(state);

    double F[3] = {0.0, 0.0, 0.0}, M[3] = {0.0, 0.0, 0.0};  // blade on hub, in (i_b, j_b, k)
    const auto add = [&](const Node& n, double mass) {
        const std::array<double, 3> ux2 = shortening(n, before, state);
        // The point's offset from the root, d = (x + u_x) e1 + u_y e2 + u_z e3, and its rates, in (i_b, j_b, k).
        double di[3], dj[3], dk[3];
        for (std::size_t d = 0; d < 3; ++d) {
            const double ux = (d == 0 ? n.x : 0.0) + dot(n.axial, at(state[d], axial_)) + ux2[d];
            const double uz = dot(n.flap, at(state[d], flap_));
            di[d] = ux * cb - uz * sb;
            dj[d] = dot(n.inplane, at(state[d], inplane_));
            dk[d] = ux * sb + uz * cb;
        }
        // The absolute acceleration in the turning frame: the hub's, relative, Coriolis, Euler and centripetal.
        const double pi = p_.a + di[0];
        const double a_i = hub_i + di[2] - 2.0 * w * dj[1] - dw * dj[0] - w * w * pi;
        const double a_j = hub_j + dj[2] + 2.0 * w * di[1] + dw * pi - w * w * dj[0];
        const double a_k = dk[2];
        const double f[3] = {mass * (g_i - a_i), mass * (g_j - a_j), mass * (g_k - a_k)};
        const double r[3] = {di[0], dj[0], dk[0]};
        for (int c = 0; c < 3; ++c) F[c] += f[c];
        M[0] += r[1] * f[2] - r[2] * f[1];
        M[1] += r[2] * f[0] - r[0] * f[2];
        M[2] += r[0] * f[1] - r[1] * f[0];
        if (key_.nt > 0) {
            const double phi[3] = {dot(n.twist, at(q, twist_)), dot(n.twist, at(qd, twist_)),
                                   dot(n.twist, at(qdd, twist_))};
            section_inertia(n, n.weight, w, dw, phi, cb, sb, M);
        }
    };
    for (const Node& n : nodes_) add(n, n.m * n.weight);
    add(tip_, p_.m_tip);
    // The tip body's rotary inertia J_t about k, turning with theta and the in-plane slope.
    const double slope_rate2 = dot(tip_.inplane_slope, at(qdd, inplane_));
    M[2] -= p_.J_tip * (dw + slope_rate2);

    // In the root frame: e1 = cb i + sb k, e2 = j, e3 = -sb i + cb k.
    RootLoads out;
    out.axial_force = cb * F[0] + sb * F[2];
    out.shear_edge = F[1];
    out.shear_flap = -sb * F[0] + cb * F[2];
    out.edge_moment = -sb * M[0] + cb * M[2];
    out.flap_moment = -M[1];
    return out;
}

std::vector<RootLoads> blade_root_loads(const Model& model, const std::vector<BladeLoads>& blades, const HubInput& u,
                                        const double* q, const double* qd, const double* qdd)
{
    const auto* rotor = dynamic_cast<const RotorModel*>(&model);
    if (rotor == nullptr) return {blades.at(0)(u, q, qd, qdd)};
    const std::size_t local = static_cast<std::size_t>(rotor->blade(0).nq());
    std::vector<double> lq(local), lqd(local), lqdd(local);
    std::vector<RootLoads> out;
    for (int b = 0; b < rotor->blades(); ++b) {
        rotor->gather(q, b, lq.data(), true);
        rotor->gather(qd, b, lqd.data(), false);
        rotor->gather(qdd, b, lqdd.data(), false);
        out.push_back(blades.at(static_cast<std::size_t>(b))(rotor->blade_input(u, b), lq.data(), lqd.data(), lqdd.data()));
    }
    return out;
}

}  // namespace hubbeam
