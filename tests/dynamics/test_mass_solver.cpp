// The linear algebra chosen from a model's structure (runtime/src/dynamics/mass_solver.*, the folded forces of
// runtime/src/dynamics/integrate.cpp) against a plain dense solve, and the generated mass pattern against M's values.
#include <catch2/catch.hpp>

#include <malloc.h>

#include <Eigen/Dense>
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include <hubbeam/make_model.hpp>
#include "dynamics/integrate.hpp"
#include "dynamics/mass_solver.hpp"
#include "models/assembled/assembled.hpp"
#include "models/generated_model.hpp"
#include "random_state.hpp"

using namespace hubbeam;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

/// q and qd of a random state (random_state.hpp).
void random_state(const VariantKey& key, std::mt19937& rng, VectorXd& q, VectorXd& qd)
{
    const test::State s = test::random_state(key, rng);
    q = s.q;
    qd = s.qd;
}

MatrixXd mass_of(const Model& model, const HubInput& u, const VectorXd& q)
{
    MatrixXd M(model.nq(), model.nq());
    model.mass(u, q.data(), M.data());  // row-major and symmetric: the same matrix read column-major
    return M;
}

/// max |a - b| / max |b|.
/// The solver's M^-1 B against a dense LU solve, at several states (the solver re-prepared at each).
void check_solver(const Model& model, std::mt19937& rng)
{
    const auto solver = MassSolver::make(model);
    INFO(model.key().name() << " (" << model.source() << "): " << solver->describe());
    const HubInput u{0.4, 1.3, -0.6};
    for (int trial = 0; trial < 4; ++trial) {
        VectorXd q, qd;
        random_state(model.key(), rng, q, qd);
        const MatrixXd M = mass_of(model, u, q);
        const MatrixXd B = MatrixXd::Random(model.nq(), 3);
        MatrixXd X = B;
        REQUIRE(solver->prepare(u, q.data()));
        solver->solve(X.data(), 3);
        CHECK(test::relative_error(X, M.partialPivLu().solve(B)) < 1e-11);
        MatrixXd x = B.col(0);  // the right-hand side's path: prepared and solved in one call (two solves as a pair)
        REQUIRE(solver->prepare_and_solve(u, q.data(), x.data()));
        CHECK(test::relative_error(x, M.partialPivLu().solve(B.col(0))) < 1e-11);
    }
}

}  // namespace

TEST_CASE("every generated mass pattern tells zero, constant and varying entries apart", "[structure]")
{
    std::mt19937 rng(5);
    // The extra terms' values at work: a tip body fills entries the beam's integrals leave zero (AMM's orthogonal
    // modes), a taper one a uniform mesh cancels (FEM's deflection-slope coupling at an inner node), and the pattern
    // marks both constant; a variant without these terms does not read them.
    Parameters p;
    p.m_tip = 0.5;
    p.J_tip = 0.1;
    p.tip_ratio = 0.6;
    for (const std::string& name : generated_variant_names()) {
        const VariantKey key = VariantKey::parse(name);
        const auto model = make_model(key, test::with_profile(key, p), ModelSource::generated);
        const std::string pattern = model->mass_pattern();
        INFO(name << " " << pattern);
        REQUIRE(pattern.size() == static_cast<std::size_t>(key.nq() * key.nq()));
        VectorXd q1, q2, qd;
        random_state(key, rng, q1, qd);
        random_state(key, rng, q2, qd);
        const MatrixXd M1 = mass_of(*model, {}, q1), M2 = mass_of(*model, {}, q2);
        bool some_varying_entry_changed = pattern.find('v') == std::string::npos;
        for (int i = 0; i < key.nq(); ++i)
            for (int j = 0; j < key.nq(); ++j) {
                const char kind = pattern[static_cast<std::size_t>(i * key.nq() + j)];
                CHECK(kind == pattern[static_cast<std::size_t>(j * key.nq() + i)]);  // M is symmetric
                if (kind == '0') CHECK((M1(i, j) == 0.0 && M2(i, j) == 0.0));
                if (kind == 'c') CHECK((M1(i, j) == M2(i, j) && M1(i, j) != 0.0));
                if (kind == 'v') some_varying_entry_changed = some_varying_entry_changed || M1(i, j) != M2(i, j);
            }
        CHECK(some_varying_entry_changed);
        CHECK(model->mass_is_constant() == (key.drive == Drive::prescribed));
    }
}

