// Derivation of one variant end to end: energies, Lagrange's equations, the run-time inputs, and the file.
#include "variant_source.hpp"

#include <algorithm>
#include <array>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "emit.hpp"
#include "energy.hpp"
#include "generated_abi.h"
#include "interface.hpp"
#include "lagrange.hpp"
#include "points.hpp"
#include "structure.hpp"
#include "terms.hpp"

#ifndef HUBBEAM_VERSION
#define HUBBEAM_VERSION "dev"
#endif

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

/// "(L, rho, ...)" from a list of names.
template <class Names>
std::string tuple(const Names& names)
{
    std::string t;
    for (const auto& n : names) t += (t.empty() ? "(" : ", ") + std::string(n);
    return t + ")";
}

/// The parameters p a variant's coefficients kernel takes: the paper's seven, or all of them with extra terms
/// (so that the paper's variants read, and say, what they always did).
std::vector<std::string> read_parameter_names(const VariantKey& key)
{
    return {param_names.begin(), param_names.begin() + static_cast<std::ptrdiff_t>(key.params_read())};
}

/// p's entries as the banner and the coefficients kernel's comment say them: the parameters, then a profile
/// variant's section integrals s_0..s_(n-1).
std::string parameter_tuple(const VariantKey& key, std::size_t sections)
{
    std::string t = tuple(read_parameter_names(key));
    if (sections == 0) return t;
    t.pop_back();
    return t + ", s_0.." + "s_" + std::to_string(sections - 1) + ")";
}

/// How generated code reads a profile variant's section integral n.
std::string read_section(std::size_t n)
{
    return "p[" + std::to_string(param_count + n) + "]";
}

/// A factor kind's word in the ABI (generated_abi.h's SectionFactorKind) and the letter of its field's coordinates.
struct FactorWords {
    Factor::Kind kind;
    const char* abi;
    const char* field;
};
constexpr FactorWords factor_words[] = {{Factor::Kind::axial, "axial_factor", "A"},
                                        {Factor::Kind::transverse, "transverse_factor", "B"},
                                        {Factor::Kind::coupling, "coupling_factor", "B"},
                                        {Factor::Kind::flap, "flap_factor", "Z"},
                                        {Factor::Kind::flap_coupling, "flap_coupling_factor", "Z"},
                                        {Factor::Kind::twist, "twist_factor", "P"}};

const FactorWords& words_of(Factor::Kind k)
{
    for (const FactorWords& w : factor_words)
        if (w.kind == k) return w;
    throw std::logic_error("variant_source: a section distribution is not a factor of its own integral");
}

/// A readable name of a factor for the table's comments: phi of the field's coordinate with primes, or H.
std::string factor_text(const Factor& f)
{
    const std::string field = words_of(f.kind).field;
    if (f.kind == Factor::Kind::coupling || f.kind == Factor::Kind::flap_coupling)
        return "H(" + field + std::to_string(f.i + 1) + "," + field + std::to_string(f.j + 1) + ")";
    return "phi_" + field + std::to_string(f.i + 1) + std::string(static_cast<std::size_t>(f.deriv), '\'');
}

/// A profile variant's section integrals as the table the runtime computes them from (generated_abi.h).
std::string section_table(const std::string& name, const Symbols& s)
{
    std::ostringstream t;
    t << "/* The section integrals s_n = int_0^1 xi^power d(xi) prod(factors) dxi that the coefficients kernel reads at p["
      << param_count << " + n]: {distribution, power, count, {{kind, i, j, deriv}, ...}}, generated_abi.h. */\n"
      << "const SectionIntegral " << name << "_section_integrals[] = {\n";
    for (std::size_t n = 0; n < s.section_keys.size(); ++n) {
        const SectionKey& k = s.section_keys[n];
        if (k.factors.size() > static_cast<std::size_t>(generated::max_section_factors))
            throw std::logic_error("variant_source: a section integral of more factors than the ABI holds");
        t << "    {" << k.distribution << ", " << k.power << ", " << k.factors.size() << ", {";
        std::string text = section_distribution_names[static_cast<std::size_t>(k.distribution)];
        if (k.power > 0) text += " xi" + (k.power > 1 ? "^" + std::to_string(k.power) : std::string());
        for (std::size_t i = 0; i < k.factors.size(); ++i) {
            const Factor& f = k.factors[i];
            t << (i ? ", " : "") << "{" << words_of(f.kind).abi << ", " << f.i << ", " << f.j << ", " << f.deriv << "}";
            text += " " + factor_text(f);
        }
        t << "}},  // s_" << n << ": " << text << "\n";
    }
    return t.str() + "};\n";
}

/// The kernels' u: the drive values, and where U reads the hub angle (terms.hpp) sin and cos of it.
std::vector<std::string> input_names(bool reads_angle)
{
    std::vector<std::string> names(drive_value_names.begin(), drive_value_names.end());
    if (reads_angle) names.insert(names.end(), angle_value_names.begin(), angle_value_names.end());
    return names;
}

