// The assembled path's part of each physics term (model/terms.hpp): what it adds to the constant matrices of
// docs/model.md sections 5 and 11 from which the assembled model forms M and Q. One file per term,
// runtime/src/models/assembled/terms/NAME.cpp; the table in terms/assembled_terms.cpp lines them up with the registry. The
// section terms (taper, profile) act inside the beam's quadrature (assemble_matrices) and add nothing here.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "models/assembled/assembled.hpp"
#include "models/assembled/forms.hpp"
#include "terms.hpp"

namespace hubbeam {

/// The constant matrices of M, Q and the energies: section 5.2's beam with its terms (sections 11.1, 11.3, 11.4), and
/// section 12.3's out of the plane. R_L = a + L cos(beta_c) is the tip's arm (a + L without a precone).
struct ModelMatrices {
    double J_o = 0.0;  // J_oh + J_ob (+ m_tip R_L^2 + J_tip)
    Eigen::RowVectorXd S_x, S_y;
    Eigen::MatrixXd M1, M2, M3;
    Eigen::MatrixXd M2r;  // the B-rate mass: M2 (+ J_tip Phi_y'(L)^T Phi_y'(L))
    Eigen::MatrixXd G;    // a C + cb D (+ m_tip R_L H(L))
    // Section 11.3's weight: U_g = g sin(theta) (W_o + W_x A - 1/2 B^T W_H B) + g cos(theta) W_y B.
    double g = 0.0, W_o = 0.0;
    Eigen::RowVectorXd W_x, W_y;
    Eigen::MatrixXd W_H;  // C (+ m_tip H(L)); zero at order zero
    // Section 11.4's damping: alpha M1 + beta K1, alpha M2r + beta K2; empty without it.
    Eigen::MatrixXd D_A, D_B;
    bool damped = false;
    // Section 12.3: the flapwise and twist matrices with the tip body's point values, gravity along the spin axis
    // (g_axis, read by a variant that leaves the plane) and the damping's factors, which weigh the whole mass and
    // stiffness of the elastic coordinates there.
    OutOfPlaneMatrices o;
    double g_axis = 0.0, alpha = 0.0, beta = 0.0;
    // Section 12.3's forms of the terms placed there whole (a blade's section offsets, the tip body in the blade's
    // axes), added after the beam's damping is formed.
    std::vector<QuadraticForms> forms;
};

/// What a term's twin reads: the variant, its parameters and the beam's matrices.
struct AssemblyContext {
    const VariantKey& key;
    const Parameters& p;
    const BeamMatrices& c;
};

/// The beam's own matrices (no term): section 5.2's.
ModelMatrices beam_model_matrices(const AssemblyContext& a);

/// The assembled twin of a registered term: adds its values to m (null for a section term).
using AssembledTerm = void (*)(const AssemblyContext&, ModelMatrices&);
AssembledTerm assembled_part(const TermInfo& t);

/// The beam's matrices with every term the variant carries added, in registry order.
ModelMatrices model_matrices(const AssemblyContext& a);

// One per term (runtime/src/models/assembled/terms/NAME.cpp).
void add_tip(const AssemblyContext& a, ModelMatrices& m);
/// The tip body's part of section 12.3's matrices (nothing for a planar variant, whose flap field is empty).
void add_tip_out_of_plane(const AssemblyContext& a, ModelMatrices& m);
void add_gravity(const AssemblyContext& a, ModelMatrices& m);
void add_damping(const AssemblyContext& a, ModelMatrices& m);
void add_offsets(const AssemblyContext& a, ModelMatrices& m);
/// Sections 12.5 and 12.6's terms of a blade's offsets o placed in q (the tip body's centre of mass uses them too).
void add_offset_forms(const FieldBlocks& f, const VariantKey& key, const OffsetMatrices& o, QuadraticForms& q);
void add_tip_body(const AssemblyContext& a, ModelMatrices& m);

}  // namespace hubbeam
