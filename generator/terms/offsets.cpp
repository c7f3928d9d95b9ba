// A blade's section offsets (docs/model.md sections 12.5 and 12.6): the centre of mass and the tension centre off the
// reference axis along the chord. A rigid section's kinetic energy about the reference point is m |v|^2 + 2 m d v .
// c_dot + (its rotation): the beam's T holds the first and section_rotation the last (mass moments about the reference
// axis, the bending slopes' share of the rotation left out); this term adds the middle, the reference point's velocity
// against the chord's, to second order in the deformation, and the offset mass's share of the rotation that the slopes
// turn, so that the centre of mass moves as a point should. The axial strain at the tension centre, u_x1' - d_A
// kappa_c, squared under EA: the beam's U holds EA u_x1'^2 and the table's bending stiffnesses (about the reference
// axis) EA d_A^2 kappa_c^2; this term adds the cross term.
#include <array>

#include "generator_terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

std::array<ex, 3> chord(const FieldSymbols& f, const Cone& cone, const ex& C, const ex& S)
{
    const ex cos_psi = C * (1 - pow(f.phi, 2) / 2) - S * f.phi, sin_psi = S * (1 - pow(f.phi, 2) / 2) + C * f.phi;
    const ex sigma = f.uy_x * cos_psi + f.uz_x * sin_psi;
    const ex c1 = -sigma, c2 = cos_psi - f.uy_x * sigma / 2, c3 = sin_psi - f.uz_x * sigma / 2;
    // e1 = cos i + sin k, e2 = j, e3 = -sin i + cos k.
    return {c1 * cone.cos - c3 * cone.sin, c2, c1 * cone.sin + c3 * cone.cos};
}

ex second_order(const ex& e, const FieldSymbols& f)
{
    const symbol eps("eps");
    lst first = {f.ux1,     f.uy,     f.uz,     f.phi,     f.uy_x,     f.uz_x,
                 f.ux1_dot, f.uy_dot, f.uz_dot, f.phi_dot, f.uy_x_dot, f.offsets->uz_x_dot};
    exmap scaled;
    for (const ex& x : first) scaled[x] = eps * x;
    scaled[f.ux2] = pow(eps, 2) * f.ux2;
    scaled[f.ux2_dot] = pow(eps, 2) * f.ux2_dot;
    const ex expanded = e.subs(scaled).expand();
    ex kept = 0;
    for (int k = 0; k <= 2; ++k) kept += expanded.coeff(eps, k);
    return kept;
}

/// The chord's inertial rate in hub components: it turns with phi and the slopes, and the frame with w about k.
std::array<ex, 3> chord_rate(const FieldSymbols& f, const ex& w, const std::array<ex, 3>& d)
{
    std::array<ex, 3> d_dot;
    for (std::size_t n = 0; n < 3; ++n)
        d_dot[n] =
            d[n].diff(f.phi) * f.phi_dot + d[n].diff(f.uy_x) * f.uy_x_dot + d[n].diff(f.uz_x) * f.offsets->uz_x_dot;
    return {d_dot[0] - w * d[1], d_dot[1] + w * d[0], d_dot[2]};
}

/// 1/2 m d^2 (|c_dot|^2 - |c_dot_a|^2): the offset mass's share of the section's rotation that the mass moments about
/// the reference axis leave out, c_a the chord turned by the twist and the spin alone (section_rotation's). It is
/// quadratic in the unit chord's cos and sin, whose products are written in the second moment's distributions m d^2,
/// m d^2 cos 2 psi, m d^2 sin 2 psi.
ex offset_rotation(const FieldSymbols& f, const Cone& cone, const ex& w)
{
    const symbol C("C"), S("S");
    const std::array<ex, 3> c_dot = chord_rate(f, w, chord(f, cone, C, S));
    const exmap straight = {{f.uy_x, 0}, {f.uz_x, 0}, {f.uy_x_dot, 0}, {f.offsets->uz_x_dot, 0}};
    ex twice = 0;
    for (const ex& r : c_dot) twice += pow(r, 2) - pow(r.subs(straight), 2);
    const ex q = second_order(twice, f).expand();
    const ex cc = q.coeff(C, 2).coeff(S, 0), cs = q.coeff(C, 1).coeff(S, 1), ss = q.coeff(C, 0).coeff(S, 2);
    if (!(q - cc * pow(C, 2) - cs * C * S - ss * pow(S, 2)).expand().is_zero())
        throw std::logic_error("offsets: the chord's rate squared is not a quadratic form in its cos and sin");
    const FieldSymbols::Offsets& o = *f.offsets;
    return (cc * (o.mass_offset2_x + o.mass_offset2_cos_x) + cs * o.mass_offset2_sin_x +
            ss * (o.mass_offset2_x - o.mass_offset2_cos_x)) /
           4;
}

namespace {

void offsets_energies(const TermContext& c, Energies& e)
{
    const FieldSymbols& f = c.f;
    const ex w = c.s.theta_dot;
    const Cone cone = cone_of(c.key, c.s);
    const Position p = position(c.key.order, f, cone);
    const std::array<ex, 3> d =
        chord_rate(f, w, chord(f, cone, f.offsets->mass_offset_cos_x, f.offsets->mass_offset_sin_x));
    // The reference point's inertial velocity in hub components.
    const ex v_i = p.i_dot - w * p.j, v_j = p.j_dot + w * p.i, v_k = p.k_dot;
    e.T += c.integrate(second_order(v_i * d[0] + v_j * d[1] + v_k * d[2], f));
    // Without it the axial rate's coupling to the slopes' rates, -m d u_x1_dot sigma_dot, would stand without the
    // square that completes m/2 (u_x1_dot - d sigma_dot)^2, and a fine mesh's mass matrix would not be positive.
    e.T += c.integrate(offset_rotation(f, cone, w));
    // -EA d_A u_x1' kappa_c, kappa_c = cos psi u_y'' + sin psi u_z'' at the undeformed chord's angle psi = pitch + beta
    // (the twist phi's share is of third order); 0 with nx = 0, which the scene refuses with a tension centre's offset.
    const ex At = f.offsets->tension_offset_cos_x, As = f.offsets->tension_offset_sin_x;
    e.U += c.integrate(-f.ux1_x * (At * f.uy_xx + As * f.uz_xx));
}

}  // namespace

const GeneratorTerm offsets_term = {.energies = offsets_energies};

}  // namespace hubbeam::gen
