// The assembled path's part of each physics term (model/terms.hpp): what it adds to the constant matrices of
// docs/model.md sections 5 and 11 from which the assembled model forms M and Q. One file per term,
// runtime/src/models/terms/NAME.cpp; the table in terms/assembled_terms.cpp lines them up with the registry. The
// section terms (taper, profile) act inside the beam's quadrature (assemble_matrices) and add nothing here.
#pragma once

#include <Eigen/Dense>

#include "models/assembled.hpp"
#include "terms.hpp"

namespace hubbeam {

/// The constant matrices of M, Q and the energies: section 5.2's beam with its terms (sections 11.1, 11.3, 11.4).
struct ModelMatrices {
    double J_o = 0.0;               // J_oh + J_ob (+ m_tip (a+L)^2 + J_tip)
    Eigen::RowVectorXd S_x, S_y;
    Eigen::MatrixXd M1, M2, M3;
    Eigen::MatrixXd M2r;            // the B-rate mass: M2 (+ J_tip Phi_y'(L)^T Phi_y'(L))
    Eigen::MatrixXd G;              // a C + D (+ m_tip (a+L) H(L))
    // Section 11.3's weight: U_g = g sin(theta) (W_o + W_x A - 1/2 B^T W_H B) + g cos(theta) W_y B.
    double g = 0.0, W_o = 0.0;
    Eigen::RowVectorXd W_x, W_y;
    Eigen::MatrixXd W_H;            // C (+ m_tip H(L)); zero at order zero
    // Section 11.4's damping: alpha M1 + beta K1, alpha M2r + beta K2; empty without it.
    Eigen::MatrixXd D_A, D_B;
    bool damped = false;
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

// One per term (runtime/src/models/terms/NAME.cpp).
void add_tip(const AssemblyContext& a, ModelMatrices& m);
void add_gravity(const AssemblyContext& a, ModelMatrices& m);
void add_damping(const AssemblyContext& a, ModelMatrices& m);

}  // namespace hubbeam
