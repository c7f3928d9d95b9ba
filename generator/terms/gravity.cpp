// Gravity's potential (docs/model.md sections 11.3 and 12): the weight of the beam and of a tip body along -j of a
// vertical plane of motion (g), and along the spin axis -k (g_axis, a variant that leaves the plane); a tip body's
// centre of mass off the beam's end.
#include "generator_terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

void gravity_energies(const TermContext& c, Energies& e)
{
    const Symbols& s = c.s;
    // The height of a point in the plane, p rotated by theta: sin(theta) p_i + cos(theta) p_j; order zero has no u_x2.
    const Position p = position(c.key.order, c.f, cone_of(c.key, s));
    const auto height = [&](const ex& i, const ex& j, const ex& k) {
        const ex h = s.g * (s.sin_theta * i + s.cos_theta * j);
        return c.key.out_of_plane() ? h + s.o->g_axis * k : h;
    };
    const ex weight = height(p.i, p.j, p.k);
    e.U += c.integrate(c.beam.mass * weight);
    if (c.key.extras.tip) e.U += c.at_tip(s.m_tip * weight);
    // A tip body's centre of mass off the beam's end (docs/model.md section 11.1).
    if (c.key.extras.tip_body) {
        const std::array<ex, 3> r = tip_body_centre(c);
        e.U += c.at_tip(second_order(s.m_tip * height(r[0], r[1], r[2]), c.f));
    }
}

}  // namespace

const GeneratorTerm gravity_term = {.energies = gravity_energies};

}  // namespace hubbeam::gen
