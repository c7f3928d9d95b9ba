// A blade's mode shapes along the span from its natural modes, and their polynomial fits for ElastoDyn
// (mode_shapes.hpp).
#include <hubbeam/mode_shapes.hpp>

#include <cmath>
#include <complex>
#include <hubbeam/fields.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/shortest.hpp>
#include <stdexcept>

#include "analysis/modal_coordinates.hpp"
#include "linalg/factorizations.hpp"
#include "models/model_operations.hpp"

namespace hubbeam {

PolynomialFit fit_mode_shape(const std::vector<double>& xi, const std::vector<double>& phi)
{
    if (xi.size() != phi.size()) throw std::invalid_argument("fit_mode_shape: as many abscissae as values");
    if (xi.size() < 5) throw std::invalid_argument("fit_mode_shape: at least 5 samples for 5 coefficients");
    double tip = 0.0;
    bool at_tip = false;
    for (std::size_t i = 0; i < xi.size(); ++i) {
        if (!(xi[i] >= 0.0 && xi[i] <= 1.0)) throw std::invalid_argument("fit_mode_shape: abscissae x/L in [0, 1]");
        if (xi[i] == 1.0) tip = phi[i], at_tip = true;
    }
    if (!at_tip || !(tip != 0.0) || !std::isfinite(tip))
        throw std::invalid_argument("fit_mode_shape: a sample at the tip, x/L = 1, of a value other than 0");
    // c_6 = 1 - (c_2 + ... + c_5): sum_k c_k (xi^k - xi^6) = phi - xi^6 over c_2 .. c_5, unconstrained.
    const auto n = static_cast<Eigen::Index>(xi.size());
    Eigen::MatrixXd A(n, 4);
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const double x = xi[static_cast<std::size_t>(i)], x6 = std::pow(x, 6);
        for (int k = 2; k <= 5; ++k) A(i, k - 2) = std::pow(x, k) - x6;
        b(i) = phi[static_cast<std::size_t>(i)] / tip - x6;
    }
    const Eigen::VectorXd c = A.colPivHouseholderQr().solve(b);
    PolynomialFit fit;
    for (int k = 0; k < 4; ++k) fit.coefficients[static_cast<std::size_t>(k)] = c(k);
    fit.coefficients[4] = 1.0 - (c(0) + c(1) + c(2) + c(3));
    // A c - b is p(xi_i) - phi_i: the constraint is inside b's xi^6.
    fit.residual = std::sqrt((A * c - b).squaredNorm() / static_cast<double>(n));
    return fit;
}

namespace {

/// The shape along the span of the field of kind `kind` (flap: u_z; in-plane: u_y) of the coordinates' complex
/// deviation dq (nq), at the samples xi, divided by its value at the tip and its real part taken.
std::vector<double> span_shape(const Model& model, const Parameters& p, FieldKind kind,
                               const Eigen::VectorXcd& dq, const std::vector<double>& xi)
{
    const BeamFields fields(model.key(), p);
    const CoordinateField& field = *model.coordinates().find(kind);
    std::vector<double> re(static_cast<std::size_t>(field.count)), im(re.size());
    for (int k = 0; k < field.count; ++k) {
        re[static_cast<std::size_t>(k)] = dq(field.first + k).real();
        im[static_cast<std::size_t>(k)] = dq(field.first + k).imag();
    }
    const auto at = [&](double x) {
        return std::complex<double>(fields.field(kind, re.data(), x * p.L), fields.field(kind, im.data(), x * p.L));
    };
    const std::complex<double> tip = at(1.0);
    if (std::abs(tip) == 0.0) throw std::runtime_error("a mode shape with no deflection at the tip");
    std::vector<double> phi;
    for (const double x : xi) phi.push_back((at(x) / tip).real());
    return phi;
}

}  // namespace