/// " tip_body gravity rayleigh_damping taper=width" words of the banner's variant line (the registry's, terms.hpp).
std::vector<std::string> extras_words(const Extras& x)
{
    std::vector<std::string> w;
    for (const TermInfo* t : carried_terms(x)) w.push_back(t->summary(x));
    return w;
}

/// How generated code reads one entry of p or u.
std::string read(Param p)
{
    return "p[" + std::to_string(index(p)) + "]";
}
std::string read(DriveValue u)
{
    return "u[" + std::to_string(index(u)) + "]";
}
std::string read(AngleValue u)
{
    return "u[" + std::to_string(index(u)) + "]";
}

std::string range(const std::string& stem, int n, const std::string& suffix = "")
{
    if (n == 0) return "";
    if (n == 1) return stem + "1" + suffix;
    return stem + "1" + suffix + ".." + stem + std::to_string(n) + suffix;
}

std::string banner(const VariantKey& key, bool mass_varies, std::size_t sections)
{
    const bool torque = key.drive == Drive::torque;
    std::string coords;
    for (const CoordinateField& f : coordinate_layout(key).fields)
        if (const std::string part = !f.basis ? f.symbol : range(f.symbol, f.count);
            !part.empty())
            coords += (coords.empty() ? "" : ", ") + part;
    std::ostringstream b;
    b << "// " << key.name() << ": rotating hub-beam equations of motion M(q) qdd = Q(t, q, qd).\n"
      << "// Generated by hubbeam-gen " HUBBEAM_VERSION " with GiNaC " << GINACLIB_MAJOR_VERSION << "."
      << GINACLIB_MINOR_VERSION << "." << GINACLIB_MICRO_VERSION << ". Do not edit: regenerate with\n"
      << "//   cmake --build build --target regenerate\n"
      << "// Variant: method=" << to_string(key.method) << " Nx=" << key.nx << " Ny=" << key.ny
      << " order=" << to_string(key.order) << " drive=" << to_string(key.drive);
    if (key.method == Method::bsim) b << " spline_basis=" << to_string(key.spline);
    for (const std::string& suffix : extras_words(key.extras)) b << " " << suffix;
    const bool reads_angle = kernels_read_angle(key);
    b << "\n// q = (" << coords << "), qd = d/dt q; u = " << tuple(input_names(reads_angle))
      << ", of which this variant reads "
      << (torque ? drive_value_names[index(DriveValue::tau)]
                 : std::string(drive_value_names[index(DriveValue::theta_dot)]) + ", " +
                       drive_value_names[index(DriveValue::theta_ddot)])
      << (reads_angle ? std::string(", sin_theta, cos_theta") + (torque ? " (of q[0])" : "") : std::string()) << ";\n"
      << "// p = " << parameter_tuple(key, sections)
      << (key.method == Method::bsim
              ? " in SI units. End slope coordinates (BSIM) are per knot interval, h d/dx, h = L/n.\n"
              : " in SI units. Slope coordinates (FEM, BSIM) are d/dxi = L d/dx.\n")
      << "// Derived symbolically from T and U (docs/model.md sections 2-3) by Lagrange's equations of the second "
         "kind.\n"
      << "// For implicit integrators, derivatives of the same M and Q: forces_q = dQ/dq, forces_qd = dQ/dqd, forces_u "
         "=\n"
      << "// dQ/du"
      << (mass_varies ? ", mass_q_product = (dM/dq) v.\n" : "; M is constant, so there is no mass_q_product.\n");
    return b.str();
}

/// The derivatives of M qdd = Q that an implicit integrator's Jacobian needs (docs/model.md section 5.1),
/// by differentiating the same M and Q the other kernels print.
struct JacobianPieces {
    std::vector<Poly> forces_q, forces_qd, forces_u, mass_q_product;  // row-major, see the kernels' shape comments
};

/// A kernel that writes only the nonzero values (the runtime zero-fills its output first).
KernelSpec sparse_kernel(std::string name, std::string out, std::string doc, std::vector<Poly> values)
{
    KernelSpec k{std::move(name), std::move(out), std::move(doc) + "; nonzero entries only", {}};
    for (std::size_t i = 0; i < values.size(); ++i)
        if (!values[i].is_zero()) {
            k.polys.push_back(std::move(values[i]));
            k.slots.push_back(static_cast<int>(i));
        }
    return k;
}

