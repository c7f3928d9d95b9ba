// The assembled twins lined up with the registry (model/terms.hpp): the one place a term's assembled part is named.
#include "models/assembled/assembled_terms.hpp"

#include <array>
#include <stdexcept>

namespace hubbeam {

AssembledTerm assembled_part(const TermInfo& t)
{
    // In the order of terms(): tip, gravity, damping, taper, profile (the last two inside assemble_matrices), the
    // section offsets (their own forms of section 12.3), pitch, pre-twist and
    // precone (inside the beam's quadrature too: the chord's angle and the axis's tilt, out_of_plane_matrices.cpp and
    // assemble_matrices), and the moving hub, whose coordinates have no place in these matrices (the quadratic forms'
    // model adds it: assembled_forms.cpp), and the tip body in the blade's axes (its own forms too, terms/tip.cpp).
    static const std::array<AssembledTerm, 11> table = {add_tip, add_gravity, add_damping, nullptr,
                                                        nullptr, add_offsets, nullptr,     nullptr,
                                                        nullptr, nullptr,     add_tip_body};
    if (table.size() != terms().size()) throw std::logic_error("assembled_part: not one entry per registered term");
    return table.at(static_cast<std::size_t>(&t - terms().data()));
}

ModelMatrices beam_model_matrices(const AssemblyContext& a)
{
    const BeamMatrices& c = a.c;
    ModelMatrices m;
    m.J_o = a.p.J_oh + c.J_ob;
    m.S_x = c.S_x;
    m.S_y = c.S_y;
    m.M1 = c.M1;
    m.M2 = c.M2;
    m.M3 = c.M3;
    m.M2r = c.M2;
    m.G = c.G;
    m.W_o = c.S_ob;
    m.W_x = c.P_x;
    m.W_y = c.P_y;
    m.W_H = a.key.order == Order::zero ? Eigen::MatrixXd::Zero(a.key.ny, a.key.ny) : c.C;
    m.o = c.o;
    return m;
}

ModelMatrices model_matrices(const AssemblyContext& a)
{
    ModelMatrices m = beam_model_matrices(a);
    for (const TermInfo* t : carried_terms(a.key.extras))
        if (const AssembledTerm add = assembled_part(*t)) add(a, m);
    return m;
}

}  // namespace hubbeam
