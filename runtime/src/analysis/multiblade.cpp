// The multi-blade (Coleman) coordinates of a rotor of identical blades (docs/model.md section 13.2): the transform,
// the constant state-space model it gives about a steady spin, and that model's modes named by harmonic and whirl.
#include <algorithm>
#include <cmath>
#include <complex>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <iterator>
#include <map>
#include <numbers>
#include <stdexcept>

#include "analysis/modal_coordinates.hpp"
#include "linalg/eigen_solvers.hpp"
#include "models/model_operations.hpp"
#include "models/rotor_model.hpp"
#include "terms.hpp"

namespace hubbeam {

std::string to_string(Frame frame)
{
    return frame == Frame::fixed ? "fixed" : "rotating";
}

bool parse(std::string_view word, Frame& frame)
{
    if (word == "fixed")
        frame = Frame::fixed;
    else if (word == "rotating")
        frame = Frame::rotating;
    else
        return false;
    return true;
}

std::string multiblade_refusal(const VariantKey& key, const std::vector<std::vector<double>>& blades)
{
    const auto n = blades.size();
    if (n < 3) return "multi-blade coordinates need 3 blades or more (rotor.blades), got " + std::to_string(n);
    // The hub's inertia, mass and support ride with blade 1's parameters alone (Rotor::blade): not the blade's own.
    const Param hub[] = {Param::J_oh, Param::m_hub, Param::k_x, Param::k_y, Param::c_x, Param::c_y};
    for (std::size_t b = 1; b < n; ++b)
        for (std::size_t i = 0; i < blades[b].size(); ++i)
            if (blades[b][i] != blades[0][i] &&
                std::find_if(std::begin(hub), std::end(hub), [i](Param p) { return index(p) == i; }) == std::end(hub))
                return "multi-blade coordinates need identical blades, and blade " + std::to_string(b + 1) +
                       " differs from blade 1 (rotor.pitch_offsets, rotor.tip_masses): the equations stay periodic";
    if (weight_turns_with_spin(key, blades[0]))
        return "multi-blade coordinates need no weight in the plane of rotation: it turns with each blade, whose "
               "steady states then differ";
    return {};
}

std::string multiblade_refusal(const Model& model)
{
    std::vector<std::vector<double>> blades;
    if (const auto* rotor = dynamic_cast<const RotorModel*>(&model))
        for (int b = 0; b < rotor->blades(); ++b) blades.push_back(rotor->blade(b).parameters());
    else
        blades.push_back(model.parameters());
    return multiblade_refusal(model.key(), blades);
}

namespace {

/// A rotor's q: the hub's h coordinates (theta under a torque, x_h, y_h), then N blades of e coordinates each;
/// component j of the multi-blade coordinates sits where blade j + 1's coordinates do.
struct Blades {
    int N = 0, h = 0, e = 0;
    explicit Blades(const Model& model)
        : N(blade_count(model)), h(model.coordinates().first_beam()), e((model.nq() - h) / N)
    {
    }
    /// Component j's coordinate i (0-based within a blade) in q.
    int index(int j, int i) const { return h + j * e + i; }
    /// The component of q's coordinate c (c >= h).
    int component(int c) const { return (c - h) / e; }
    bool differential(int j) const { return N % 2 == 0 && j == N - 1; }
    /// Component j's harmonic: 0 collective, n for the cyclic pair (cos n psi, sin n psi), N/2 differential.
    int harmonic(int j) const { return differential(j) ? N / 2 : (j + 1) / 2; }
    /// The name's suffix of component j: coll, cos1, sin1, ..., diff.
    std::string suffix(int j) const
    {
        if (j == 0) return "coll";
        if (differential(j)) return "diff";
        return (j % 2 == 1 ? "cos" : "sin") + std::to_string(harmonic(j));
    }
    /// Component j's blade function at blade b (0-based) at the rotor's azimuth psi, or its derivative d (0 to 2) in
    /// psi: 1, cos n psi_b, sin n psi_b, (-1)^b.
    double basis(int j, int b, double psi, int d) const
    {
        if (j == 0 || differential(j)) return d > 0 ? 0.0 : j == 0 || b % 2 == 0 ? 1.0 : -1.0;
        const int n = harmonic(j);
        const double angle = n * (psi + 2.0 * std::numbers::pi * b / N), c = std::cos(angle), s = std::sin(angle);
        const double scale = std::pow(n, d);
        const bool cosine = j % 2 == 1;
        switch (d) {
            case 0:
                return cosine ? c : s;
            case 1:
                return scale * (cosine ? -s : c);
            default:
                return scale * (cosine ? -c : -s);
        }
    }
};

/// q = P(psi) z, with dP/dpsi, d2P/dpsi2 and P^-1 (the definition of docs/model.md section 13.2: 1/N of the sums
/// for the collective and differential components, 2/N for the cyclic ones), over q's layout.
struct Transform {
    Eigen::MatrixXd P, dP, ddP, inverse;
};

Transform transform(const Model& model, double psi)
{
    const Blades r(model);
    const int n = model.nq();
    Transform t{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n),
                Eigen::MatrixXd::Zero(n, n)};
    for (int i = 0; i < r.h; ++i) t.P(i, i) = t.inverse(i, i) = 1.0;
    for (int b = 0; b < r.N; ++b)
        for (int j = 0; j < r.N; ++j) {
            const double weight = (j == 0 || r.differential(j) ? 1.0 : 2.0) / r.N;
            for (int i = 0; i < r.e; ++i) {
                const int blade = r.index(b, i), component = r.index(j, i);
                t.P(blade, component) = r.basis(j, b, psi, 0);
                t.dP(blade, component) = r.basis(j, b, psi, 1);
                t.ddP(blade, component) = r.basis(j, b, psi, 2);
                t.inverse(component, blade) = weight * r.basis(j, b, psi, 0);
            }
        }
    return t;
}

/// The rotor's azimuth at s: theta under a torque, the prescribed angle otherwise.
double azimuth_of(const Model& model, const SteadySpin& s)
{
    return model.key().drive == Drive::torque ? s.q[0] : s.u.theta;
}

/// s with the rotor turned to azimuth psi (every other value of a steady spin is the same at every azimuth).
SteadySpin turned(const Model& model, SteadySpin s, double psi)
{
    if (model.key().drive == Drive::torque)
        s.q[0] = psi;
    else
        s.u.theta = psi;
    return s;
}

void require_multiblade(const Model& model)
{
    if (const std::string why = multiblade_refusal(model); !why.empty()) throw std::invalid_argument(why);
}

/// The linearized equations about s in multi-blade coordinates, q = P z (psi = Omega t): premultiplied by P^T,
/// M_z = P^T M P, Qqd_z = P^T (Qqd P - 2 Omega M P'), Qq_z = P^T (Qq P + Omega Qqd P' - Omega^2 M P''), constant
/// (P^T P is: N for the collective and differential components, N/2 for the cyclic ones).
LinearEquations multiblade_equations(const Model& model, const SteadySpin& s)
{
    const Transform t = transform(model, azimuth_of(model, s));
    const ForceJacobians J = force_jacobians(model, s.u, s.q, s.qd);
    const Eigen::MatrixXd M = mass_at(model, s.u, s.q);
    const double w = s.omega;
    return {t.P.transpose() * M * t.P, t.P.transpose() * (J.q * t.P + w * J.qd * t.dP - w * w * M * t.ddP),
            t.P.transpose() * (J.qd * t.P - 2.0 * w * M * t.dP)};
}

/// The state's names: theta, the hub's translation, each blade field's coordinates per component, then the rates.
std::vector<std::string> state_names(const Model& model)
{
    const Blades r(model);
    std::vector<std::string> names{"theta"};
    for (int c = model.coordinates().first_elastic(); c < model.nq(); ++c) {
        const CoordinateField& f = model.coordinates().field_of(c);
        names.push_back(c < r.h ? f.name(0)
                                : f.symbol + std::to_string(c - f.first + 1) + "_" + r.suffix(r.component(c)));
    }
    const std::size_t positions = names.size();
    for (std::size_t i = 0; i < positions; ++i) names.push_back(names[i] + "_dot");
    return names;
}

/// The outputs: each tip value's components (a tip value is linear in its blade's coordinates, and its components
/// are that row applied to each component's coordinates), theta after tip_uy's.
void add_outputs(StateSpace& ss, const Model& model, const SteadySpin& s, Eigen::Index offset)
{
    const Blades r(model);
    const VariantKey& key = model.key();
    std::vector<std::pair<std::string, double Tip::*>> values = {{"tip_uy", &Tip::uy}};
    if (key.nz > 0) values.emplace_back("tip_uz", &Tip::uz);
    if (key.nt > 0) values.emplace_back("tip_phi", &Tip::phi);
    std::vector<int> blade1;
    for (int i = 0; i < r.e; ++i) blade1.push_back(r.index(0, i));
    const auto states = ss.A.rows();
    std::vector<Eigen::RowVectorXd> rows;
    for (std::size_t v = 0; v < values.size(); ++v) {
        const Eigen::VectorXd tip = tip_row(model, s.q, blade1, values[v].second);  // blade 1's tip: Model::tip
        for (int j = 0; j < r.N; ++j) {
            Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(states);
            for (int i = 0; i < r.e; ++i) row[offset + r.index(j, i)] = tip[i];
            rows.push_back(row);
            ss.outputs.push_back(values[v].first + "_" + r.suffix(j));
        }
        if (v == 0) {
            rows.push_back(Eigen::RowVectorXd::Unit(states, 0));
            ss.outputs.emplace_back("theta");
        }
    }
    ss.C.resize(static_cast<Eigen::Index>(rows.size()), states);
    for (std::size_t k = 0; k < rows.size(); ++k) ss.C.row(static_cast<Eigen::Index>(k)) = rows[k];
    ss.D = Eigen::MatrixXd::Zero(ss.C.rows(), 1);
}

}  // namespace