/// The tip displacements (docs/model.md section 5.4) u_y(L) = Phi_y(1) B, u_x1(L) = Phi_x(1) A and
/// u_x(L) = u_x1(L) - 1/2 B^T H(L) B with H(L) = H_xi(1) / L: the shape values and integrals as numbers, so
/// that the runtime needs no shape functions or quadrature for its rows. Order zero is the linear model
/// (section 3), which has no foreshortening u_x2: its u_x is u_x1. A variant that leaves the plane adds
/// u_z(L) = Phi_z(1) Z and phi(L) = Phi_t(1) P, and its u_x shortens with both slopes (section 12).
std::vector<ex> tip_displacements(const VariantKey& key, const Symbols& s)
{
    const FieldBasis axial = key.axial_basis(), transverse = key.transverse_basis(), flap = key.flap_basis(),
                     twist = key.twist_basis();
    ShapeIntegrals integrals(axial, transverse, flap, twist);
    const auto at_tip = [](const FieldBasis& basis, const std::vector<symbol>& coordinates) {
        ex sum = 0;
        for (int j = 0; j < basis.size(); ++j)
            sum += numeric(basis.at(j, 1.0).v) * coordinates[static_cast<std::size_t>(j)];
        return sum;
    };
    const ex uy = at_tip(transverse, s.B), ux1 = at_tip(axial, s.A);
    ex ux2 = 0;
    using K = Factor::Kind;
    for (const auto& [kind, basis, c] : {std::tuple{K::transverse, &transverse, &s.B}, {K::flap, &flap, &s.Z}})
        for (int j = 0; j < basis->size(); ++j)
            for (int k = 0; k < basis->size(); ++k)
                ux2 -= integrals.integrate({{kind, j, 0, 1}, {kind, k, 0, 1}}, 0) * (*c)[static_cast<std::size_t>(j)] *
                       (*c)[static_cast<std::size_t>(k)] / (2 * s.L);
    const ex ux = key.order == Order::zero ? ux1 : (ux1 + ux2).expand();
    if (!key.out_of_plane()) return {uy, ux1, ux};
    return {uy, ux1, ux, at_tip(flap, s.Z), at_tip(twist, s.P)};
}

/// Variable indices of the Polys: the order of Signature::state_inputs.
struct Variables {
    std::vector<int> q, qd;
    int tau = -1, theta_dot = -1, theta_ddot = -1;  // -1 where the variant does not read the drive value
    int sin_theta = -1, cos_theta = -1;             // gravity variants only
};

JacobianPieces jacobian_pieces(const PolyEquations& eq, const Variables& v, const PolyCoordinates& c, bool torque)
{
    const std::size_t n = v.q.size();
    JacobianPieces j;
    j.forces_q.resize(n * n);
    j.forces_qd.resize(n * n);
    j.mass_q_product.resize(n * n);
    j.forces_u.resize(n * drive_value_count);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t k = 0; k < n; ++k) {
            j.forces_q[i * n + k] = c.d_dq(eq.Q[i], k);
            j.forces_qd[i * n + k] = eq.Q[i].diff(v.qd[k]);
            // v is read from the qd slot, so the rates' variables stand for v here.
            for (std::size_t l = 0; l < n; ++l)
                j.mass_q_product[i * n + k] += c.d_dq(eq.M[i * n + l], k).times(v.qd[l]);
        }
    // dQ/du only for the drive values the variant reads: under torque theta_dot is the rate qd[0], not an input.
    std::vector<std::pair<DriveValue, int>> inputs;
    if (torque)
        inputs.emplace_back(DriveValue::tau, v.tau);
    else
        inputs.insert(inputs.end(), {{DriveValue::theta_dot, v.theta_dot}, {DriveValue::theta_ddot, v.theta_ddot}});
    for (std::size_t i = 0; i < n; ++i)
        for (const auto& [u, var] : inputs) j.forces_u[i * drive_value_count + index(u)] = eq.Q[i].diff(var);
    // The runtime's dfdt = M^-1 dQ/du du/dt assumes M does not depend on the drive or on the rates.
    // Under torque the angle's sine and cosine are functions of q[0] (a moving hub's M holds them): d_dq follows them.
    std::vector<int> not_in_M = v.qd;
    for (int d : {v.tau, v.theta_dot, v.theta_ddot})
        if (d >= 0) not_in_M.push_back(d);
    // A prescribed angle's sine and cosine in M (a moving hub's) are the runtime's: it adds dM/dtheta qdd to df/dt.
    if (c.angle < 0 && c.angle_rate < 0)
        for (int d : {v.sin_theta, v.cos_theta})
            if (d >= 0) not_in_M.push_back(d);
    for (const Poly& Mij : eq.M)
        for (int var : not_in_M)
            if (Mij.has(var))
                throw std::logic_error("lagrange: M depends on the rates or the drive; the Jacobian assumes not");
    return j;
}

