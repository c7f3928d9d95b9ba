// The fields along the beam (fields.hpp) on a beam bent statically by the inertia of a hub acceleration alpha:
// a load -rho S alpha x per length (the beam lags), whose exact bending moment is M(x) = -rho S alpha (L^3/3 - L^2 x/2 + x^3/6).
// FEM's moment jumps at its element nodes, less as Ny grows; AMM's, BIM's and BSIM's is continuous (paper
// conclusion 3, docs/model.md section 7).
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include <hubbeam/fields.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include "models/model_operations.hpp"

using namespace hubbeam;

namespace {

constexpr double alpha = 0.5;  // rad/s^2

/// B of the beam in static equilibrium under the hub's angular acceleration alpha: K B = Q(theta_ddot = alpha).
std::vector<double> statically_bent(const Model& model)
{
    const int n = model.nq();
    HubInput u;
    u.theta_ddot = alpha;
    const std::vector<double> zero(static_cast<std::size_t>(n), 0.0);
    std::vector<double> Q(zero);
    model.forces(u, zero.data(), zero.data(), Q.data());
    const Eigen::MatrixXd K = -force_q_jacobian(model, u, zero, zero);
    const Eigen::VectorXd q = K.partialPivLu().solve(Eigen::Map<const Eigen::VectorXd>(Q.data(), n));
    return {q.data(), q.data() + n};
}

VariantKey bending_key(Method method, int ny) { return {.method = method, .nx = 0, .ny = ny, .extras = {}}; }

double exact_moment(const Parameters& p, double x)
{
    const double L = p.L;
    return -p.rho * p.S * alpha * (L * L * L / 3.0 - L * L * x / 2.0 + x * x * x / 6.0);
}

}  // namespace

TEST_CASE("FEM's bending moment jumps at its nodes, less as Ny grows - the other methods' is continuous", "[fields]")
{
    const Parameters p;
    const double root = std::abs(exact_moment(p, 0.0));
    const auto largest_jump = [&](Method method, int ny) {
        const auto model = make_model(bending_key(method, ny), p, ModelSource::assembled);
        const std::vector<double> B = statically_bent(*model);
        const BeamFields fields(model->key(), p);
        double jump = 0.0;
        // At FEM's nodes for this Ny, whatever the method: where the pieces of FEM meet.
        for (int k = 1; k < ny / 2; ++k) {
            const double x = p.L * k / (ny / 2);
            jump = std::max(jump, std::abs(fields.bending_moment(B.data(), x * (1 + 1e-9)) -
                                           fields.bending_moment(B.data(), x * (1 - 1e-9))));
        }
        return jump / root;
    };
    // FEM: a jump thousands of times round-off, which falls as the elements shrink, by 8 per halving here
    // (0.025, 0.0031, 0.00039 of the root moment at Ny 4, 8, 16): at least by 6 is asserted.
    const double fem4 = largest_jump(Method::fem, 4), fem8 = largest_jump(Method::fem, 8), fem16 = largest_jump(Method::fem, 16);
    INFO("FEM jumps / root moment: Ny 4 " << fem4 << ", Ny 8 " << fem8 << ", Ny 16 " << fem16);
    CHECK(fem4 > 1e-3);
    CHECK(fem8 < fem4 / 6.0);
    CHECK(fem16 < fem8 / 6.0);
    // The others are C2 (BSIM's cubic splines) or smooth (AMM, BIM): no jump beyond round-off.
    for (Method method : {Method::amm, Method::bim, Method::bsim}) {
        INFO(to_string(method));
        CHECK(largest_jump(method, 8) < 1e-6);
    }
}

TEST_CASE("the fields converge to the statically bent beam's exact moment and slope", "[fields]")
{
    const Parameters p;
    const double root = std::abs(exact_moment(p, 0.0));
    for (Method method : {Method::fem, Method::bim, Method::bsim}) {
        const auto model = make_model(bending_key(method, 16), p, ModelSource::assembled);
        const std::vector<double> B = statically_bent(*model);
        const BeamFields fields(model->key(), p);
        for (double x : {0.5, 2.0, 4.0 + 1e-6, 6.0}) {
            INFO(to_string(method) << " x = " << x);
            CHECK(fields.bending_moment(B.data(), x) == Approx(exact_moment(p, x)).margin(2e-2 * root));
        }
        // u_x2(x) = -1/2 int_0^x u_y'^2 by the recorder's quadrature, against a fine midpoint sum.
        const std::vector<double> xs{2.0, 5.0, 8.0};
        const std::vector<double> ux2 = fields.foreshortening(B.data(), xs);
        for (std::size_t i = 0; i < xs.size(); ++i) {
            double sum = 0.0;
            const int steps = 20000;
            for (int k = 0; k < steps; ++k) {
                const double s = fields.slope(B.data(), (k + 0.5) * xs[i] / steps);
                sum += s * s * xs[i] / steps;
            }
            CHECK(ux2[i] == Approx(-0.5 * sum).epsilon(1e-7));
        }
        // At the tip it is the model's own u_x2(L) = -1/2 B^T H(L) B.
        const Tip tip = model->tip(B.data());
        CHECK(ux2.back() == Approx(tip.ux - tip.ux1).epsilon(1e-12));
    }
}