StateSpace multiblade_state_space(const Model& model, const SteadySpin& steady, double azimuth)
{
    require_multiblade(model);
    const SteadySpin s = turned(model, steady, azimuth);
    const StateSpace rotating = state_space(model, s);
    const Transform t = transform(model, azimuth);
    // The state's positions: theta (a state of a prescribed hub too), then q's coordinates but a torque's theta.
    const Eigen::Index m = rotating.A.rows() / 2, n = model.nq(), offset = m - n;
    const auto positions = [&](const Eigen::MatrixXd& X) {
        Eigen::MatrixXd out = Eigen::MatrixXd::Identity(m, m);
        out.bottomRightCorner(n, n) = X;
        return out;
    };
    Eigen::MatrixXd dP = positions(t.dP), ddP = positions(t.ddP);
    dP.topLeftCorner(offset, offset).setZero();
    ddP.topLeftCorner(offset, offset).setZero();
    const Eigen::MatrixXd P = positions(t.P), inverse = positions(t.inverse);
    // x = T z with x = (q, qd): T = [[P, 0], [Omega P', P]]; z' = T^-1 (A T - dT/dt) z.
    const double w = s.omega;
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(2 * m, 2 * m), Tdot = T, Tinv = T;
    T.topLeftCorner(m, m) = T.bottomRightCorner(m, m) = P;
    T.bottomLeftCorner(m, m) = w * dP;
    Tdot.topLeftCorner(m, m) = Tdot.bottomRightCorner(m, m) = w * dP;
    Tdot.bottomLeftCorner(m, m) = w * w * ddP;
    Tinv.topLeftCorner(m, m) = Tinv.bottomRightCorner(m, m) = inverse;
    Tinv.bottomLeftCorner(m, m) = -w * inverse * dP * inverse;
    StateSpace ss;
    ss.A = Tinv * (rotating.A * T - Tdot);
    ss.B = Tinv * rotating.B;
    ss.inputs = rotating.inputs;
    ss.states = state_names(model);
    add_outputs(ss, model, s, offset);
    return ss;
}

