// Displacements and stress resultants of the beam from the generalized coordinates (docs/model.md section 5,
// "Useful outputs"): at the tip, and along the beam at any abscissa x.
#pragma once

#include <Eigen/Dense>

#include "model.hpp"

namespace hubbeam {

/// Field outputs of one variant. A and B point at the axial and transverse coordinates (A may be null when
/// nx = 0); x is in metres, 0 <= x <= L (std::out_of_range otherwise).
class BeamFields {
public:
    /// The shape functions of key's variant, their tip values and H(L), for parameters p.
    BeamFields(const VariantKey& key, const Parameters& p);

    /// Tip displacements at coordinates A, B.
    Tip tip(const double* A, const double* B) const;

    /// Transverse deflection u_y(x) = Phi_y(x) B.
    double uy(const double* B, double x) const;
    /// Phi_x(L) (1 x Nx), Phi_y(L) (1 x Ny) and H(L) = int_0^L Phi_y'^T Phi_y' dx (Ny x Ny).
    const Eigen::RowVectorXd& Phi_x_L() const { return Phi_x_L_; }
    const Eigen::RowVectorXd& Phi_y_L() const { return Phi_y_L_; }
    const Eigen::MatrixXd& H_L() const { return H_L_; }

    /// Axial stretch displacement u_x1(x) = Phi_x(x) A.
    double ux1(const double* A, double x) const;
    /// Bending moment EI u_y''(x).
    double bending_moment(const double* B, double x) const;
    /// Axial force ES u_x1'(x).
    double axial_force(const double* A, double x) const;

private:
    double xi_of(double x) const;

    FieldBasis axial_, transverse_;
    double L_, EI_, ES_;
    Eigen::RowVectorXd Phi_x_L_, Phi_y_L_;
    Eigen::MatrixXd H_L_;
};

}  // namespace hubbeam