TEST_CASE("mass solvers equal a dense solve, for every structure they are chosen for", "[structure]")
{
    std::mt19937 rng(9);
    Parameters p;
    p.a = 0.35;
    SECTION("every generated variant (constant, and Schur complement under torque)")
    {
        for (const std::string& name : generated_variant_names())
            check_solver(*make_model(VariantKey::parse(name), test::with_profile(VariantKey::parse(name), p), ModelSource::generated), rng);
    }
    SECTION("banded for large FEM and BSIM, prescribed and under torque")
    {
        for (Method method : {Method::fem, Method::bsim})
            for (Drive drive : {Drive::prescribed, Drive::torque}) {
                VariantKey key;
                key.method = method;
                key.nx = 8;
                key.ny = 32;
                key.drive = drive;
                const auto model = make_assembled_model(key, p);
                CHECK(MassSolver::make(*model)->describe().find("banded") != std::string::npos);
                check_solver(*model, rng);
            }
    }
    SECTION("a Schur complement over a block in no narrow band, its couplings varying")
    {
        // Bernstein's full blocks (bandwidth 5 at Ny = 6): the Cholesky factor's general loops, solve_pair's among them.
        const auto model =
            make_assembled_model({.method = Method::bim, .nx = 4, .ny = 6, .drive = Drive::torque, .extras = {}}, p);
        const std::string how = MassSolver::make(*model)->describe();
        INFO(how);
        CHECK(how.find("Schur") != std::string::npos);
        CHECK(how.find("bandwidth 3") == std::string::npos);
        CHECK(how.find("bandwidth 4") == std::string::npos);
        check_solver(*model, rng);
    }
    SECTION("dense when nothing else applies")
    {
        VariantKey key;
        key.method = Method::amm;
        key.nx = 2;
        key.ny = 3;
        key.drive = Drive::torque;
        const auto model = make_assembled_model(key, p);
        check_solver(*model, rng);
    }
}

TEST_CASE("folded forces: one multiply-add pass gives M^-1 Q", "[structure]")
{
    // A constant M with Q = F m is folded into W = M^-1 F once per run (integrate.cpp): the small prescribed
    // variants take that path; the large FEM ones (W would be dense) a banded solve, the torque ones the Schur
    // complement, folded into F where that costs less than the mass solver's solves (always without axial
    // coordinates at these sizes, where only the hub's entry of M varies). Every path gives M^-1 Q.
    std::mt19937 rng(13);
    Parameters p;
    p.a = 0.35;
    const Motion motion{Motion::Kind::spin_up, 4.0, 15.0, 0.0, 10.0};
    const Motion torque{Motion::Kind::torque, 0.0, 15.0, 10.0, 10.0};
    for (const std::string& name : generated_variant_names()) {
        const VariantKey key = VariantKey::parse(name);
        const auto model = make_model(key, test::with_profile(key, p), ModelSource::generated);
        FirstOrderSystem system(*model, key.drive == Drive::prescribed ? motion : torque);
        INFO(name << ": " << system.linear_algebra());
        const std::string algebra = system.linear_algebra();
        if (key.drive == Drive::torque) CHECK(algebra.find("Schur") != std::string::npos);
        if (key.drive == Drive::torque && key.nx == 0 && key.nq() <= 8) CHECK(algebra.find("folded") != std::string::npos);
        else if (key.nq() <= 8) CHECK(algebra.find("folded") != std::string::npos);
        else if (key.nq() >= 32 && key.drive == Drive::prescribed) CHECK(algebra.find("banded") != std::string::npos);
        for (const double t : {3.7, 12.2}) {
            VectorXd q, qd;
            random_state(key, rng, q, qd);
            VectorXd y(2 * key.nq()), f(2 * key.nq());
            y << q, qd;
            REQUIRE(system.rhs(t, y.data(), f.data()) == 0);
            const HubInput u = (key.drive == Drive::prescribed ? motion : torque).at(t);
            VectorXd Q(key.nq());
            model->forces(u, q.data(), qd.data(), Q.data());
            const VectorXd qdd = mass_of(*model, u, q).partialPivLu().solve(Q);
            CHECK(f.head(key.nq()) == qd);
            CHECK(test::relative_error(f.tail(key.nq()), qdd) < 1e-11);
        }
    }
}