ElastoDynShapes elastodyn_mode_shapes(const Model& model, const Parameters& p, double omega, Axial axial,
                                      double theta, int samples)
{
    if (model.coordinates().count(FieldKind::flap) == 0)
        throw std::invalid_argument("the blade's flap mode shapes need flapwise coordinates (discretization.nz > 0)");
    if (samples < 5) throw std::invalid_argument("at least 5 samples along the span");
    const SteadySpin s = steady_spin(model, omega, theta);
    const std::vector<NaturalMode> modes = natural_modes(model, s, axial);
    // A mode's shape is U v (v the coordinates' rates of R, M = U^T U over R): v = U^-1 shape, in the direction of
    // the eigenvector's positions (rates = lambda x).
    const std::vector<int> R = modal_coordinates(model, s, axial);
    const Eigen::MatrixXd M = mass_at(model, s.u, s.q);
    Eigen::MatrixXd MR(static_cast<Eigen::Index>(R.size()), static_cast<Eigen::Index>(R.size()));
    for (std::size_t i = 0; i < R.size(); ++i)
        for (std::size_t j = 0; j < R.size(); ++j)
            MR(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = M(R[i], R[j]);
    const Eigen::LLT<Eigen::MatrixXd> llt(MR);
    if (llt.info() != Eigen::Success)
        throw std::runtime_error("the mass matrix at the steady spin is not positive definite");
    const Eigen::MatrixXd U = llt.matrixU();
    std::vector<double> xi;
    for (int i = 0; i < samples; ++i) xi.push_back(static_cast<double>(i) / (samples - 1));
    const auto shape_of = [&](const std::string& kind, int order) {
        int seen = 0;
        for (const NaturalMode& m : modes) {
            if (m.kind != kind || !(m.rad_s > 0.0) || ++seen < order) continue;
            Eigen::VectorXcd v(m.shape.size()), dq = Eigen::VectorXcd::Zero(model.nq());
            v.real() = U.triangularView<Eigen::Upper>().solve(Eigen::VectorXd(m.shape.real()));
            v.imag() = U.triangularView<Eigen::Upper>().solve(Eigen::VectorXd(m.shape.imag()));
            for (std::size_t i = 0; i < R.size(); ++i) dq(R[i]) = v(static_cast<Eigen::Index>(i));
            BladeModeShape b{kind + " " + std::to_string(order), m.rad_s, xi,
                             span_shape(model, p, kind == "flap" ? FieldKind::flap : FieldKind::inplane, dq, xi), {}};
            b.fit = fit_mode_shape(b.xi, b.phi);
            return b;
        }
        throw std::runtime_error("no " + kind + " mode " + std::to_string(order) + " that oscillates at Omega = " +
                                 shortest(omega) + " rad/s (ElastoDyn's blade file needs flap 1, flap 2 and edge 1)");
    };
    return {omega, shape_of("flap", 1), shape_of("flap", 2), shape_of("edge", 1)};
}

std::string elastodyn_section(const ElastoDynShapes& shapes)
{
    std::string text = "---------------------- BLADE MODE SHAPES ---------------------------------\n";
    const struct {
        const char* name;
        const char* title;
        const BladeModeShape& shape;
    } parts[] = {{"BldFl1Sh", "Flap mode 1", shapes.flap1},
                 {"BldFl2Sh", "Flap mode 2", shapes.flap2},
                 {"BldEdgSh", "Edge mode 1", shapes.edge1}};
    for (const auto& part : parts)
        for (int k = 2; k <= 6; ++k) {
            // ElastoDyn's own layout: the value, then the name, then the comment, "Flap mode 1" on the first line.
            const std::string value = shortest(part.shape.fit.coefficients[static_cast<std::size_t>(k - 2)]);
            text += std::string(value.size() < 24 ? 24 - value.size() : 1, ' ') + value + "   " + part.name + "(" +
                    std::to_string(k) + ") - " + (k == 2 ? part.title : "           ") + ", coeff of x^" +
                    std::to_string(k) + "\n";
        }
    return text;
}

}  // namespace hubbeam