/// The symbols the coefficients kernel reads from p: the beam's, the extra terms' (all of them for any extra), the
/// out-of-plane model's, then each profile station's.
std::vector<Input> parameter_inputs(const Symbols& s, const VariantKey& key)
{
    const Extras& x = key.extras;
    // m = rho S, EI and ES are formed from p once, in the coefficients kernel.
    std::vector<Input> inputs = {{s.L, read(Param::L)},
                                 {s.m, read(Param::rho) + " * " + read(Param::S)},
                                 {s.EI, read(Param::E) + " * " + read(Param::I)},
                                 {s.ES, read(Param::E) + " * " + read(Param::S)},
                                 {s.a, read(Param::a)},
                                 {s.J_oh, read(Param::J_oh)}};
    if (x.any())
        inputs.insert(inputs.end(), {{s.m_tip, read(Param::m_tip)},
                                     {s.J_tip, read(Param::J_tip)},
                                     {s.g, read(Param::g)},
                                     {s.alpha, read(Param::alpha)},
                                     {s.beta, read(Param::beta)},
                                     {s.tip_ratio, read(Param::tip_ratio)}});
    if (s.o) {
        // The out-of-plane model's (docs/model.md section 12): j_n = rho I, j_c = rho I_flap for a homogeneous section.
        const Symbols::OutOfPlane& o = *s.o;
        inputs.insert(inputs.end(), {{o.EI_flap, read(Param::E) + " * " + read(Param::I_flap)},
                                     {o.GJ, read(Param::G) + " * " + read(Param::J_t)},
                                     {o.j_n, read(Param::rho) + " * " + read(Param::I)},
                                     {o.j_c, read(Param::rho) + " * " + read(Param::I_flap)},
                                     {o.cos_2pitch, "std::cos(2 * " + read(Param::pitch) + ")"},
                                     {o.sin_2pitch, "std::sin(2 * " + read(Param::pitch) + ")"},
                                     {o.twist, read(Param::twist)},
                                     {o.cos_cone, "std::cos(" + read(Param::precone) + ")"},
                                     {o.sin_cone, "std::sin(" + read(Param::precone) + ")"},
                                     {o.g_axis, read(Param::g_axis)}});
    }
    for (const auto& [i, x] : s.inputs) {
        static constexpr const char* around[][2] = {{"", ""}, {"std::cos(", ")"}, {"std::sin(", ")"}};
        const auto& [open, close] = around[static_cast<int>(i.of)];
        inputs.push_back({x, open + read(i.param) + close});
    }
    for (std::size_t n = 0; n < s.section.size(); ++n) inputs.push_back({s.section[n], read_section(n)});
    return inputs;
}

/// The symbols every other kernel reads from u, q and qd: the drive values the variant reads, gravity's sin and cos
/// of the angle, then the coordinates and their rates.
std::vector<Input> state_inputs(const Symbols& s, const VariantKey& key)
{
    std::vector<Input> inputs;
    if (key.drive == Drive::torque)
        inputs.push_back({s.tau, read(DriveValue::tau)});
    else
        inputs.insert(inputs.end(),
                      {{s.theta_dot, read(DriveValue::theta_dot)}, {s.theta_ddot, read(DriveValue::theta_ddot)}});
    if (kernels_read_angle(key))
        inputs.insert(inputs.end(),
                      {{s.sin_theta, read(AngleValue::sin_theta)}, {s.cos_theta, read(AngleValue::cos_theta)}});
    for (std::size_t i = 0; i < s.q.size(); ++i) inputs.push_back({s.q[i], "q[" + std::to_string(i) + "]"});
    for (std::size_t i = 0; i < s.qd.size(); ++i) inputs.push_back({s.qd[i], "qd[" + std::to_string(i) + "]"});
    return inputs;
}

/// The kernels' inputs: the parameters p, read once by the coefficients kernel, and the state u, q, qd.
Signature signature(const Symbols& s, const VariantKey& key)
{
    const int nq = key.nq();
    const std::size_t p_count = read_parameter_names(key).size() + s.section.size();
    Signature sig;
    sig.parameters = {"p", static_cast<int>(p_count), "p = " + parameter_tuple(key, s.section.size())};
    sig.derivative_entries = static_cast<int>(key.params_read());
    sig.state = {
        {"u", static_cast<int>(input_names(kernels_read_angle(key)).size()), ""}, {"q", nq, ""}, {"qd", nq, ""}};
    sig.parameter_inputs = parameter_inputs(s, key);
    sig.state_inputs = state_inputs(s, key);
    return sig;
}

/// Lagrange's equations of one variant as polynomials in the kernels' variables, and where those variables are.
struct Derivation {
    PolyEquations eq;
    Variables v;
    PolyCoordinates c;
    std::size_t parameter_count = 0;
};

/// Lagrange's equations on the energies, over sig's parameter and state inputs; without_point_terms: of T without
/// order full's terms beyond order first (points.hpp).
Derivation derive(const VariantKey& key, const Symbols& s, const Signature& sig, bool without_point_terms = false)
{
    const bool torque = key.drive == Drive::torque;
    std::vector<symbol> parameters, variables = sig.state_inputs_symbols();
    for (const Input& i : sig.parameter_inputs) parameters.push_back(i.symbol);
    const auto variable = [&](const symbol& x) {
        for (std::size_t i = 0; i < variables.size(); ++i)
            if (variables[i] == x) return static_cast<int>(i);
        return -1;
    };
    Variables v;
    for (const symbol& x : s.q) v.q.push_back(variable(x));
    for (const symbol& x : s.qd) v.qd.push_back(variable(x));
    v.tau = variable(s.tau);
    v.theta_dot = variable(s.theta_dot);
    v.theta_ddot = variable(s.theta_ddot);
    v.sin_theta = variable(s.sin_theta);
    v.cos_theta = variable(s.cos_theta);
    const PolyReader reader(parameters, variables);
    PolyCoordinates c;
    c.q = v.q;
    c.qd = v.qd;
    c.force.resize(s.q.size());
    c.spin = torque ? v.qd[0] : v.theta_dot;
    if (torque)
        c.force[0] = reader(s.tau);
    else
        c.driven.emplace_back(v.theta_dot, v.theta_ddot);
    if (kernels_read_angle(key)) {
        c.angle = torque ? 0 : -1;
        c.angle_sin = v.sin_theta;
        c.angle_cos = v.cos_theta;
        // A prescribed angle moves with time: where T holds its sine and cosine (a moving hub), so do the momenta.
        if (!torque) c.angle_rate = v.theta_dot;
    }
    const Energies en = derive_energies(key, s, reader, without_point_terms);
    c.dissipation = en.D;
    return {lagrange(en.T, en.U, c), v, c, parameters.size()};
}

