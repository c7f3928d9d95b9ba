// The generated derivatives of M, Q, F and the tip by each physical parameter (ParameterDerivatives, from the
// generated dc/dp) against central differences of models built at perturbed parameters, for every generated variant.
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <cmath>
#include <random>

#include <hubbeam/make_model.hpp>
#include "models/generated_model.hpp"
#include "random_state.hpp"

using namespace hubbeam;

namespace {

/// p with parameter k moved by h.
Parameters moved(Parameters p, Param k, double h)
{
    value(p, k) += h;
    return p;
}

/// Everything ParameterDerivatives gives at one state, or the same quantities of a model (to difference them).
struct Values {
    Eigen::MatrixXd M, F;
    Eigen::VectorXd Q, tip;
};
Values values(const Model& model, const HubInput& u, const Eigen::VectorXd& q, const Eigen::VectorXd& qd)
{
    const int n = model.nq();
    Values v{Eigen::MatrixXd(n, n), Eigen::MatrixXd(), Eigen::VectorXd(n), Eigen::VectorXd(3)};
    model.mass(u, q.data(), v.M.data());
    model.forces(u, q.data(), qd.data(), v.Q.data());
    const Tip t = model.tip(q.data());
    v.tip << t.uy, t.ux1, t.ux;
    if (const TermForces* f = model.term_forces()) {
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> F(n, f->term_count());
        f->term_matrix(F.data());
        v.F = F;
    }
    return v;
}
Values derivatives(const Model& model, Param k, const HubInput& u, const Eigen::VectorXd& q, const Eigen::VectorXd& qd)
{
    const ParameterDerivatives& d = *model.parameter_derivatives();
    const int n = model.nq();
    Values v{Eigen::MatrixXd(n, n), Eigen::MatrixXd(), Eigen::VectorXd(n), Eigen::VectorXd(3)};
    d.mass_p(k, u, q.data(), v.M.data());  // symmetric: row- or column-major alike
    d.forces_p(k, u, q.data(), qd.data(), v.Q.data());
    const Tip t = d.tip_p(k, q.data());
    v.tip << t.uy, t.ux1, t.ux;
    if (const TermForces* f = model.term_forces()) {
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> F(n, f->term_count());
        REQUIRE(d.term_matrix_p(k, F.data()));
        v.F = F;
    }
    return v;
}

/// |a - b| against the size of b (or of the value itself where the derivative is zero: scale, p_k dX/dp_k).
double error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double scale)
{
    if (a.size() == 0 && b.size() == 0) return 0.0;
    return (a - b).lpNorm<Eigen::Infinity>() / std::max({b.lpNorm<Eigen::Infinity>(), scale, 1e-300});
}

}  // namespace

TEST_CASE("generated parameter derivatives equal central differences of models at perturbed parameters",
          "[parameters]")
{
    std::vector<std::string> names = generated_variant_names();
    REQUIRE(!names.empty());
    // and order full below Ny = 8 (polynomial kernels), compiled on demand
    for (const char* full : {"amm_nx2_ny3_prescribed_full", "fem_nx2_ny4_torque_full"}) names.emplace_back(full);
    std::mt19937 rng(61);
    for (const std::string& name : names) {
        const VariantKey key = VariantKey::parse(name);
        SECTION(name)
        {
            const Parameters p = test::with_profile(key, test::with_every_term());
            const auto model = make_model(key, p, ModelSource::generated);
            REQUIRE(model->parameter_derivatives() != nullptr);
            const std::vector<double> packed = p.packed();
            const test::State s = test::random_state(key, rng);
            HubInput u{2.5, 3.0, 0.7, 0.4};
            const std::size_t read = key.params_read();
            for (std::size_t j = 0; j < param_count; ++j) {
                const Param k = static_cast<Param>(j);
                INFO("parameter " << param_names[j]);
                const Values exact = derivatives(*model, k, u, s.q, s.qd);
                if (j >= read) {  // a parameter the variant does not read: exactly zero
                    CHECK(exact.M.lpNorm<Eigen::Infinity>() == 0.0);
                    CHECK(exact.Q.lpNorm<Eigen::Infinity>() == 0.0);
                    continue;
                }
                // Central differences with Richardson's extrapolation: the error of the oracle ~ h^4, round-off
                // ~ eps / h (h 1e-3 of the value).
                const double h = 1e-3 * packed[j];
                const auto at = [&](double step) {
                    return values(*make_model(key, moved(p, k, step), ModelSource::generated), u, s.q, s.qd);
                };
                const Values p1 = at(h), m1 = at(-h), p2 = at(2 * h), m2 = at(-2 * h), base = at(0.0);
                const auto d = [&](Eigen::MatrixXd Values::*x) {
                    return ((8.0 * (p1.*x - m1.*x) - (p2.*x - m2.*x)) / (12.0 * h)).eval();
                };
                const auto dv = [&](Eigen::VectorXd Values::*x) {
                    return Eigen::MatrixXd((8.0 * (p1.*x - m1.*x) - (p2.*x - m2.*x)) / (12.0 * h));
                };
                const double pk = packed[j];
                CHECK(error(exact.M, d(&Values::M), base.M.lpNorm<Eigen::Infinity>() / pk * 1e-3) < 1e-7);
                CHECK(error(exact.Q, dv(&Values::Q), base.Q.lpNorm<Eigen::Infinity>() / pk * 1e-3) < 1e-7);
                CHECK(error(exact.tip, dv(&Values::tip), base.tip.lpNorm<Eigen::Infinity>() / pk * 1e-3) < 1e-7);
                if (base.F.size() > 0)
                    CHECK(error(exact.F, d(&Values::F), base.F.lpNorm<Eigen::Infinity>() / pk * 1e-3) < 1e-7);
            }
            // All the parameters at once (the sensitivities' call), last first: each one's mass_p and forces_p.
            std::vector<Param> ks;
            for (std::size_t j = read; j-- > 0;) ks.push_back(static_cast<Param>(j));
            const int n = model->nq(), count = static_cast<int>(ks.size());
            std::vector<double> dMs(static_cast<std::size_t>(count * n * n)), dQs(static_cast<std::size_t>(count * n));
            model->parameter_derivatives()->derivatives_p(ks.data(), count, n, u, s.q.data(), s.qd.data(),
                                                          dMs.data(), dQs.data());
            for (int j = 0; j < count; ++j) {
                INFO("parameter " << param_names[index(ks[static_cast<std::size_t>(j)])] << " of several");
                const Values one = derivatives(*model, ks[static_cast<std::size_t>(j)], u, s.q, s.qd);
                CHECK(Eigen::Map<const Eigen::MatrixXd>(dMs.data() + j * n * n, n, n) == one.M);
                CHECK(Eigen::Map<const Eigen::VectorXd>(dQs.data() + j * n, n) == one.Q);
            }
        }
    }
}

TEST_CASE("order full's quadrature sums have no generated parameter derivatives", "[parameters]")
{
    // Their hand-written sums multiply coefficients, so the affine rule does not hold: a caller differences.
    const VariantKey key = VariantKey::parse("amm_nx2_ny8_prescribed_full");
    CHECK(make_model(key, Parameters{}, ModelSource::generated)->parameter_derivatives() == nullptr);
}