namespace {

/// One harmonic's coordinates among R: collective (with theta), a cyclic pair (with n = 1, the hub's x_h, y_h),
/// differential.
struct Harmonic {
    int n = 0;
    bool cyclic = false;
    std::vector<int> R;                      // indices into q, in R's order
    std::vector<std::pair<int, int>> pairs;  // positions in R of a cyclic pair's cos and sin coordinates
    std::pair<int, int> hub{-1, -1};         // positions in R of x_h and y_h
};

std::vector<Harmonic> harmonics(const Model& model, const std::vector<int>& R)
{
    const Blades r(model);
    // Harmonic groups by their first component: 0, 1 (cos1, sin1), 3 (cos2, sin2), ..., differential.
    std::map<int, Harmonic> by;
    for (const int c : R) {
        const FieldKind kind = model.coordinates().field_of(c).kind;
        const int j = c < r.h ? (kind == FieldKind::hub_angle ? 0 : 1) : r.component(c);
        const int first = j == 0 || r.differential(j) ? j : j - (j + 1) % 2;
        Harmonic& g = by[first];
        g.n = j == 0 ? 0 : r.harmonic(j);
        g.cyclic = j != 0 && !r.differential(j);
        g.R.push_back(c);
    }
    std::vector<Harmonic> out;
    for (auto& [first, g] : by) {
        const auto at = [&g](int c) { return static_cast<int>(std::find(g.R.begin(), g.R.end(), c) - g.R.begin()); };
        for (std::size_t k = 0; k < g.R.size(); ++k) {
            const int c = g.R[k];
            const FieldKind kind = model.coordinates().field_of(c).kind;
            if (kind == FieldKind::hub_x)
                g.hub = {static_cast<int>(k), at(model.coordinates().first(FieldKind::hub_y))};
            if (g.cyclic && c >= r.h && r.component(c) == first) g.pairs.emplace_back(static_cast<int>(k), at(c + r.e));
        }
        out.push_back(std::move(g));
    }
    return out;
}

using Matrix = Eigen::MatrixXd;

/// Im(a^H W b) over the pairs (a the cos coordinates' rates, b the sin coordinates', W the mass among the cos
/// coordinates): negative where the mode whirls in the sense of positive theta (cos = cos wt, sin = sin wt).
double whirl(const std::vector<std::pair<int, int>>& pairs, const Matrix& M, const Eigen::VectorXcd& v)
{
    std::complex<double> sum = 0.0;
    for (const auto& [c1, s1] : pairs)
        for (const auto& [c2, s2] : pairs) sum += std::conj(v[c1]) * M(c1, c2) * v[s2];
    return sum.imag();
}

/// The Hermitian form whose eigenvectors within a set of repeated eigenvalues are modes of one field kind each and,
/// for a cyclic pair, of one whirl: the mass of each field kind weighted by a number of its own, plus a quarter of
/// the whirl form (whirl(): +-1/2 of the energy for a circular whirl).
Eigen::MatrixXcd labelling_form(const Model& model, const Harmonic& g, const Matrix& M)
{
    const auto r = static_cast<Eigen::Index>(g.R.size());
    Eigen::MatrixXcd H = Eigen::MatrixXcd::Zero(r, r);
    const auto weight = [&](int k) {
        const FieldKind kind = model.coordinates().field_of(g.R[static_cast<std::size_t>(k)]).kind;
        return kind == FieldKind::hub_x || kind == FieldKind::hub_y ? 1.0 : 2.0 + static_cast<double>(kind);
    };
    for (Eigen::Index i = 0; i < r; ++i)
        for (Eigen::Index j = 0; j < r; ++j)
            if (weight(static_cast<int>(i)) == weight(static_cast<int>(j)))
                H(i, j) = weight(static_cast<int>(i)) * M(i, j);
    std::vector<std::pair<int, int>> pairs = g.pairs;
    if (g.hub.first >= 0) pairs.push_back(g.hub);
    const std::complex<double> half_i(0.0, 0.5);
    for (const auto& [c1, s1] : pairs)
        for (const auto& [c2, s2] : pairs) {
            if (weight(c1) != weight(c2)) continue;
            H(c1, s2) += 0.25 * -half_i * M(c1, c2);
            H(s2, c1) += 0.25 * half_i * M(c2, c1);
        }
    return H;
}

/// Within each set of repeated eigenvalues, the vectors turned into the basis that diagonalizes H (labelling_form)
/// in the mass M: each a mode of one field kind and one whirl.
void separate(const Eigen::MatrixXcd& H, const Matrix& M, const Eigen::VectorXcd& lambda, Eigen::MatrixXcd& rates)
{
    std::vector<bool> done(static_cast<std::size_t>(lambda.size()), false);
    for (Eigen::Index k = 0; k < lambda.size(); ++k) {
        if (done[static_cast<std::size_t>(k)]) continue;
        std::vector<Eigen::Index> group;
        for (Eigen::Index j = k; j < lambda.size(); ++j)
            if (std::abs(lambda[j] - lambda[k]) <= 1e-6 * std::abs(lambda[k])) {  // as natural_modes' separation
                group.push_back(j);
                done[static_cast<std::size_t>(j)] = true;
            }
        if (group.size() < 2) continue;
        Eigen::MatrixXcd V(rates.rows(), static_cast<Eigen::Index>(group.size()));
        for (std::size_t g = 0; g < group.size(); ++g) V.col(static_cast<Eigen::Index>(g)) = rates.col(group[g]);
        const Eigen::MatrixXcd E = V.adjoint() * H * V, G = V.adjoint() * M.cast<std::complex<double>>() * V;
        const Eigen::MatrixXcd turned = V * hermitian_pairs(E, G).vectors;
        for (std::size_t g = 0; g < group.size(); ++g) rates.col(group[g]) = turned.col(static_cast<Eigen::Index>(g));
    }
}

/// A mode's kind in harmonic g (multiblade_modes): its blades' field kind by where their kinetic energy lies, led by
/// the harmonic and, for a cyclic pair, the whirl; or the hub's.
std::string kind_of(const Model& model, const Harmonic& g, const Matrix& Mg, const Matrix& M,
                    const Eigen::VectorXcd& rates, double rad_s, double omega)
{
    const std::vector<double> energy = energy_by_field(model, M, g.R, rates);
    std::map<FieldKind, double> by_kind;
    for (std::size_t f = 0; f < energy.size(); ++f) by_kind[model.coordinates().fields[f].kind] += energy[f];
    const double hub = by_kind[FieldKind::hub_x] + by_kind[FieldKind::hub_y];
    FieldKind blade = FieldKind::inplane;
    double largest = -1.0;
    for (const auto& [kind, e] : by_kind)
        if (kind != FieldKind::hub_angle && kind != FieldKind::hub_x && kind != FieldKind::hub_y &&
            (e > largest || (e == largest && kind == FieldKind::inplane)))
            largest = e, blade = kind;
    const double spin = omega < 0.0 ? -1.0 : 1.0;  // the sense of the spin; at rest, that of positive theta
    if (g.hub.first >= 0 && hub > largest) {
        const std::complex<double> x = rates[g.hub.first], y = rates[g.hub.second], i(0.0, 1.0);
        const double forward = std::norm(x + i * y), backward = std::norm(x - i * y);
        if (std::max(forward, backward) > 9.0 * std::min(forward, backward))
            return spin * (forward - backward) > 0.0 ? "FW hub" : "BW hub";
        return std::norm(x) >= std::norm(y) ? "hub x" : "hub y";
    }
    const std::string field = mode_kind(blade, model.key());
    if (!g.cyclic) return (g.n == 0 ? "collective " : "differential ") + field;
    // Forward: the blades' pattern turns with the spin faster than the rotor, n Omega; a rotating-frame frequency
    // omega_r appears at omega_r + n Omega. Else backward, at |omega_r - n Omega|.
    const double sense = spin * (whirl(g.pairs, Mg, rates) < 0.0 ? 1.0 : -1.0);
    const std::string n = g.n == 1 ? "" : std::to_string(g.n);
    return (sense * rad_s > g.n * std::abs(omega) ? "FW" : "BW") + n + " " + field;
}

}  // namespace