/// A kernel that writes every value, zeros included.
KernelSpec dense_kernel(std::string name, std::string out, std::string doc, std::vector<Poly> values)
{
    KernelSpec k{std::move(name), std::move(out), std::move(doc), {}};
    k.polys = std::move(values);
    return k;
}

/// M's kernels: M is symmetric, so its upper triangle is emitted, structural zeros are not, and the
/// state-dependent entries (pattern 'v') get a kernel of their own for runtimes that keep the constant ones.
std::pair<KernelSpec, KernelSpec> mass_kernels(const std::vector<Poly>& M, const std::string& pattern, int nq)
{
    const std::string n2 = std::to_string(nq * nq);
    KernelSpec mass{"mass", "M[" + n2 + "]", "row-major; M = d2T/dqd2, upper triangle, nonzero entries only", {}};
    KernelSpec mass_varying{"mass_varying", "M[" + n2 + "]", "as mass, the entries that depend on q only", {}};
    mass.every_right_hand_side = mass_varying.every_right_hand_side = true;
    for (int i = 0; i < nq; ++i)
        for (int j = i; j < nq; ++j) {
            const char kind = pattern[static_cast<std::size_t>(i * nq + j)];
            if (kind == '0') continue;
            for (KernelSpec* k : {&mass, &mass_varying})
                if (k == &mass || kind == 'v') {
                    k->polys.push_back(M[static_cast<std::size_t>(i * nq + j)]);
                    k->slots.push_back(i * nq + j);
                }
        }
    return {std::move(mass), std::move(mass_varying)};
}

KernelSpec tip_kernel(const VariantKey& key, const Symbols& s)
{
    if (key.out_of_plane())
        return {"tip", "tip[5]",
                key.order == Order::zero
                    ? "tip = (u_y(L), u_x1(L), u_x(L), u_z(L), phi(L)), u_x = u_x1 (order zero: no foreshortening)"
                    : "tip = (u_y(L), u_x1(L), u_x(L), u_z(L), phi(L)), u_x = u_x1 - 1/2 (B^T H(L) B + Z^T H_z(L) Z)",
                tip_displacements(key, s)};
    return {"tip", "tip[3]",
            key.order == Order::zero ? "tip = (u_y(L), u_x1(L), u_x(L)), u_x = u_x1 (order zero: no foreshortening)"
                                     : "tip = (u_y(L), u_x1(L), u_x(L)), u_x = u_x1 - 1/2 B^T H(L) B",
            tip_displacements(key, s)};
}

/// Which entries of the runtime's folded product P (nq x K, row-major) can be nonzero, or empty when the runtime
/// folds nothing for this mass pattern. The constant rows C (those of M's entries that do not depend on q) hold
/// C^-1 F_C: C^-1 is block diagonal over the connected components of C's graph, so row i is nonzero at most where
/// some F row of its component is. A varying row (only the hub's, under torque, where every varying entry lies in
/// row and column 0) holds F_0 - b^T C^-1 F_C over the couplings b that are constant, so its F row joined with the
/// rows of C it couples to by a constant entry. The pattern is structural: it holds for every parameter value.
std::vector<bool> folded_pattern(const std::string& mass_pattern, const std::vector<Poly>& F, int nq, std::size_t K)
{
    const auto at = [&](int i, int j) { return mass_pattern[static_cast<std::size_t>(i * nq + j)]; };
    std::vector<bool> varying_row(static_cast<std::size_t>(nq), false);
    for (int i = 0; i < nq; ++i)
        for (int j = 0; j < nq; ++j)
            if (at(i, j) == 'v') {
                if (i != 0 && j != 0) return {};  // a varying entry off the hub's row: no fold
                varying_row[0] = true;
            }
    // Components of C's graph by repeated relabelling (nq is small).
    std::vector<int> component(static_cast<std::size_t>(nq));
    for (int i = 0; i < nq; ++i) component[static_cast<std::size_t>(i)] = i;
    for (bool changed = true; changed;) {
        changed = false;
        for (int i = 0; i < nq; ++i)
            for (int j = 0; j < nq; ++j) {
                auto& ci = component[static_cast<std::size_t>(i)];
                auto& cj = component[static_cast<std::size_t>(j)];
                if (varying_row[static_cast<std::size_t>(i)] || varying_row[static_cast<std::size_t>(j)] ||
                    at(i, j) == '0' || ci == cj)
                    continue;
                ci = cj = std::min(ci, cj);
                changed = true;
            }
    }
    const auto F_nonzero = [&](int i, std::size_t k) { return !F[static_cast<std::size_t>(i) * K + k].is_zero(); };
    std::vector<bool> pattern(static_cast<std::size_t>(nq) * K, false);
    for (int i = 0; i < nq; ++i) {
        if (varying_row[static_cast<std::size_t>(i)]) continue;
        for (int j = 0; j < nq; ++j)
            if (!varying_row[static_cast<std::size_t>(j)] &&
                component[static_cast<std::size_t>(j)] == component[static_cast<std::size_t>(i)])
                for (std::size_t k = 0; k < K; ++k)
                    if (F_nonzero(j, k)) pattern[static_cast<std::size_t>(i) * K + k] = true;
    }
    if (varying_row[0])
        for (std::size_t k = 0; k < K; ++k) {
            bool nonzero = F_nonzero(0, k);
            for (int j = 1; j < nq && !nonzero; ++j)
                nonzero = at(0, j) == 'c' && pattern[static_cast<std::size_t>(j) * K + k];
            pattern[k] = nonzero;
        }
    return pattern;
}

