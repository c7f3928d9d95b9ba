// A blade's section offsets' assembled twin (docs/model.md sections 12.5 and 12.6): their integrals
// (out_of_plane_matrices.cpp) placed in section 12.3's forms. Without a precone: make_assembled_model refuses one.
#include <utility>

#include "models/assembled/assembled_terms.hpp"

namespace hubbeam {

using Eigen::MatrixXd;
using namespace fields;

/// Sections 12.5 and 12.6's terms of a blade's section offsets (no precone: R = a + x, C, S, D, E as
/// OffsetMatrices says; v = u_y, z = u_z):
///   T_g = int [ (C z_dot - S v_dot) phi_dot - u_x1_dot (C v_dot' + S z_dot')
///             + w ( C (v v_dot' - v_dot v') + S (v z_dot' - v_dot z') - R S phi_dot - (u_x1_dot + u_x2_dot) C
///                   + u_x1_dot S phi - u_x1 S phi_dot - R C phi phi_dot - R (C v' v_dot' + S (v' z')_dot / 2) )
///             + w^2 ( C v - S v phi - R (C v' + S z') + R phi (S v' - C z') - u_x1 (C v' + S z') ) ] dx
///   T_r = 1/2 int D [ sigma_dot^2 + 2 w (sigma_dot cos psi + sigma phi_dot sin psi) + w^2 z' sigma sin psi ] dx
///   U_A = - int u_x1' (E_c v'' + E_s z'') dx
/// with sigma = v' cos psi + z' sin psi, psi the chord's angle with phi, to second order in the deformation. The
/// rates' terms linear in w are w q^T X qd with X general: its skew part joins N, its symmetric part is P.
void add_offset_forms(const FieldBlocks& f, const VariantKey& key, const OffsetMatrices& o, QuadraticForms& q)
{
    const auto both = [&](MatrixXd& m, FieldKind r, FieldKind c, const MatrixXd& v) { f.add_both(m, r, c, v); };
    // M: T_g's couplings of the rates, and T_r's sigma_dot^2 = (v_dot' cos psi + z_dot' sin psi)^2.
    both(q.M, Z, P, o.C_zt);
    both(q.M, B, P, -o.S_yt);
    both(q.M, A, B, -o.C_xy1);
    both(q.M, A, Z, -o.S_xz1);
    f(q.M, B, B) += o.Dcc_yy;
    f(q.M, Z, Z) += o.Dss_zz;
    both(q.M, B, Z, o.Dcs_yz);
    // s: the rates' terms linear in w and in the deformation; T_r's w sigma_dot cos psi at phi = 0.
    f(q.s, P) -= o.RS_t.transpose();
    f(q.s, A) -= o.C_x.transpose();
    f(q.s, B) += o.Dcc_y.transpose();
    f(q.s, Z) += o.Dcs_z.transpose();
    // X: w q^T X qd, row by the coordinate, column by the rate.
    const int n = f.size();
    MatrixXd X = MatrixXd::Zero(n, n);
    f(X, B, B) += o.C_yy1 - o.C_yy1.transpose() - o.RC_yy;
    f(X, B, Z) += o.S_yz1 - 0.5 * o.RS_yz;
    f(X, Z, B) -= o.S_yz1.transpose() + 0.5 * o.RS_yz.transpose();
    if (key.order != Order::zero) {  // -w C u_x2_dot, u_x2 = -1/2 int_0^x (v'^2 + z'^2): the tail C^ weighs it
        f(X, B, B) += o.Ct_yy;
        f(X, Z, Z) += o.Ct_zz;
    }
    f(X, P, A) += o.S_xt.transpose();
    f(X, A, P) -= o.S_xt;
    f(X, P, P) -= o.RC_tt;
    // T_r's w (sigma_dot cos psi + sigma phi_dot sin psi) to second order: psi = psi_0 + phi in sigma and the cosine.
    f(X, Z, P) += o.D_zt;
    f(X, P, B) -= 2.0 * o.Dcs_ty;
    f(X, P, Z) += o.D2c_tz;
    q.N += 0.5 * (X - X.transpose());
    q.P += 0.5 * (X + X.transpose());
    // b and K_w: the centrifugal terms, w^2 (b^T q + 1/2 q^T K_w q), T_r's w^2 z' sigma sin psi among them.
    f(q.b, B) += o.C_y.transpose() - o.RC_y1.transpose();
    f(q.b, Z) -= o.RS_z1.transpose();
    both(q.K_w, B, P, -o.S_yt);
    both(q.K_w, P, B, o.RS_ty);
    both(q.K_w, P, Z, -o.RC_tz);
    both(q.K_w, A, B, -o.C_xy1);
    both(q.K_w, A, Z, -o.S_xz1);
    f(q.K_w, Z, Z) += o.Dss_zz;
    both(q.K_w, Z, B, 0.5 * o.Dcs_yz.transpose());
    // K: the tension centre's cross term of the axial strain and the curvature along the chord.
    both(q.K, A, B, -o.E_xy);
    both(q.K, A, Z, -o.E_xz);
}

void add_offsets(const AssemblyContext& a, ModelMatrices& m)
{
    const FieldBlocks f(a.key);
    QuadraticForms forms = zero_forms(f.size());
    add_offset_forms(f, a.key, assemble_offsets(a.key, a.p), forms);
    m.forms.push_back(std::move(forms));
}

}  // namespace hubbeam
