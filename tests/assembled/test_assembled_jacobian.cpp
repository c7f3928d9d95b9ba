// The hand-assembled model's exact Jacobian (runtime/src/models/assembled/assembled.cpp, assembled_forms.cpp: the derivatives of
// docs/model.md sections 5.2 and 12.3's blocks, written by hand) on two independent paths: against the generated
// derivative kernels (the generator's symbolic differentiation) at random states, and against fourth-order central
// differences of the assembled forces and mass. Then what it is for: the modes of a stiff real blade by either source.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/on_demand.hpp>
#include <hubbeam/scene.hpp>
#include <random>
#include <string>
#include <vector>

#include "random_state.hpp"
#include "temp_folder.hpp"

using namespace hubbeam;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

namespace {

/// What ExactJacobian gives at a state: dQ/dq, dQ/dqd, dQ/du and (dM/dq) v.
struct Derivatives {
    MatrixXd q, qd, u, Mv;
};

Derivatives derivatives_of(const Model& model, const test::State& s, const VectorXd& v)
{
    const int n = model.nq();
    RowMajorMatrix q(n, n), qd(n, n), u(n, static_cast<Eigen::Index>(drive_value_count)), Mv(n, n);
    model.jacobian()->force_derivatives(s.u, s.q.data(), s.qd.data(), q.data(), qd.data(), u.data());
    model.jacobian()->mass_q_product(s.u, s.q.data(), v.data(), Mv.data());
    return {q, qd, u, Mv};
}

/// a against b relative to b's largest entry; where b is zero, a must be zero too (both exactly).
double relative(const MatrixXd& a, const MatrixXd& b)
{
    return b.lpNorm<Eigen::Infinity>() == 0.0 ? a.lpNorm<Eigen::Infinity>() : test::relative_error(a, b);
}

using test::key_of;

/// Every built-in variant (in the plane: the four methods, both drives, orders zero and first, a tip body, gravity,
/// damping, either taper, a profile), then out of the plane every method with every term under both drives and both
/// orders, a profile's tabulated chord angles, a blade's section offsets, the tip body, and a moving hub in and out of
/// the plane: the variants that test_out_of_plane_assembled.cpp and test_moving_hub.cpp compile too, so that one cache
/// serves all three.
std::vector<VariantKey> variants()
{
    std::vector<VariantKey> keys;
    for (const std::string& name : generated_variant_names()) keys.push_back(VariantKey::parse(name));
    const Extras all{.tip = true, .gravity = true, .damping = true, .pitch = true, .twist = true, .cone = true};
    keys.push_back(key_of(Method::amm, 2, 4, 2, Drive::torque, Order::first, all));
    keys.push_back(key_of(Method::fem, 0, 4, 2, Drive::prescribed, Order::first, all));
    keys.push_back(key_of(Method::bim, 0, 4, 2, Drive::torque, Order::zero, all));
    keys.push_back(key_of(Method::bsim, 3, 4, 3, Drive::prescribed, Order::zero, all, SplineBasis::open));
    keys.push_back(key_of(Method::amm, 2, 2, 2, Drive::prescribed, Order::first, {.gravity = true}));
    keys.push_back(key_of(Method::fem, 2, 2, 0, Drive::prescribed, Order::first, {.cone = true}));
    Extras blade = all;
    blade.twist = false;
    blade.tabulated = true;
    keys.push_back(key_of(Method::fem, 2, 4, 2, Drive::torque, Order::first, blade));
    keys.push_back(key_of(Method::bsim, 3, 4, 3, Drive::torque, Order::first, blade));
    // A blade's section offsets, as test_out_of_plane_assembled.cpp compiles them.
    const Extras offsets{.tip = true, .damping = true, .pitch = true, .tabulated = true, .offsets = true};
    keys.push_back(key_of(Method::fem, 2, 4, 2, Drive::torque, Order::first, offsets));
    keys.push_back(key_of(Method::bim, 2, 4, 2, Drive::prescribed, Order::zero, {.tabulated = true, .offsets = true}));
    // The tip body in the blade's axes, likewise.
    keys.push_back(
        key_of(Method::fem, 2, 4, 2, Drive::torque, Order::first,
               {.tip = true, .gravity = true, .damping = true, .pitch = true, .twist = true, .tip_body = true}));
    for (const char* hub :
         {"fem_nx2_ny4_torque_first_hub", "bsim_nx3_ny4_prescribed_first_tip_gravity_damped_depth_hub",
          "amm_nx0_ny3_nz3_nt2_torque_first_tip_gravity_damped_pitched_twisted_coned_hub",
          "fem_nx2_ny4_nz4_nt2_prescribed_first_tip_gravity_damped_pitched_coned_hub"})
        keys.push_back(VariantKey::parse(hub));
    return keys;
}

/// Q, M v and the Jacobian's columns by fourth-order central differences, (8 (f(h) - f(-h)) - (f(2h) - f(-2h))) / 12h,
/// exact for a polynomial of degree 4 and less. Q and M are polynomials of degree 2 at most in q_e, in qd and in the
/// drive, each apart (docs/model.md sections 5.2, 12.3 and 13.1): h = 1 there, which leaves round-off alone, eps |Q|.
/// In the hub angle they hold sin and cos: h = 1e-3 leaves h^4/30 of their fifth derivative, 3e-14.
Derivatives differences_of(const Model& model, const test::State& s, const VectorXd& v)
{
    const int n = model.nq();
    const auto forces = [&](const test::State& at) {
        VectorXd Q(n);
        model.forces(at.u, at.q.data(), at.qd.data(), Q.data());
        return Q;
    };
    const auto mass_times_v = [&](const test::State& at) {
        RowMajorMatrix M(n, n);
        model.mass(at.u, at.q.data(), M.data());
        return VectorXd(M * v);
    };
    const auto column = [&](const auto& f, const auto& move, double h) {
        const auto at = [&](double by) {
            test::State moved = s;
            move(moved, by);
            return f(moved);
        };
        return VectorXd((8.0 * (at(h) - at(-h)) - (at(2.0 * h) - at(-2.0 * h))) / (12.0 * h));
    };
    const CoordinateLayout& layout = model.coordinates();
    Derivatives d{MatrixXd(n, n), MatrixXd(n, n), MatrixXd(n, static_cast<Eigen::Index>(drive_value_count)),
                  MatrixXd(n, n)};
    for (int k = 0; k < n; ++k) {
        const double h = layout.field_of(k).kind == FieldKind::hub_angle ? 1e-3 : 1.0;
        d.q.col(k) = column(
            forces, [k](test::State& m, double by) { m.q[k] += by; }, h);
        d.qd.col(k) = column(
            forces, [k](test::State& m, double by) { m.qd[k] += by; }, 1.0);
        d.Mv.col(k) = column(
            mass_times_v, [k](test::State& m, double by) { m.q[k] += by; }, h);
    }
    d.u.col(0) = column(
        forces, [](test::State& m, double by) { m.u.tau += by; }, 1.0);
    d.u.col(1) = column(
        forces, [](test::State& m, double by) { m.u.theta_dot += by; }, 1.0);
    d.u.col(2) = column(
        forces, [](test::State& m, double by) { m.u.theta_ddot += by; }, 1.0);
    return d;
}

/// The largest of the four comparisons' relative differences.
double worst(const Derivatives& a, const Derivatives& b)
{
    return std::max({relative(a.q, b.q), relative(a.qd, b.qd), relative(a.u, b.u), relative(a.Mv, b.Mv)});
}

}  // namespace

