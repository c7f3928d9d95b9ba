// The hand-assembled path: docs/model.md section 5's constant coefficient matrices by Gauss-Legendre
// quadrature over the shape functions, extended by section 11's tip body, taper, gravity and Rayleigh damping and by
// section 12's fields out of the plane, and the Model built from them (orders zero and first).
#pragma once

#include <Eigen/Dense>
#include <hubbeam/model.hpp>
#include <memory>

#include "models/assembled/out_of_plane_matrices.hpp"

namespace hubbeam {

/// docs/model.md section 5's coefficient matrices in SI units ('= d/dx). For a tapered variant m, ES and EI are the
/// root values times the section's profile, m(x) = m s(xi), ES(x) = ES s(xi), EI(x) = EI i(xi) (section 11), inside
/// every integral. The beam alone: the tip body is added by the model from the tip values below. A precone beta_c
/// (section 12) tilts the beam out of the plane, and a point's distance from the spin axis is then R(x) = a + x cb
/// (cb = cos beta_c; a + x without a precone), the arm of J_ob, S_x, S_y, G and S_ob.
struct BeamMatrices {
    double cb = 1.0, sb = 0.0;  // cos and sin of the precone (1 and 0 without one)
    double J_ob = 0.0;          // int m R^2 dx
    Eigen::RowVectorXd S_x;     // 1 x Nx, int m R Phi_x dx
    Eigen::RowVectorXd S_y;     // 1 x Ny, int m R Phi_y dx
    Eigen::MatrixXd M1;         // Nx x Nx, int m Phi_x^T Phi_x dx
    Eigen::MatrixXd M2;         // Ny x Ny, int m Phi_y^T Phi_y dx
    Eigen::MatrixXd M3;         // Nx x Ny, int m Phi_x^T Phi_y dx
    Eigen::MatrixXd K1;         // Nx x Nx, int ES Phi_x'^T Phi_x' dx
    Eigen::MatrixXd K2;         // Ny x Ny, int EI Phi_y''^T Phi_y'' dx (o.K_yy out of the plane)
    Eigen::MatrixXd C;          // Ny x Ny, int m H(x) dx = int (int_x^L m ds) Phi_y'^T Phi_y' dx
    Eigen::MatrixXd D;          // Ny x Ny, int m x H(x) dx = int (int_x^L m s ds) Phi_y'^T Phi_y' dx
    Eigen::MatrixXd G;          // Ny x Ny, int m R H(x) dx = a C + cb D: geometric stiffness per unit theta_dot^2

    // Section 11: the weight's integrals and the shape functions at the tip.
    double S_ob = 0.0;            // int m R dx, the beam's first moment about o
    double mass = 0.0;            // int m dx (a moving hub carries it)
    Eigen::RowVectorXd P_x;       // 1 x Nx, int m Phi_x dx
    Eigen::RowVectorXd P_y;       // 1 x Ny, int m Phi_y dx
    Eigen::RowVectorXd Phi_x_L;   // 1 x Nx, Phi_x(L)
    Eigen::RowVectorXd Phi_y_L;   // 1 x Ny, Phi_y(L)
    Eigen::RowVectorXd Phi_y1_L;  // 1 x Ny, Phi_y'(L) (1/m)
    Eigen::MatrixXd H_L;          // Ny x Ny, H(L) = int Phi_y'^T Phi_y' dx

    OutOfPlaneMatrices o;  // section 12.3's flapwise and twist matrices; empty for a planar variant
};

/// A drive value's column in dQ/du (ExactJacobian::force_derivatives).
inline Eigen::Index drive_column(DriveValue v)
{
    return static_cast<Eigen::Index>(index(v));
}

/// docs/model.md section 5's coefficient matrices of a variant (order and drive do not matter); symmetric ones are
/// exactly symmetric. Throws std::invalid_argument if the variant's DOF counts are invalid for its method.
BeamMatrices assemble_matrices(const VariantKey& key, const Parameters& p);

/// An assembled model's mass pattern: 'c' where M at q = 0 is nonzero and '0' where it is exactly zero (the shape
/// functions vanish outside their support), and under torque 'v' in the hub's row and column, which depend on q.
std::string assembled_mass_pattern(const Model& model);

/// docs/model.md sections 5, 11 and 12 assembled numerically; orders zero and first only (throws
/// std::invalid_argument). A planar variant gets section 5.2's block form, one that leaves the plane section 12.3's.
std::unique_ptr<Model> make_assembled_model(const VariantKey& key, const Parameters& p);

/// Section 12.3's form of the equations (T, U and D as quadratic forms in the elastic coordinates), for any variant
/// of orders zero and first: what make_assembled_model returns out of the plane; on a planar variant it must equal
/// the block form, which the tests check.
std::unique_ptr<Model> make_quadratic_form_model(const VariantKey& key, const Parameters& p);

}  // namespace hubbeam