/// Every kernel of a variant, in the order of its table row, and what the row says about them.
struct Kernels {
    std::vector<KernelSpec> list;
    std::string mass_pattern;
    std::size_t nterms = 0;
    bool mass_varies = false, folded = false;
};

/// M's pattern ('0', 'c', 'v' per entry, mass_pattern), order full's quadrature points making the entries their
/// code adds to (and the mirror ones) varying.
std::string mass_pattern_with_points(const Derivation& d, int nq, const PointCode* points)
{
    // An entry that holds the angle's sine or cosine varies with the coordinate theta (a moving hub's couplings).
    std::vector<int> varying = d.v.q;
    if (d.c.angle_sin >= 0) varying.insert(varying.end(), {d.v.sin_theta, d.v.cos_theta});
    std::string pattern = mass_pattern(d.eq.M, varying);
    if (points != nullptr)
        for (int k : points->mass_entries) {
            pattern[static_cast<std::size_t>(k)] = 'v';
            pattern[static_cast<std::size_t>(k % nq * nq + k / nq)] = 'v';
        }
    return pattern;
}

/// The kernels every variant has, in its table row's order: M, Q and its form F m, the energies, the momentum, the
/// tip and the Jacobian's derivatives of Q (taken from jac).
std::vector<KernelSpec> common_kernels(const VariantKey& key, const Symbols& s, const PolyEquations& eq,
                                       const KernelSpec& mass, const TermMatrix& terms, JacobianPieces& jac)
{
    const int nq = key.nq();
    const std::string n2 = std::to_string(nq * nq), n1 = std::to_string(nq);
    const std::string nk = std::to_string(terms.terms.size());
    const std::string nu = std::to_string(nq * static_cast<int>(drive_value_count));
    KernelSpec forces =
        dense_kernel("forces", "Q[" + n1 + "]", "Q = tau e_theta + dT/dq - d(dT/dqd)/dt at qdd = 0 - dU/dq", eq.Q);
    KernelSpec forces_terms = dense_kernel("forces_terms", "m[" + nk + "]", "the state monomials of Q: Q = F m", terms.terms);
    forces.every_right_hand_side = forces_terms.every_right_hand_side = true;
    return {
        mass,
        std::move(forces),
        std::move(forces_terms),
        sparse_kernel("forces_matrix", "F[" + n1 + "*" + nk + "]", "row-major, state-free: Q = F m", terms.matrix),
        dense_kernel("energy", "E[4]", "E = (T2, T1, T0, U), T split by degree in qd", {eq.T2, eq.T1, eq.T0, eq.U}),
        dense_kernel("momentum", "h[1]", "h = dT/dtheta_dot, angular momentum about the hub axis", {eq.momentum}),
        tip_kernel(key, s),
        sparse_kernel("forces_q", "dQdq[" + n2 + "]", "row-major; out[i*" + n1 + "+k] = dQ_i/dq_k",
                      std::move(jac.forces_q)),
        sparse_kernel("forces_qd", "dQdqd[" + n2 + "]", "row-major; out[i*" + n1 + "+k] = dQ_i/dqd_k",
                      std::move(jac.forces_qd)),
        sparse_kernel("forces_u", "dQdu[" + nu + "]",
                      "row-major; out[i*3+j] = dQ_i/du_j, u = " + tuple(drive_value_names), std::move(jac.forces_u)),
    };
}