TEST_CASE("the assembled exact Jacobian equals the generated derivative kernels", "[assembled_jacobian][generated]")
{
    // Two derivations of the same equations (by hand from the blocks, by the generator from the energies): they agree
    // as their M and Q do, to round-off of each matrix's largest entry.
    const Parameters every = test::with_every_term();
    std::mt19937 rng(4817);
    for (const VariantKey& key : variants()) {
        SECTION(key.name())
        {
            const Parameters p = test::with_profile(key, every);
            const auto gen = make_model(key, p, ModelSource::generated);
            const auto asm_ = make_model(key, p, ModelSource::assembled);
            REQUIRE(std::string(gen->source()) == "generated");
            REQUIRE(asm_->jacobian() != nullptr);
            for (int trial = 0; trial < 3; ++trial) {
                const test::State s = test::random_state_with_angle(key, rng);
                const VectorXd v = VectorXd::Random(key.nq());
                const Derivatives g = derivatives_of(*gen, s, v), a = derivatives_of(*asm_, s, v);
                INFO("trial " << trial << ": dQ/dq " << relative(a.q, g.q) << ", dQ/dqd " << relative(a.qd, g.qd)
                              << ", dQ/du " << relative(a.u, g.u) << ", (dM/dq) v " << relative(a.Mv, g.Mv));
                CHECK(worst(a, g) < 1e-12);
            }
        }
    }
}

