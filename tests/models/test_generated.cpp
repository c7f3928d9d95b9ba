// Generated kernels against the hand-assembled docs/model.md section 5 at random states (an independent path:
// symbolic differentiation of the energies vs. the transcribed matrix equations), for every variant in
// this build; and the mass matrix's symmetry and definiteness.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <random>

#include <hubbeam/make_model.hpp>
#include "models/generated_model.hpp"
#include "random_state.hpp"

using namespace hubbeam;
using test::random_state;
using test::State;

namespace {

/// max |a - b| / max |b|: relative error of a whole vector or matrix.
}  // namespace

TEST_CASE("generated kernels equal the hand-assembled equations", "[generated]")
{
    Parameters p;
    p.a = 0.35;  // nonzero, so that the hub-radius terms are exercised (the paper's cases have a = 0)
    std::mt19937 rng(2026);
    const std::vector<std::string> names = generated_variant_names();
    REQUIRE(!names.empty());
    for (const std::string& name : names) {
        const VariantKey key = VariantKey::parse(name);
        SECTION(key.name())
        {
            const auto gen = make_model(key, test::with_profile(key, p), ModelSource::generated);
            const auto asm_ = make_model(key, test::with_profile(key, p), ModelSource::assembled);
            REQUIRE(std::string(gen->source()) == "generated");
            REQUIRE(std::string(asm_->source()) == "assembled");
            CHECK(gen->mass_is_constant() == asm_->mass_is_constant());
            const int n = key.nq();
            for (int trial = 0; trial < 5; ++trial) {
                const State s = random_state(key, rng);
                Eigen::MatrixXd Mg(n, n), Ma(n, n);
                gen->mass(s.u, s.q.data(), Mg.data());
                asm_->mass(s.u, s.q.data(), Ma.data());
                CHECK(test::relative_error(Mg.reshaped(), Ma.reshaped()) < 1e-12);

                Eigen::VectorXd Qg(n), Qa(n);
                gen->forces(s.u, s.q.data(), s.qd.data(), Qg.data());
                asm_->forces(s.u, s.q.data(), s.qd.data(), Qa.data());
                CHECK(test::relative_error(Qg, Qa) < 1e-12);

                const Energy eg = gen->energy(s.u, s.q.data(), s.qd.data());
                const Energy ea = asm_->energy(s.u, s.q.data(), s.qd.data());
                const Eigen::Vector4d vg(eg.T2, eg.T1, eg.T0, eg.U), va(ea.T2, ea.T1, ea.T0, ea.U);
                CHECK(test::relative_error(vg, va) < 1e-12);
                // Tip displacements: generated shape values and H(1) against the runtime's shape functions and
                // quadrature (BeamFields).
                const Tip tg = gen->tip(s.q.data()), ta = asm_->tip(s.q.data());
                CHECK(test::relative_error(Eigen::Vector3d(tg.uy, tg.ux1, tg.ux), Eigen::Vector3d(ta.uy, ta.ux1, ta.ux)) < 1e-12);
                const double hg = gen->momentum(s.u, s.q.data(), s.qd.data());
                const double ha = asm_->momentum(s.u, s.q.data(), s.qd.data());
                CHECK(std::abs(hg - ha) <= 1e-12 * std::abs(ha));
            }
        }
    }
}

TEST_CASE("the mass matrix is symmetric positive definite", "[generated]")
{
    const Parameters p;
    std::mt19937 rng(7);
    for (const std::string& name : generated_variant_names()) {
        const VariantKey key = VariantKey::parse(name);
        const auto model = make_model(key, test::with_profile(key, p), ModelSource::generated);
        const int n = key.nq();
        for (int trial = 0; trial < 5; ++trial) {
            const State s = random_state(key, rng);
            Eigen::MatrixXd M(n, n);
            model->mass(s.u, s.q.data(), M.data());
            INFO(key.name());
            CHECK((M - M.transpose()).lpNorm<Eigen::Infinity>() == 0.0);
            CHECK(Eigen::LLT<Eigen::MatrixXd>(M).info() == Eigen::Success);
        }
    }
}
