// The hand-assembled path: docs/model.md section 5's constant coefficient matrices by Gauss-Legendre
// quadrature over the shape functions, and the Model built from them (orders zero and first).
#pragma once

#include <memory>

#include <Eigen/Dense>

#include "model.hpp"

namespace hubbeam {

/// docs/model.md section 5's coefficient matrices in SI units ('= d/dx).
struct BeamMatrices {
    double J_ob = 0.0;          // int m (a+x)^2 dx
    Eigen::RowVectorXd S_x;     // 1 x Nx, int m (a+x) Phi_x dx
    Eigen::RowVectorXd S_y;     // 1 x Ny, int m (a+x) Phi_y dx
    Eigen::MatrixXd M1;         // Nx x Nx, int m Phi_x^T Phi_x dx
    Eigen::MatrixXd M2;         // Ny x Ny, int m Phi_y^T Phi_y dx
    Eigen::MatrixXd M3;         // Nx x Ny, int m Phi_x^T Phi_y dx
    Eigen::MatrixXd K1;         // Nx x Nx, int ES Phi_x'^T Phi_x' dx
    Eigen::MatrixXd K2;         // Ny x Ny, int EI Phi_y''^T Phi_y'' dx
    Eigen::MatrixXd C;          // Ny x Ny, int m H(x) dx = int m (L-x) Phi_y'^T Phi_y' dx
    Eigen::MatrixXd D;          // Ny x Ny, int m x H(x) dx = int m (L^2-x^2)/2 Phi_y'^T Phi_y' dx
    Eigen::MatrixXd G;          // Ny x Ny, a C + D: geometric stiffness per unit theta_dot^2
};

/// docs/model.md section 5's coefficient matrices of a variant (order and drive do not matter); symmetric ones are
/// exactly symmetric. Throws std::invalid_argument if the variant's DOF counts are invalid for its method.
BeamMatrices assemble_matrices(const VariantKey& key, const Parameters& p);

/// docs/model.md section 5 assembled numerically; orders zero and first only (throws std::invalid_argument).
std::unique_ptr<Model> make_assembled_model(const VariantKey& key, const Parameters& p);

}  // namespace hubbeam
