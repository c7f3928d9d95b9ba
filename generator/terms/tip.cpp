// The tip body's kinetic energy (docs/model.md section 11.1): m_tip at x = L moving with the beam's end, J_tip turning
// with the hub and the slope there; or, with its flap and torsion inertias or its offset (tip_body), a rigid body
// carried by the tip section in the blade's axes. Its weight and damping are added by gravity.cpp and damping.cpp.
#include "generator_terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

void tip_energies(const TermContext& c, Energies& e)
{
    const Symbols& s = c.s;
    e.T += c.at_tip(s.m_tip * c.v2 / 2);
    // With its own axes the body's rotation is tip_body_energies' (J_tip about the chord's normal there).
    if (!c.key.extras.tip_body) e.T += c.at_tip(s.J_tip * pow(s.theta_dot + c.f.uy_x_dot, 2) / 2);
}

/// The rate in the inertial frame, in hub components, of a vector a carried by the section (a function of phi and
/// the slopes): its rate in the hub frame plus the frame's turn w k x a.
std::array<ex, 3> inertial_rate(const std::array<ex, 3>& a, const FieldSymbols& f, const ex& w)
{
    std::array<ex, 3> rate;
    for (std::size_t n = 0; n < 3; ++n)
        rate[n] = a[n].diff(f.phi) * f.phi_dot + a[n].diff(f.uy_x) * f.uy_x_dot + a[n].diff(f.uz_x) * f.offsets->uz_x_dot;
    return {rate[0] - w * a[1], rate[1] + w * a[0], rate[2]};
}

ex dot(const std::array<ex, 3>& a, const std::array<ex, 3>& b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

}  // namespace

namespace {

/// The tip body's axes at the tip, in hub components: the chord (towards the leading edge), its normal (the chord
/// turned a quarter turn further from e2 towards e3) and the bent axis's tangent, their cross product.
struct TipAxes {
    std::array<ex, 3> chord, normal, tangent;
};

TipAxes tip_axes(const TermContext& c)
{
    const Cone cone = cone_of(c.key, c.s);
    const ex C = c.s.input("cos_pitch"), S = c.s.input("sin_pitch");
    TipAxes a{chord(c.f, cone, C, S), chord(c.f, cone, -S, C), {}};
    const std::array<ex, 3>& c_ = a.chord, &n = a.normal;
    a.tangent = {c_[1] * n[2] - c_[2] * n[1], c_[2] * n[0] - c_[0] * n[2], c_[0] * n[1] - c_[1] * n[0]};
    return a;
}

/// The centre of mass from the beam's end on the body's axes: tip_offset is positive towards the trailing edge, the
/// chord towards the leading edge.
std::array<ex, 3> centre_on(const TermContext& c, const TipAxes& a)
{
    const ex d = -c.s.input("tip_offset");
    return {d * a.chord[0], d * a.chord[1], d * a.chord[2]};
}

}  // namespace

std::array<ex, 3> tip_body_centre(const TermContext& c)
{
    return centre_on(c, tip_axes(c));
}

namespace {

void tip_body_energies(const TermContext& c, Energies& e)
{
    const Symbols& s = c.s;
    const FieldSymbols& f = c.f;
    const ex w = s.theta_dot;
    const TipAxes axes = tip_axes(c);
    // About its centre of mass, 1/2 omega . J omega with J = J_t t t^T + J_c c c^T + J_n n n^T is 1/2 sum_a P_a
    // |a_dot|^2 with the body's second moments of mass P_t = (J_c + J_n - J_t)/2, ... (|a_dot|^2 = |omega|^2 -
    // (omega . a)^2); the centre of mass at r from the beam's end (tip_body_centre) adds m V . r_dot + m |r_dot|^2 / 2
    // to the beam's end's m |V|^2 / 2 (docs/model.md section 11.1).
    const ex J_n = s.J_tip, J_c = s.input("J_tip_flap"), J_t = s.input("J_tip_twist");
    const ex P_t = (J_c + J_n - J_t) / 2, P_c = (J_t + J_n - J_c) / 2, P_n = (J_t + J_c - J_n) / 2;
    const std::array<ex, 3> t_dot = inertial_rate(axes.tangent, f, w), c_dot = inertial_rate(axes.chord, f, w),
                            n_dot = inertial_rate(axes.normal, f, w), r_dot = inertial_rate(centre_on(c, axes), f, w);
    const Position p = position(c.key.order, f, cone_of(c.key, s));
    const std::array<ex, 3> V = {p.i_dot - w * p.j, p.j_dot + w * p.i, p.k_dot};
    const ex T = (P_t * dot(t_dot, t_dot) + P_c * dot(c_dot, c_dot) + P_n * dot(n_dot, n_dot)) / 2 +
                 s.m_tip * (dot(V, r_dot) + dot(r_dot, r_dot) / 2);
    e.T += c.at_tip(second_order(T, f));
}

}  // namespace

const GeneratorTerm tip_term = {.energies = tip_energies};

// Its flap and torsion inertias, its offset along the chord, and the pitch that turns its axes.
const GeneratorTerm tip_body_term = {.energies = tip_body_energies,
                                     .inputs = {{"J_tip_flap", Param::J_tip_flap},
                                                {"J_tip_twist", Param::J_tip_twist},
                                                {"tip_offset", Param::tip_offset},
                                                {"cos_pitch", Param::pitch, TermInput::Of::cos},
                                                {"sin_pitch", Param::pitch, TermInput::Of::sin}}};

}  // namespace hubbeam::gen
