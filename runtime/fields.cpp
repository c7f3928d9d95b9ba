// BeamFields: u_y, u_x1, u_x, EI u_y'' and ES u_x1' from the shape functions (docs/model.md section 5 outputs).
#include "fields.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace hubbeam {

BeamFields::BeamFields(const VariantKey& key, const Parameters& p)
    : axial_(key.axial_basis()), transverse_(key.transverse_basis()), L_(p.L), EI_(p.E * p.I), ES_(p.E * p.S),
      Phi_x_L_(axial_.size()), Phi_y_L_(transverse_.size()), H_L_(Eigen::MatrixXd::Zero(transverse_.size(), transverse_.size()))
{
    for (int i = 0; i < axial_.size(); ++i) Phi_x_L_(i) = axial_.at(i, 1.0).v;
    for (int i = 0; i < transverse_.size(); ++i) Phi_y_L_(i) = transverse_.at(i, 1.0).v;
    // H(L) = int_0^L Phi_y'^T Phi_y' dx = (1/L) int_0^1 (dPhi_y/dxi)^T (dPhi_y/dxi) dxi.
    const QuadratureRule rule = product_rule(transverse_, transverse_);
    Eigen::RowVectorXd slope(transverse_.size());
    for (std::size_t r = 0; r < rule.nodes.size(); ++r) {
        for (int i = 0; i < transverse_.size(); ++i) slope(i) = transverse_.at(i, rule.nodes[r]).d1;
        H_L_.noalias() += (rule.weights[r] / L_) * slope.transpose() * slope;
    }
}

Tip BeamFields::tip(const double* A, const double* B) const
{
    Tip t;
    if (A && axial_.size() > 0) t.ux1 = Phi_x_L_.dot(Eigen::Map<const Eigen::VectorXd>(A, axial_.size()));
    if (B) {
        const Eigen::Map<const Eigen::VectorXd> b(B, transverse_.size());
        t.uy = Phi_y_L_.dot(b);
        t.ux = t.ux1 - 0.5 * b.dot(H_L_.lazyProduct(b));  // u_x2(L) = -1/2 B^T H(L) B
    } else {
        t.ux = t.ux1;
    }
    return t;
}

double BeamFields::xi_of(double x) const
{
    if (!(x >= -1e-12 * L_ && x <= L_ * (1.0 + 1e-12)))
        throw std::out_of_range("beam abscissa x = " + std::to_string(x) + " outside [0, L]");
    return std::clamp(x / L_, 0.0, 1.0);
}

namespace {

/// d^deriv/dxi^deriv of sum_i phi_i(xi) c_i; zero when the coordinates are absent.
double combination(const FieldBasis& basis, const double* c, double xi, int deriv)
{
    double s = 0.0;
    if (c)
        for (int i = 0; i < basis.size(); ++i) {
            const Jet<double> phi = basis.at(i, xi);
            s += (deriv == 0 ? phi.v : deriv == 1 ? phi.d1 : phi.d2) * c[i];
        }
    return s;
}

}  // namespace

double BeamFields::uy(const double* B, double x) const { return combination(transverse_, B, xi_of(x), 0); }

double BeamFields::ux1(const double* A, double x) const { return combination(axial_, A, xi_of(x), 0); }

double BeamFields::bending_moment(const double* B, double x) const
{
    return EI_ * combination(transverse_, B, xi_of(x), 2) / (L_ * L_);  // d2/dx2 = (1/L^2) d2/dxi2
}

double BeamFields::axial_force(const double* A, double x) const
{
    return ES_ * combination(axial_, A, xi_of(x), 1) / L_;  // d/dx = (1/L) d/dxi
}

}  // namespace hubbeam
