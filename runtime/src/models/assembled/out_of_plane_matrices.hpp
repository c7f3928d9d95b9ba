// The hand-assembled path's integrals of the fields that leave the plane (docs/model.md section 12.3): the flapwise
// field's mass, couplings and geometric stiffness, the bending stiffness about the chord turned by pitch and pre-twist,
// the twist field's torsional stiffness and the section's rotary inertia, by Gauss-Legendre quadrature over the shape
// functions. Written from the energies of section 12, not from the generator's expansion, so that it checks it.
#pragma once

#include <Eigen/Dense>
#include <hubbeam/model.hpp>
#include <string>
#include <vector>

namespace hubbeam {

/// Section 12.3's matrices of the beam alone (the tip body's point values are added by its twin, terms/tip.cpp), in
/// SI units ('= d/dx). R(x) = a + x cos(beta_c) is a point's distance from the spin axis (beta_c the precone, 0
/// without one); c = cos beta(x), s = sin beta(x) of the chord angle beta = pitch + twist x/L; C2 = cos 2 beta,
/// S2 = sin 2 beta. A profile's section (section 12.4) stands in the integrands as its stations' values turned by
/// pitch + their tabulated angle, each product linear between stations. A matrix of an absent field has no rows.
struct OutOfPlaneMatrices {
    Eigen::MatrixXd M_z;         // Nz x Nz, int m Phi_z^T Phi_z dx
    Eigen::MatrixXd M_xz;        // Nx x Nz, int m Phi_x^T Phi_z dx
    Eigen::MatrixXd M_zy;        // Nz x Ny, int m Phi_z^T Phi_y dx
    Eigen::RowVectorXd S_z;      // 1 x Nz, int m R Phi_z dx
    Eigen::RowVectorXd P_z;      // 1 x Nz, int m Phi_z dx
    Eigen::MatrixXd C_z;         // Nz x Nz, int m H_z(x) dx = int m (L - x) Phi_z'^T Phi_z' dx
    Eigen::MatrixXd G_z;         // Nz x Nz, int m R H_z(x) dx = a C_z + cos(beta_c) int m x H_z(x) dx
    double X_ob = 0.0;           // int m x dx, the beam's first moment about its root along its axis
    Eigen::MatrixXd K_yy;        // Ny x Ny, int (EI_e c^2 + EI_f s^2) Phi_y''^T Phi_y'' dx
    Eigen::MatrixXd K_zz;        // Nz x Nz, int (EI_e s^2 + EI_f c^2) Phi_z''^T Phi_z'' dx
    Eigen::MatrixXd K_yz;        // Ny x Nz, int (EI_e - EI_f) S2/2 Phi_y''^T Phi_z'' dx
    Eigen::MatrixXd K_t;         // Nt x Nt, int GJ Phi_t'^T Phi_t' dx
    Eigen::MatrixXd M_t;         // Nt x Nt, int j_p Phi_t^T Phi_t dx (the section's polar rotary inertia)
    Eigen::RowVectorXd S_t;      // 1 x Nt, int j_p Phi_t dx
    Eigen::RowVectorXd F_t;      // 1 x Nt, 1/2 int (j_c - j_n) S2 Phi_t dx (the propeller moment's drive)
    Eigen::MatrixXd K_p;         // Nt x Nt, int (j_c - j_n) C2 Phi_t^T Phi_t dx (the propeller moment's stiffness)
    double J_p = 0.0;            // int j_p dx
    double J_n = 0.0;            // int ((j_c + j_n)/2 + (j_n - j_c) C2/2) dx: the section's inertia about k at phi = 0
    Eigen::RowVectorXd Phi_z_L;  // 1 x Nz, Phi_z(L)
    Eigen::RowVectorXd Phi_z1_L;  // 1 x Nz, Phi_z'(L) (1/m)
    Eigen::MatrixXd H_z_L;       // Nz x Nz, H_z(L) = int Phi_z'^T Phi_z' dx
    Eigen::RowVectorXd Phi_t_L;  // 1 x Nt, Phi_t(L)
};

/// Section 12.3's integrals of a variant that leaves the plane, on a uniform or tapered section or a tabulated profile
/// (section 12.4).
OutOfPlaneMatrices assemble_out_of_plane(const VariantKey& key, const Parameters& p);

/// Sections 12.5 and 12.6's integrals of a blade's section offsets, without a precone (R = a + x), named by the
/// fields they join (x axial, y in-plane, z flapwise, t twist; ' = d/dx). The table's distributions, each linear
/// between stations from its values there: C = m d cos psi, S = m d sin psi (d = -cg_offset, psi = pitch + the
/// station's chord angle), the tail C^(x) = int_x^L C dt, D = m d^2 with D2c = D cos 2 psi and D2s = D sin 2 psi,
/// E_c = EA d_A cos psi and E_s = EA d_A sin psi (d_A = -tc_offset). Each matrix is one integral of the energies'
/// terms; quadratic_forms.cpp places them.
struct OffsetMatrices {
    Eigen::MatrixXd C_zt;      // Nz x Nt, int C Phi_z^T Phi_t dx
    Eigen::MatrixXd S_yt;      // Ny x Nt, int S Phi_y^T Phi_t dx
    Eigen::MatrixXd C_xy1;     // Nx x Ny, int C Phi_x^T Phi_y' dx
    Eigen::MatrixXd S_xz1;     // Nx x Nz, int S Phi_x^T Phi_z' dx
    Eigen::MatrixXd S_xt;      // Nx x Nt, int S Phi_x^T Phi_t dx
    Eigen::MatrixXd C_yy1;     // Ny x Ny, int C Phi_y^T Phi_y' dx
    Eigen::MatrixXd S_yz1;     // Ny x Nz, int S Phi_y^T Phi_z' dx
    Eigen::MatrixXd RC_tt;     // Nt x Nt, int R C Phi_t^T Phi_t dx
    Eigen::MatrixXd RC_yy;     // Ny x Ny, int R C Phi_y'^T Phi_y' dx
    Eigen::MatrixXd RS_yz;     // Ny x Nz, int R S Phi_y'^T Phi_z' dx
    Eigen::MatrixXd RS_ty;     // Nt x Ny, int R S Phi_t^T Phi_y' dx
    Eigen::MatrixXd RC_tz;     // Nt x Nz, int R C Phi_t^T Phi_z' dx
    Eigen::MatrixXd Ct_yy;     // Ny x Ny, int C^ Phi_y'^T Phi_y' dx
    Eigen::MatrixXd Ct_zz;     // Nz x Nz, int C^ Phi_z'^T Phi_z' dx
    Eigen::MatrixXd Dcc_yy;    // Ny x Ny, int D cos^2 psi Phi_y'^T Phi_y' dx
    Eigen::MatrixXd Dss_zz;    // Nz x Nz, int D sin^2 psi Phi_z'^T Phi_z' dx
    Eigen::MatrixXd Dcs_yz;    // Ny x Nz, int D cos psi sin psi Phi_y'^T Phi_z' dx
    Eigen::MatrixXd D_zt;      // Nz x Nt, int D Phi_z'^T Phi_t dx
    Eigen::MatrixXd Dcs_ty;    // Nt x Ny, int D cos psi sin psi Phi_t^T Phi_y' dx
    Eigen::MatrixXd D2c_tz;    // Nt x Nz, int D2c Phi_t^T Phi_z' dx
    Eigen::MatrixXd E_xy;      // Nx x Ny, int E_c Phi_x'^T Phi_y'' dx
    Eigen::MatrixXd E_xz;      // Nx x Nz, int E_s Phi_x'^T Phi_z'' dx
    Eigen::RowVectorXd C_x;    // 1 x Nx, int C Phi_x dx
    Eigen::RowVectorXd RS_t;   // 1 x Nt, int R S Phi_t dx
    Eigen::RowVectorXd Dcc_y;  // 1 x Ny, int D cos^2 psi Phi_y' dx
    Eigen::RowVectorXd Dcs_z;  // 1 x Nz, int D cos psi sin psi Phi_z' dx
    Eigen::RowVectorXd C_y;    // 1 x Ny, int C Phi_y dx
    Eigen::RowVectorXd RC_y1;  // 1 x Ny, int R C Phi_y' dx
    Eigen::RowVectorXd RS_z1;  // 1 x Nz, int R S Phi_z' dx
};

/// Sections 12.5 and 12.6's integrals of a tabulated blade's offsets (Parameters::offsets), by the same quadrature.
OffsetMatrices assemble_offsets(const VariantKey& key, const Parameters& p);

/// OffsetMatrices' distributions at a rule's nodes: C, S, D, D2c, D2s, E_c, E_s, and the tail C^ (SI).
struct OffsetValues {
    std::vector<double> C, S, D, D2c, D2s, Ec, Es, Ct;
};

/// OffsetMatrices of the distributions v at rule's nodes (x/L), on a blade of length L at the radius a: each matrix the
/// rule's sum of its integrand. A rule of one node at the tip, of weight 1/L, gives the integrands' values there.
OffsetMatrices offset_matrices(const VariantKey& key, const QuadratureRule& rule, double L, double a,
                               const OffsetValues& v);

}  // namespace hubbeam