/// Order full's code for its quadrature points' terms, added to the kernels of list (common_kernels' order) and to
/// M's varying entries.
void add_point_terms(std::vector<KernelSpec>& list, KernelSpec& mass_varying, const PointCode& points)
{
    const auto add = [&](KernelSpec& k, const std::string& tail) {
        k.tail = tail;
        k.tail_coefficients = points.coefficients;
        k.doc += "; plus the quadrature points' terms";
    };
    add(list[0], points.mass);
    add(mass_varying, points.mass);
    add(list[1], points.forces);
    add(list[4], points.energy);
    add(list[5], points.momentum);
    add(list[7], points.forces_q);
    add(list[8], points.forces_qd);
    if (!points.forces_u.empty()) add(list[9], points.forces_u);
}

/// The kernel of P m, added to out where the runtime folds M's constant part into F (folded_pattern) and unrolling
/// still pays; out.folded says whether it was.
void add_folded_kernel(Kernels& out, const TermMatrix& terms, int nq)
{
    const std::string n1 = std::to_string(nq), nk = std::to_string(terms.terms.size());
    // The runtime folds M's constant part into F once (folded_pattern); this kernel evaluates P m with P's entries at
    // fixed places, unrolled over the entries that can be nonzero, up to a size where unrolling stops paying (the
    // runtime then walks a table of P's nonzeros).
    std::vector<bool> pattern = folded_pattern(out.mass_pattern, terms.matrix, nq, terms.terms.size());
    const auto folded_terms = static_cast<std::size_t>(std::count(pattern.begin(), pattern.end(), true));
    out.folded = !pattern.empty() && folded_terms <= 2000;
    if (!out.folded) return;
    constexpr std::size_t W = generated::folded_lanes;
    KernelSpec f = dense_kernel(
        "forces_folded", "y[" + n1 + "]",
        "y = P m, P (" + n1 + " x " + nk + ") passed in the c slot by groups of " + std::to_string(W) +
            " rows, P(i, k) at c[(j/" + std::to_string(W) + ")*" + std::to_string(W * terms.terms.size()) + " + " +
            std::to_string(W) + "k + j%" + std::to_string(W) + "], j = i" +
            (out.mass_varies ? " + " + std::to_string(W - 1) : "") + ": M^-1 F for a constant M, else C^-1 F_C in " +
            "the rows of M's constant block C and F_0 - b^T C^-1 F_C in the hub's (b its constant couplings); " +
            "of the " + std::to_string(folded_terms) + " entries that can be nonzero, a group of rows reads the " +
            "columns any of its rows has",
        terms.terms);
    f.rows = nq;
    f.row_offset = out.mass_varies ? W - 1 : 0;  // the hub's row, which couples to every other, stays alone
    f.pattern = std::move(pattern);
    out.list.push_back(f);
}

/// M's varying entries and (dM/dq) v, added to out for a mass matrix that depends on q (with order full's points'
/// terms where it has them).
void add_varying_mass_kernels(Kernels& out, int nq, KernelSpec mass_varying, std::vector<Poly> mass_q_product,
                              const PointCode* points)
{
    const std::string n2 = std::to_string(nq * nq), n1 = std::to_string(nq);
    out.list.push_back(std::move(mass_varying));
    out.list.push_back(sparse_kernel("mass_q_product", "dMv[" + n2 + "]",
                                     "row-major; v in the qd slot; out[i*" + n1 + "+k] = sum_j dM_ij/dq_k v_j",
                                     std::move(mass_q_product)));
    if (points != nullptr) {
        out.list.back().tail = points->mass_q_product;
        out.list.back().tail_coefficients = points->coefficients;
        out.list.back().doc += "; plus the quadrature points' terms";
    }
}

/// points: where order full's foreshortening terms go to quadrature points (d then holds the equations without
/// them), the code that every kernel of M, Q, the energies and the Jacobian adds; Q then has no form F m.
Kernels variant_kernels(const VariantKey& key, const Symbols& s, const Derivation& d, const PointCode* points = nullptr)
{
    const PolyEquations& eq = d.eq;
    const int nq = key.nq();
    Kernels out;
    JacobianPieces jac = jacobian_pieces(eq, d.v, d.c, key.drive == Drive::torque);
    out.mass_pattern = mass_pattern_with_points(d, nq, points);
    auto [mass, mass_varying] = mass_kernels(eq.M, out.mass_pattern, nq);
    out.mass_varies = !mass_varying.polys.empty();
    // Q = F m lets the runtime fold M^-1 into F once: all of M where it is constant (prescribed rotation), the
    // constant beam block where only the hub's entry varies (hub torque without axial coordinates).
    const TermMatrix terms = points == nullptr ? term_matrix(eq.Q, d.parameter_count) : TermMatrix{};
    out.nterms = terms.terms.size();
    out.list = common_kernels(key, s, eq, mass, terms, jac);
    if (points != nullptr) add_point_terms(out.list, mass_varying, *points);
    add_folded_kernel(out, terms, nq);
    // A constant M has dM/dq = 0: no kernels, null pointers in the table row, and the runtime skips the terms.
    if (out.mass_varies)
        add_varying_mass_kernels(out, nq, std::move(mass_varying), std::move(jac.mass_q_product), points);
    return out;
}