std::vector<NaturalMode> multiblade_modes(const Model& model, const SteadySpin& steady, Axial axial)
{
    require_multiblade(model);
    const LinearEquations e = multiblade_equations(model, steady);
    const std::vector<int> R = modal_coordinates(model, steady, axial);
    // A support without dampers and blades without Rayleigh damping dissipate nothing, though the variant of a moving
    // hub carries the support's dissipation: the eigen solver's real parts are then round-off.
    const std::vector<double>& p = model.parameters();
    const bool damped = dissipates(model.key()) && (model.key().extras.damping || p[index(Param::c_x)] != 0.0 ||
                                                    p[index(Param::c_y)] != 0.0 || !model.key().extras.hub);
    std::vector<NaturalMode> modes;
    // One eigenproblem per harmonic: the transformed equations couple none of them (theta moves with the collective
    // component alone, the hub's translation with the first cyclic pair alone), so their vectors are never mixed.
    for (const Harmonic& g : harmonics(model, R)) {
        Matrix Mg(static_cast<Eigen::Index>(g.R.size()), static_cast<Eigen::Index>(g.R.size()));
        for (std::size_t i = 0; i < g.R.size(); ++i)
            for (std::size_t j = 0; j < g.R.size(); ++j)
                Mg(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = e.M(g.R[i], g.R[j]);
        const Eigen::MatrixXcd H = labelling_form(model, g, Mg);
        ModeNaming naming;
        naming.damped = damped;
        naming.separate = [&](const Eigen::VectorXcd& lambda, Eigen::MatrixXcd& rates) {
            separate(H, Mg, lambda, rates);
        };
        naming.kind = [&](const Eigen::VectorXcd& rates, double rad_s) {
            return kind_of(model, g, Mg, e.M, rates, rad_s, steady.omega);
        };
        for (NaturalMode& mode : eigen_modes(model, e, g.R, naming)) {
            // The shape over all of R (zero on the other harmonics' coordinates, M-orthogonal to them): the MAC
            // between modes of different harmonics is 0.
            Eigen::VectorXcd shape = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(R.size()));
            for (std::size_t k = 0; k < g.R.size(); ++k)
                shape[std::find(R.begin(), R.end(), g.R[k]) - R.begin()] = mode.shape[static_cast<Eigen::Index>(k)];
            mode.shape = shape;
            modes.push_back(std::move(mode));
        }
    }
    sort_modes(modes, damped);
    return modes;
}

}  // namespace hubbeam
