// BeamFields: u_y, u_x1, u_x, EI u_y'' and ES u_x1' from the shape functions (docs/model.md section 5 outputs).
#include <hubbeam/fields.hpp>

#include "profile.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace hubbeam {

BeamFields::BeamFields(const VariantKey& key, const Parameters& p)
    : axial_(key.axial_basis()), transverse_(key.transverse_basis()), flap_(key.flap_basis()),
      twist_(key.twist_basis()), foreshortened_(key.order != Order::zero), L_(p.L),
      EI_(p.E * p.I), ES_(p.E * p.S), taper_(key.extras.taper), tip_ratio_(p.tip_ratio),
      stations_(p.stations), profile_(p.profile),
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
        if (foreshortened_) t.ux = t.ux1 - 0.5 * b.dot(H_L_.lazyProduct(b));  // u_x2(L) = -1/2 B^T H(L) B
        else t.ux = t.ux1;
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

const FieldBasis& BeamFields::basis(FieldKind k) const
{
    switch (k) {
        case FieldKind::axial:
            return axial_;
        case FieldKind::inplane:
            return transverse_;
        case FieldKind::flap:
            return flap_;
        case FieldKind::twist:
            return twist_;
        default:
            throw std::invalid_argument("BeamFields: the hub's coordinates are not a field along the beam");
    }
}

double BeamFields::field(FieldKind k, const double* c, double x, int derivative) const
{
    // d/dx = (1/L) d/dxi.
    return combination(basis(k), c, xi_of(x), derivative) / (derivative == 0 ? 1.0 : derivative == 1 ? L_ : L_ * L_);
}

double BeamFields::uy(const double* B, double x) const { return combination(transverse_, B, xi_of(x), 0); }

double BeamFields::ux1(const double* A, double x) const { return combination(axial_, A, xi_of(x), 0); }

double BeamFields::ux1_slope(const double* A, double x) const { return combination(axial_, A, xi_of(x), 1) / L_; }

double BeamFields::bending_moment(const double* B, double x) const
{
    // A profile's own EI(x), else the root's times the taper's ratio.
    const double EI = stations_.empty() ? EI_ * moment_ratio(x) : profile_value(stations_, profile_, ProfileValue::EI, xi_of(x));
    return EI * combination(transverse_, B, xi_of(x), 2) / (L_ * L_);  // d2/dx2 = (1/L^2) d2/dxi2
}

double BeamFields::axial_force(const double* A, double x) const
{
    const double ES = stations_.empty() ? ES_ * area_ratio(x) : profile_value(stations_, profile_, ProfileValue::ES, xi_of(x));
    return ES * combination(axial_, A, xi_of(x), 1) / L_;  // d/dx = (1/L) d/dxi
}

double BeamFields::slope(const double* B, double x) const
{
    return combination(transverse_, B, xi_of(x), 1) / L_;
}

double BeamFields::curvature(const double* B, double x) const
{
    return combination(transverse_, B, xi_of(x), 2) / (L_ * L_);
}

std::vector<double> BeamFields::ux(const double* A, const double* B, const std::vector<double>& xs) const
{
    std::vector<double> u = foreshortened_ ? foreshortening(B, xs) : std::vector<double>(xs.size(), 0.0);
    for (std::size_t i = 0; i < xs.size(); ++i) u[i] += ux1(A, xs[i]);
    return u;
}

std::vector<double> BeamFields::piece_boundaries() const
{
    std::vector<double> xs;
    if (!transverse_.polynomial()) return xs;
    const int pieces = transverse_.intervals();
    for (int k = 1; k < pieces; ++k) xs.push_back(L_ * k / pieces);
    return xs;
}

std::vector<double> BeamFields::foreshortening(const double* B, const std::vector<double>& xs) const
{
    return foreshortening(FieldKind::inplane, B, xs);
}

std::vector<double> BeamFields::foreshortening(FieldKind kind, const double* c, const std::vector<double>& xs) const
{
    const FieldBasis& field = basis(kind);
    // Cuts at the pieces' boundaries and at the abscissae, so that every panel is one smooth piece; a rule that
    // integrates the squared slope exactly (polynomials) or to round-off (AMM's panels, as for H(L)).
    std::vector<double> cuts{0.0, 1.0};
    const bool polynomial = field.polynomial();
    const int panels = polynomial ? field.intervals() : transcendental_panels(field.size());
    for (int k = 1; k < panels; ++k) cuts.push_back(static_cast<double>(k) / panels);
    for (double x : xs) cuts.push_back(xi_of(x));
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    const QuadratureRule g = gauss_legendre(polynomial ? field.degree() + 1 : transcendental_points);
    std::vector<double> out;
    double integral = 0.0;  // int_0^cut (du/dxi)^2 dxi
    std::size_t next = 0;
    for (std::size_t n = 0; n < cuts.size(); ++n) {
        if (n > 0) {
            const double lo = cuts[n - 1], width = cuts[n] - cuts[n - 1];
            for (std::size_t j = 0; j < g.nodes.size(); ++j) {
                const double d = combination(field, c, lo + width * g.nodes[j], 1);
                integral += width * g.weights[j] * d * d;
            }
        }
        for (; next < xs.size() && xi_of(xs[next]) <= cuts[n]; ++next) out.push_back(-0.5 * integral / L_);
    }
    return out;
}

double BeamFields::area_ratio(double x) const
{
    return taper_ == Taper::uniform ? 1.0 : 1.0 + (tip_ratio_ - 1.0) * xi_of(x);
}

double BeamFields::moment_ratio(double x) const
{
    const double s = area_ratio(x);
    return taper_ == Taper::depth ? s * s * s : s;
}

double BeamFields::flap_moment_ratio(double x) const
{
    const double s = area_ratio(x);
    return taper_ == Taper::width ? s * s * s : s;
}

}  // namespace hubbeam