/// The variant's table row: designated initializers in the order of generated_abi.h's fields (C++20 requires
/// that order), so that a field renamed, removed or moved there makes the generated source fail to compile
/// instead of shifting every later pointer.
std::string table_row(const std::string& name, int nq, int ncoeff, bool affine, const Kernels& k, std::size_t sections)
{
    const auto kernel = [&](const char* kernel) { return name + "_" + kernel; };
    const auto optional = [&](bool present, const char* kernel) {
        return present ? name + "_" + kernel : std::string("nullptr");
    };
    const std::vector<std::pair<const char*, std::string>> row = {
        {"abi_version", std::to_string(generated::abi_version)},
        {"name", "\"" + name + "\""},
        {"nq", std::to_string(nq)},
        {"ncoeff", std::to_string(ncoeff)},
        {"nterms", std::to_string(k.nterms)},
        {"mass_pattern", "\"" + k.mass_pattern + "\""},
        {"coefficients", kernel("coefficients")},
        {"coefficients_p", optional(affine, "coefficients_p")},
        {"mass", kernel("mass")},
        {"mass_varying", optional(k.mass_varies, "mass_varying")},
        {"forces", kernel("forces")},
        {"forces_terms", kernel("forces_terms")},
        {"forces_matrix", kernel("forces_matrix")},
        {"energy", kernel("energy")},
        {"momentum", kernel("momentum")},
        {"forces_q", kernel("forces_q")},
        {"forces_qd", kernel("forces_qd")},
        {"mass_q_product", optional(k.mass_varies, "mass_q_product")},
        {"forces_u", kernel("forces_u")},
        {"tip", kernel("tip")},
        {"forces_folded", optional(k.folded, "forces_folded")},
    };
    std::vector<std::pair<const char*, std::string>> fields = row;
    fields.insert(fields.end(),
                  {{"nsection", std::to_string(sections)},
                   {"section_integrals", sections > 0 ? name + "_section_integrals" : std::string("nullptr")}});
    std::string text = "extern const Variant " + name + " = {\n";
    for (const auto& [field, value] : fields) text += "    ." + std::string(field) + " = " + value + ",\n";
    return text + "};\n";
}

}  // namespace

std::string variant_source(const VariantKey& key, const EmitOptions& options)
{
    const Symbols s(key);
    const Signature sig = signature(s, key);
    const bool at_points = foreshortening_at_points(key);
    const Derivation d = derive(key, s, sig, at_points);
    const PointCode points = at_points ? point_code(key, s) : PointCode{};
    Kernels kernels = variant_kernels(key, s, d, at_points ? &points : nullptr);
    const std::string name = key.name();
    EmitOptions emit_options = options;
    // The pre-twist enters through section integrals, which dc/dp does not see (they are data, not parameters): a
    // twisted variant's sensitivities are differenced, which recomputes them; so are a tabulated blade's, whose
    // coefficients are long sums over its section integrals.
    emit_options.parameter_derivatives =
        options.parameter_derivatives && !key.extras.twist && !(key.out_of_plane() && key.extras.profile());
    const EmittedCode code = emit_kernels(name, sig, std::move(kernels.list), emit_options);
    std::ostringstream f;
    // std::cos and std::sin of the pitch and the precone, once per parameter set in the coefficients kernel.
    const std::string cmath = key.out_of_plane() ? "\n#include <cmath>\n" : "";
    const std::size_t sections = s.section.size();
    f << banner(key, kernels.mass_varies, sections) << cmath
      << "\n#include \"generated_abi.h\"\n\nnamespace hubbeam::generated {\n\nnamespace {\n"
      << (at_points ? "\n" + points.tables : std::string()) << code.text
      << (sections > 0 ? "\n" + section_table(name, s) : std::string()) << "\n}  // namespace\n\n"
      << table_row(name, key.nq(), code.ncoeff, code.affine, kernels, sections)
      << "\n}  // namespace hubbeam::generated\n";
    return f.str();
}

std::string module_entry_source(const std::string& name)
{
    return "\n// The entry point of this source built as a shared object (an on-demand variant).\n"
           "extern \"C\" __attribute__((visibility(\"default\"))) const hubbeam::generated::Variant* "
           "hubbeam_variant();\n"
           "extern \"C\" const hubbeam::generated::Variant* hubbeam_variant() { return &hubbeam::generated::" +
           name + "; }\n";
}

std::string registry_source(const std::vector<std::string>& names)
{
    std::ostringstream f;
    f << "// The table of generated variants compiled into this build.\n"
      << "// Generated by hubbeam-gen " HUBBEAM_VERSION ". Do not edit: regenerate with\n"
      << "//   cmake --build build --target regenerate\n\n#include \"generated_abi.h\"\n\nnamespace hubbeam::generated "
         "{\n\n";
    for (const std::string& n : names) f << "extern const Variant " << n << ";\n";
    f << "\nconst Variant* const variants[] = {\n";
    for (const std::string& n : names) f << "    &" << n << ",\n";
    if (names.empty()) f << "    nullptr,\n";
    f << "};\nconst int variant_count = " << names.size() << ";\n\n}  // namespace hubbeam::generated\n";
    return f.str();
}

}  // namespace hubbeam::gen
