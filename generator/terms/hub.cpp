// A moving hub's energies (docs/model.md section 13): the hub's centre translates by (x_h, y_h) in the plane of
// rotation on a support of stiffness k_x, k_y and damping c_x, c_y, carrying the translating mass m_hub; every point
// of the blade (and a tip body) moves with it.
#include "generator_terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

void hub_energies(const TermContext& c, Energies& e)
{
    const Symbols& s = c.s;
    const Symbols::MovingHub& h = *s.h;
    const FieldSymbols& f = c.f;
    // The hub's velocity in the blade's frame (i along the blade's root, j ahead of it): v_i, v_j.
    const ex v_i = h.x_dot * s.cos_theta + h.y_dot * s.sin_theta, v_j = -h.x_dot * s.sin_theta + h.y_dot * s.cos_theta;
    // |v_h + r_dot|^2 = v_h^2 + 2 v_h . r_dot + |r_dot|^2: the last is the beam's own T, v_h^2 = x_h_dot^2 + y_h_dot^2
    // exactly (written so, for the sine and cosine to cancel), and the cross term couples the hub to the beam.
    const Position p = position(c.key.order, f, cone_of(c.key, s));
    const ex w = s.theta_dot;
    ex cross = (v_i * (p.i_dot - w * p.j) + v_j * (p.j_dot + w * p.i)).expand();
    if (c.key.order != Order::full) {
        // Second order in x_h, y_h, the deformation and their rates (docs/model.md section 3): v is first order.
        const symbol eps("eps");
        cross = cross
                    .subs(lst{h.x_dot == eps * h.x_dot, h.y_dot == eps * h.y_dot, f.ux1 == eps * f.ux1,
                              f.uy == eps * f.uy, f.ux1_dot == eps * f.ux1_dot, f.uy_dot == eps * f.uy_dot,
                              f.uz == eps * f.uz, f.uz_dot == eps * f.uz_dot, f.ux2 == pow(eps, 2) * f.ux2,
                              f.ux2_dot == pow(eps, 2) * f.ux2_dot})
                    .expand();
        cross = cross.coeff(eps, 1) + cross.coeff(eps, 2);
    }
    const ex v2 = pow(h.x_dot, 2) + pow(h.y_dot, 2);
    const ex m_hub = s.input("m_hub"), k_x = s.input("k_x"), k_y = s.input("k_y"), c_x = s.input("c_x"),
             c_y = s.input("c_y");
    e.T += c.integrate(c.beam.mass * (cross + v2 / 2));
    if (c.key.extras.tip) e.T += c.at_tip(s.m_tip * (cross + v2 / 2));
    const auto read = [&](const ex& x) { return c.at_tip(x); };
    e.T += read(m_hub * v2 / 2);
    e.U += read((k_x * pow(h.x, 2) + k_y * pow(h.y, 2)) / 2);
    e.D += read((c_x * pow(h.x_dot, 2) + c_y * pow(h.y_dot, 2)) / 2);
    // Gravity along -j of the inertial plane lifts the whole rotor with y_h: the hub's mass here, the beam's and the
    // tip body's weight too (their points sit at y_h + their height in the plane).
    if (c.key.extras.gravity) {
        e.U += read(s.g * m_hub * h.y);
        e.U += c.integrate(s.g * c.beam.mass * h.y);
        if (c.key.extras.tip) e.U += c.at_tip(s.g * s.m_tip * h.y);
    }
}

}  // namespace

// Its parameters: the translating mass, the support's stiffness and damping.
const GeneratorTerm hub_term = {.energies = hub_energies,
                                .inputs = {{"m_hub", Param::m_hub},
                                           {"k_x", Param::k_x},
                                           {"k_y", Param::k_y},
                                           {"c_x", Param::c_x},
                                           {"c_y", Param::c_y}}};

}  // namespace hubbeam::gen