TEST_CASE("the assembled exact Jacobian equals central differences of the assembled forces and mass",
          "[assembled_jacobian]")
{
    // The same variants against the assembled model's own Q and M, differenced (differences_of: exact but for
    // round-off): 1e-9 of each matrix's largest entry.
    const Parameters every = test::with_every_term();
    std::mt19937 rng(4818);
    for (const VariantKey& key : variants()) {
        SECTION(key.name())
        {
            const auto model = make_model(key, test::with_profile(key, every), ModelSource::assembled);
            for (int trial = 0; trial < 2; ++trial) {
                const test::State s = test::random_state_with_angle(key, rng);
                const VectorXd v = VectorXd::Random(key.nq());
                const Derivatives exact = derivatives_of(*model, s, v), differenced = differences_of(*model, s, v);
                INFO("trial " << trial << ": dQ/dq " << relative(exact.q, differenced.q) << ", dQ/dqd "
                              << relative(exact.qd, differenced.qd) << ", dQ/du " << relative(exact.u, differenced.u)
                              << ", (dM/dq) v " << relative(exact.Mv, differenced.Mv));
                CHECK(worst(exact, differenced) < 1e-9);
            }
        }
    }
}

TEST_CASE("a real blade's linearization: the assembled exact Jacobian gives the generated state matrices and modes",
          "[assembled_jacobian][blade_files]")
{
    // OpenFAST's NREL 5-MW blade file, all 49 stations, AMM Ny = Nz = 20 (docs/performance.md, "A real blade's Campbell
    // table"), about its steady coning at rated spin (12.1 rpm) under either drive: the state matrices of the two
    // sources row by row (measured 5e-14 and 2e-13), and the natural modes they give, all 40 of them (0.68 to 640 Hz;
    // measured 1.2e-10). The modes agree only as far as the first-order eigenproblem resolves them, to about eps times
    // its largest entries (the highest frequency squared) absolutely: at FEM Ny = Nz = 32, ten times stiffer, the two
    // sources' modes differ by as much as 8e-8, each as far from a symmetric solve of its own K and M.
    const TempFolder folder("assembled_jacobian_blade");
    const double rated = 12.1 * 2.0 * 3.14159265358979323846 / 60.0;
    for (const char* motion : {"kind = \"spin-up\"\nomega0 = 1.267\nduration = 10.0\n",
                               "kind = \"torque\"\ntau0 = 1e5\nduration = 10.0\n"}) {
        const std::string scene = folder.write(
            "blade.toml", "[beam]\nlength = 61.5\nblade_file = \"" + std::string(HUBBEAM_SOURCE_DIR) +
                              "/tests/data/import/5MW_Baseline/NRELOffshrBsline5MW_Blade.dat\"\n[hub]\nradius = 1.5\n"
                              "inertia = 1e5\n[motion]\n" +
                              motion +
                              "[discretization]\nmethod = \"amm\"\nnx = 0\n"
                              "ny = 20\nnz = 20\n[output]\nt_end = 1.0\n");
        const Scene s = load_scene(scene);
        SECTION(s.key().name())
        {
            const auto gen = make_model(s.key(), s.parameters, ModelSource::generated);
            const auto asm_ = make_model(s.key(), s.parameters, ModelSource::assembled);
            REQUIRE(std::string(gen->source()) == "generated");
            const SteadySpin steady_g = steady_spin(*gen, rated), steady_a = steady_spin(*asm_, rated);
            const MatrixXd Ag = state_space(*gen, steady_g).A, Aa = state_space(*asm_, steady_a).A;
            double rows = 0.0;  // each row of A against its own largest entry (rows of rates and of accelerations)
            for (Eigen::Index i = 0; i < Ag.rows(); ++i) rows = std::max(rows, relative(Aa.row(i), Ag.row(i)));
            INFO("state matrices: " << rows);
            CHECK(rows < 1e-12);
            const std::vector<NaturalMode> g = natural_modes(*gen, steady_g), a = natural_modes(*asm_, steady_a);
            REQUIRE(g.size() == a.size());
            double modes = 0.0;
            for (std::size_t k = 0; k < g.size(); ++k) modes = std::max(modes, std::abs(a[k].rad_s / g[k].rad_s - 1.0));
            INFO("modes: " << modes);
            CHECK(modes < 1e-9);
        }
    }
}
