// Displacements and stress resultants of the beam from the generalized coordinates (docs/model.md section 5,
// "Useful outputs"): at the tip, and along the beam at any abscissa x.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include <hubbeam/model.hpp>

namespace hubbeam {

/// Field outputs of one variant. A and B point at the axial and transverse coordinates (A may be null when
/// nx = 0); x is in metres, 0 <= x <= L (std::out_of_range otherwise). Every beam field (axial, in-plane, flapwise,
/// twist) is read alike by field() and foreshortening(kind, ...); the named ones are the planar beam's.
class BeamFields {
public:
    /// The shape functions of key's variant, their tip values and H(L), for parameters p.
    BeamFields(const VariantKey& key, const Parameters& p);

    /// Tip displacements at coordinates A, B; order zero, the linear model, has no foreshortening: u_x = u_x1.
    Tip tip(const double* A, const double* B) const;

    /// The beam field of kind k (FieldKind::axial, inplane, flap or twist: u_x1, u_y, u_z or phi) at x from its
    /// coordinates c (null: a field without coordinates, 0), or its first or second derivative by x (derivative 1, 2).
    double field(FieldKind k, const double* c, double x, int derivative = 0) const;
    /// What a transverse field's slope (kind inplane: u_y; flap: u_z) shortens the beam by at each of the sorted
    /// abscissae xs, -1/2 int_0^x u'^2, by Gauss quadrature exact on the polynomial pieces (round-off for AMM).
    std::vector<double> foreshortening(FieldKind k, const double* c, const std::vector<double>& xs) const;

    /// Transverse deflection u_y(x) = Phi_y(x) B.
    double uy(const double* B, double x) const;
    /// Phi_x(L) (1 x Nx), Phi_y(L) (1 x Ny) and H(L) = int_0^L Phi_y'^T Phi_y' dx (Ny x Ny).
    const Eigen::RowVectorXd& Phi_x_L() const { return Phi_x_L_; }
    const Eigen::RowVectorXd& Phi_y_L() const { return Phi_y_L_; }
    const Eigen::MatrixXd& H_L() const { return H_L_; }

    /// Slope u_y'(x) and curvature u_y''(x).
    double slope(const double* B, double x) const;
    double curvature(const double* B, double x) const;
    /// The foreshortening u_x2(x) = -1/2 int_0^x u_y'^2 at each of the sorted abscissae xs (the in-plane field's).
    std::vector<double> foreshortening(const double* B, const std::vector<double>& xs) const;
    /// The axial displacement u_x(x) = u_x1(x) + u_x2(x) at each of the sorted abscissae xs; u_x1(x) alone for
    /// order zero, the linear model (docs/model.md section 3).
    std::vector<double> ux(const double* A, const double* B, const std::vector<double>& xs) const;
    /// The interior boundaries (m) between the transverse basis's polynomial pieces: FEM's element nodes, BSIM's
    /// knots; none for AMM and BIM.
    std::vector<double> piece_boundaries() const;

    /// Axial stretch displacement u_x1(x) = Phi_x(x) A, and its derivative u_x1'(x).
    double ux1(const double* A, double x) const;
    double ux1_slope(const double* A, double x) const;
    /// Bending moment EI(x) u_y''(x), with a tapered beam's own EI(x) (docs/model.md section 11).
    double bending_moment(const double* B, double x) const;
    /// Axial force ES(x) u_x1'(x).
    double axial_force(const double* A, double x) const;
    /// The section's area and second moment at x over the root's: 1 for a uniform beam; s = 1 + (tip_ratio - 1) x/L
    /// for the area of either taper, s for the second moment of a width taper and s^3 of a depth taper.
    double area_ratio(double x) const;
    double moment_ratio(double x) const;
    /// The flapwise second moment's ratio of a blade (docs/model.md section 12: the width is its thickness, the depth
    /// its chord): s^3 for a width taper, s for a depth taper.
    double flap_moment_ratio(double x) const;

private:
    double xi_of(double x) const;
    /// The basis of the field of kind k.
    const FieldBasis& basis(FieldKind k) const;

    FieldBasis axial_, transverse_, flap_, twist_;
    bool foreshortened_;  // u_x includes u_x2: every order but zero
    double L_, EI_, ES_;
    Taper taper_;
    double tip_ratio_;
    std::vector<double> stations_, profile_;  // a tabulated profile's x/L and values (docs/model.md section 11.2)
    Eigen::RowVectorXd Phi_x_L_, Phi_y_L_;
    Eigen::MatrixXd H_L_;
};

}  // namespace hubbeam
