// The questions the runtime asks the terms' registry (model/terms.hpp) against the hand-assembled model's forces, a
// path that reads no registry bit: a variant dissipates where its forces take power from the elastic rates, and its
// potential reads the hub angle where its forces change with the angle.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <hubbeam/make_model.hpp>
#include <memory>
#include <random>
#include <vector>

#include "terms.hpp"

using namespace hubbeam;

namespace {

/// Q at the drive u and the state (q, qd).
Eigen::VectorXd forces(const Model& model, const HubInput& u, const std::vector<double>& q,
                       const std::vector<double>& qd)
{
    Eigen::VectorXd Q(model.nq());
    model.forces(u, q.data(), qd.data(), Q.data());
    return Q;
}

}  // namespace

TEST_CASE("dissipates and the angle in U answer as the assembled model's forces do, term by term", "[terms][assembled]")
{
    std::mt19937 rng(32);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (const Drive drive : {Drive::prescribed, Drive::torque}) {
        for (const TermInfo& t : terms()) {
            if (t.params.empty()) continue;  // a profile: its values are a table (tests/generator/test_term_bits.cpp)
            // On a blade (flapwise and twist fields), where pitch, pre-twist and precone act too; every parameter of
            // the term nonzero.
            VariantKey key{
                .method = Method::fem, .nx = 2, .ny = 2, .nz = 2, .nt = 2, .order = Order::first, .drive = drive};
            t.set(key.extras, true);
            // A moving hub is chosen by the scene's [support] table, not set by values; a taper by its kind.
            if (!t.carried(key.extras)) {
                if ((t.energies & kinetic_reads_angle) != 0)
                    key.extras.hub = true;
                else
                    key.extras.taper = Taper::width;
            }
            REQUIRE(carried_terms(key.extras) == std::vector<const TermInfo*>{&t});
            Parameters p;
            p.I_flap = 4.0 * p.I;
            p.G = 0.4 * p.E;
            p.J_t = 2.0 * p.I;
            for (const Param k : t.params) value(p, k) = 0.2;
            INFO(t.name << ", " << key.name());
            // The tip body in the blade's axes has no assembled form: its generated model's forces answer for it.
            const std::unique_ptr<Model> model =
                make_model(key, p, key.extras.tip_body ? ModelSource::generated : ModelSource::assembled);
            const auto n = static_cast<std::size_t>(model->nq());
            const std::size_t e0 = static_cast<std::size_t>(model->coordinates().first_elastic());

            // At rest and without spin (a torque variant's hub rate 0 too), elastic rates qd_e: a conservative
            // model's forces change with them only through the spin, so the power qd . dQ is 0; Rayleigh damping's
            // is -qd^T C qd < 0.
            std::vector<double> q(n, 0.0), qd(n, 0.0);
            for (std::size_t i = e0; i < n; ++i) qd[i] = 1e-3 * unit(rng);
            const Eigen::Map<const Eigen::VectorXd> v(qd.data(), static_cast<Eigen::Index>(n));
            const double power = v.dot(forces(*model, {}, q, qd) - forces(*model, {}, q, std::vector<double>(n, 0.0)));
            std::vector<double> Mv(n * n);
            model->mass(HubInput{}, q.data(), Mv.data());
            const double kinetic_rate = v.dot(Eigen::Map<const Eigen::MatrixXd>(Mv.data(), n, n) * v);  // 2 T / s
            CHECK(dissipates(key) == (power < -1e-6 * kinetic_rate));

            // The angle turned by one radian: the prescribed input, or a torque variant's coordinate q[0]; spinning,
            // with the elastic rates above (a moving hub's angle enters its forces through the rates alone).
            HubInput spin, turned;
            std::vector<double> q_turned = q, qd_spin = qd;
            if (drive == Drive::prescribed)
                spin.theta_dot = 2.0;
            else
                qd_spin[0] = 2.0;
            turned = spin;
            if (drive == Drive::prescribed)
                turned.theta = 1.0;
            else
                q_turned[0] = 1.0;
            const Eigen::VectorXd Q0 = forces(*model, spin, q, qd_spin), Q1 = forces(*model, turned, q_turned, qd_spin);
            const bool reads_angle = (Q1 - Q0).norm() > 1e-12 * (Q0.norm() + Q1.norm());
            // The weight's U or a moving hub's T (which of the two: tests/generator/test_term_bits.cpp, on the
            // generator's energies).
            CHECK(kernels_read_angle(key) == reads_angle);
            CHECK(reads_driven_angle(key) == (reads_angle && drive == Drive::prescribed));
        }
    }
}