namespace {

/// A constant tridiagonal mass matrix, -1 or +2 on the diagonal (indefinite or definite, switched by the test),
/// 0.5 beside it: large enough to be solved banded. Only the mass matters here.
class Tridiagonal final : public Model {
public:
    explicit Tridiagonal(const VariantKey& key) : Model(key) {}
    double diagonal = -1.0;
    const char* source() const override { return "test"; }
    bool mass_is_constant() const override { return true; }
    std::string mass_pattern() const override
    {
        std::string p(static_cast<std::size_t>(nq() * nq()), '0');
        for (int i = 0; i < nq(); ++i)
            for (int j = std::max(0, i - 1); j <= std::min(nq() - 1, i + 1); ++j) p[static_cast<std::size_t>(i * nq() + j)] = 'c';
        return p;
    }
    void mass(const HubInput&, const double*, double* M) const override
    {
        const int n = nq();
        std::fill(M, M + n * n, 0.0);
        for (int i = 0; i < n; ++i) {
            M[i * n + i] = diagonal;
            if (i + 1 < n) M[i * n + i + 1] = M[(i + 1) * n + i] = 0.5;
        }
    }
    void forces(const HubInput&, const double*, const double*, double* Q) const override
    {
        std::fill(Q, Q + nq(), 0.0);
    }
    Energy energy(const HubInput&, const double*, const double*) const override { return {}; }
    double momentum(const HubInput&, const double*, const double*) const override { return 0.0; }
    Tip tip(const double*) const override { return {}; }
};

}  // namespace

TEST_CASE("a banded factorization retried after failing holds one factor, not one per attempt", "[structure]")
{
    VariantKey key;
    key.method = Method::fem;
    key.nx = 0;
    key.ny = 40;
    Tridiagonal model(key);
    const auto solver = MassSolver::make(model);
    REQUIRE(solver->describe().find("banded") != std::string::npos);
    // An indefinite M fails at every prepare() and is factored again at the next: the heap in use must not grow
    // with the attempts (a band of 40 x 2 doubles left behind each time would be some 4 MB after 5000).
    const std::vector<double> q(static_cast<std::size_t>(model.nq()), 0.0);
    REQUIRE_FALSE(solver->prepare({}, q.data()));
    const std::size_t before = mallinfo2().uordblks;
    for (int attempt = 0; attempt < 5000; ++attempt) REQUIRE_FALSE(solver->prepare({}, q.data()));
    const std::size_t after = mallinfo2().uordblks;
    CHECK(after < before + 64 * 1024);
    // The band reused for a definite M solves it (nothing of the failed attempts left in it).
    model.diagonal = 2.0;
    REQUIRE(solver->prepare({}, q.data()));
    const MatrixXd M = mass_of(model, {}, VectorXd::Zero(model.nq()));
    const MatrixXd B = MatrixXd::Random(model.nq(), 2);
    MatrixXd X = B;
    solver->solve(X.data(), 2);
    CHECK(test::relative_error(X, M.llt().solve(B)) < 1e-13);
}
