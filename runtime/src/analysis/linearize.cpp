// The linearized hub-beam about a steady spin: force Jacobians, the steady stretch, the state-space matrices and
// the natural modes (docs/model.md section 10).
#include <hubbeam/csv_columns.hpp>
#include <hubbeam/linearize.hpp>

#include "analysis/modal_coordinates.hpp"
#include "linalg/eigen_solvers.hpp"
#include "linalg/factorizations.hpp"
#include "models/mode_kinds.hpp"
#include "models/modal_damping.hpp"
#include "models/model_operations.hpp"
#include "terms.hpp"

#include <algorithm>
#include <array>
#include <complex>
#include <deque>
#include <iterator>
#include <limits>
#include <map>
#include <tuple>
#include <numeric>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace hubbeam {

bool weight_turns_with_spin(const VariantKey& key, const std::vector<double>& p)
{
    return potential_reads_angle(key) && (p.empty() || p[index(Param::g)] != 0.0 || !key.out_of_plane());
}

std::vector<int> modal_coordinates(const Model& model, const SteadySpin& s, Axial axial)
{
    std::vector<int> R = kept_coordinates(model.coordinates(), axial);
    if (model.key().drive == Drive::torque && s.held) R.erase(R.begin());
    return R;
}

std::string unsteady_spin(const VariantKey& key, const std::vector<double>& p, double omega)
{
    // A hub that translates sees the blade at an azimuth that turns: about a spin its equations are periodic.
    if (omega != 0.0 && mass_reads_angle(key))
        return "with a moving hub ([support]) a spin at a constant rate is not steady in the blade's frame (the "
               "support is fixed, the blade turns: the linear equations are periodic); linearize at rest, Omega = 0";
    if (omega == 0.0 || !weight_turns_with_spin(key, p)) return {};
    return "with gravity in the plane of rotation a spin at a constant rate is not steady (the beam's weight turns "
           "with it: the motion is periodic); linearize about the held hub, Omega = 0";
}

SteadySpin steady_spin(const Model& model, double omega, double theta)
{
    const VariantKey& key = model.key();
    const std::vector<double>& p = model.parameters();
    // A rotor of identical blades on a moving hub has a steady spin, the hub at rest: the blades' pulls cancel. Its
    // linearization is periodic in the blades' frames and constant in the multi-blade coordinates.
    const bool balanced_hub = key.extras.hub && multiblade_refusal(model).empty();
    if (const std::string why = unsteady_spin(key, p, omega); !why.empty() && !balanced_hub)
        throw std::invalid_argument(why);
    if (potential_reads_angle(key) && (omega == 0.0 || weight_turns_with_spin(key, p)))
        return held_equilibrium(model, theta);
    // Newton on the axial rows with the bending fields straight (the straight beam is an equilibrium by symmetry);
    // out of the plane a pitch, pre-twist or precone bends and twists the steady beam (coning): on every elastic row.
    // The rows solved: every elastic one out of the plane, else every axial field's (each blade's, on a rotor).
    const int n = model.nq();
    std::vector<int> rows;
    // A balanced hub's translation stays 0 (by symmetry; a support without stiffness would make its rows singular).
    for (const CoordinateField& f : model.coordinates().fields)
        if (f.kind != FieldKind::hub_angle && (key.out_of_plane() || f.kind == FieldKind::axial) &&
            (f.basis || omega == 0.0 || !balanced_hub))
            for (int i = f.first; i < f.end(); ++i) rows.push_back(i);
    const int na = static_cast<int>(rows.size());
    const Eigen::VectorXi at = Eigen::Map<const Eigen::VectorXi>(rows.data(), na);
    SteadySpin s;
    s.omega = omega;
    s.q.assign(static_cast<std::size_t>(n), 0.0);
    s.qd = s.q;
    if (key.drive == Drive::torque)
        s.qd[0] = omega;
    else
        s.u.theta_dot = omega;
    // One step for the linear equations of orders zero and first, a few for full. Converged when the step is
    // round-off of the stretch, or stops shrinking at a level that is round-off of the forces (a FEM blade of
    // Ny = Nz = 32 stalls near 1e-12 of its coning: 50 steps of an LU each, before this test, at every rate).
    double previous = HUGE_VAL;
    for (int iteration = 0; na > 0 && iteration < 50; ++iteration) {
        std::vector<double> Q(static_cast<std::size_t>(n));
        model.forces(s.u, s.q.data(), s.qd.data(), Q.data());
        const Eigen::MatrixXd K = force_q_jacobian(model, s.u, s.q, s.qd)(at, at);
        const Eigen::VectorXd dA = K.partialPivLu().solve(-Eigen::Map<const Eigen::VectorXd>(Q.data(), n)(at));
        double size = 0.0;
        for (int i = 0; i < na; ++i) {
            s.q[static_cast<std::size_t>(at[i])] += dA[i];
            size = std::max(size, std::abs(s.q[static_cast<std::size_t>(at[i])]));
        }
        if (!dA.allFinite())
            throw std::runtime_error(key.out_of_plane() ? "the steady deflection at this spin has no solution"
                                                        : "the steady axial stretch at this spin has no solution");
        const double step = dA.cwiseAbs().maxCoeff();
        if (step <= 1e-14 * std::max(size, 1e-300) || (step <= 1e-10 * size && step >= 0.5 * previous)) break;
        previous = step;
    }
    return s;
}

SteadySpin held_equilibrium(const Model& model, double theta, double theta_dot)
{
    const VariantKey& key = model.key();
    const int n = model.nq(), e0 = model.coordinates().first_elastic(), ne = n - e0;
    SteadySpin s;
    s.held = true;
    s.u.theta = theta;
    s.q.assign(static_cast<std::size_t>(n), 0.0);
    s.qd = s.q;
    s.omega = theta_dot;
    if (key.drive == Drive::torque) {
        s.q[0] = theta;
        s.qd[0] = theta_dot;
    } else {
        s.u.theta_dot = theta_dot;
    }
    // Newton on the elastic rows (their rates 0): one step where they are linear in q_e (orders zero and first), a few
    // where the weight meets full order's nonlinear terms. Converged when the residual is round-off against the
    // terms that make it up (the load and K q), which holds whatever K's condition, near buckling too.
    std::vector<double> Q(static_cast<std::size_t>(n));
    const auto elastic = [&] { return Eigen::Map<const Eigen::VectorXd>(Q.data() + e0, ne); };
    model.forces(s.u, s.q.data(), s.qd.data(), Q.data());
    const double load = elastic().cwiseAbs().maxCoeff();
    bool converged = load == 0.0;
    for (int iteration = 0; iteration < 50 && !converged; ++iteration) {
        const Eigen::MatrixXd K = force_q_jacobian(model, s.u, s.q, s.qd).block(e0, e0, ne, ne);
        const Eigen::VectorXd dq = K.partialPivLu().solve(-elastic());
        if (!dq.allFinite()) break;
        for (int i = 0; i < ne; ++i) s.q[static_cast<std::size_t>(e0 + i)] += dq[i];
        model.forces(s.u, s.q.data(), s.qd.data(), Q.data());
        const double terms = load + K.cwiseAbs().maxCoeff() *
                                        Eigen::Map<const Eigen::VectorXd>(s.q.data() + e0, ne).cwiseAbs().maxCoeff();
        converged = elastic().cwiseAbs().maxCoeff() <= 1e-12 * terms;
    }
    if (!converged)
        throw std::runtime_error("the beam has no static equilibrium under its weight with the hub held at this angle");
    // The torque that holds a free hub: Q_theta with tau = 0 is the weight's moment about the axis.
    if (key.drive == Drive::torque) {
        model.forces(s.u, s.q.data(), s.qd.data(), Q.data());
        const ForceJacobians J = force_jacobians(model, s.u, s.q, s.qd);
        s.u.tau = -Q[0] / J.u(0, static_cast<Eigen::Index>(DriveValue::tau));
    }
    return s;
}

namespace {

/// The row and column among q's of state coordinate c (0 = theta, 1.. = flexible): the model's own index, or none
/// (-1) for a prescribed hub (theta is not among q).
int model_index(bool torque, int c)
{
    return torque ? c : c - 1;
}

/// The state space's outputs (C, D and their names) about the steady state s, m the state's coordinates: tip_uy and
/// theta, then a blade's tip_uz and tip_phi where it has those fields (docs/model.md 12.1).
void add_outputs(StateSpace& ss, const Model& model, const SteadySpin& s, int m)
{
    const VariantKey& key = model.key();
    const bool torque = key.drive == Drive::torque;
    ss.outputs = {"tip_uy", "theta"};
    std::vector<double Tip::*> tip_values = {&Tip::uy};
    if (key.nz > 0) ss.outputs.emplace_back("tip_uz"), tip_values.push_back(&Tip::uz);
    if (key.nt > 0) ss.outputs.emplace_back("tip_phi"), tip_values.push_back(&Tip::phi);
    const auto outputs = static_cast<Eigen::Index>(ss.outputs.size());
    ss.C = Eigen::MatrixXd::Zero(outputs, 2 * m);
    std::vector<int> flexible;  // the state's flexible coordinates 1..m-1 among q's
    for (int c = 1; c < m; ++c) flexible.push_back(model_index(torque, c));
    for (std::size_t k = 0; k < tip_values.size(); ++k)
        ss.C.block(k == 0 ? 0 : static_cast<Eigen::Index>(k + 1), 1, 1, m - 1) =
            tip_row(model, s.q, flexible, tip_values[k]).transpose();
    ss.C(1, 0) = 1.0;
    ss.D = Eigen::MatrixXd::Zero(outputs, 1);
}

/// The state's names: theta (a state of a prescribed hub too) and the flexible coordinates, then their rates.
void name_states(StateSpace& ss, const Model& model)
{
    std::vector<std::string> names{"theta"};  // a state of a prescribed hub too
    for (const CoordinateField& f : model.coordinates().fields)
        if (f.kind != FieldKind::hub_angle)
            for (int k = 0; k < f.count; ++k) names.push_back(f.name(k));
    ss.states = names;
    for (const std::string& name : names) ss.states.push_back(name + "_dot");
}

}  // namespace

StateSpace state_space(const Model& model, const SteadySpin& s)
{
    const VariantKey& key = model.key();
    const int n = model.nq();
    const bool torque = key.drive == Drive::torque;
    const int f0 = model.coordinates().first_elastic();  // the first flexible coordinate in q
    const int nf = n - f0;                               // flexible coordinates
    const int m = nf + 1;                                // theta and the flexible coordinates
    const ForceJacobians J = force_jacobians(model, s.u, s.q, s.qd);
    const Eigen::MatrixXd M = mass_at(model, s.u, s.q);
    const auto llt = M.llt();
    if (llt.info() != Eigen::Success)
        throw std::runtime_error("the mass matrix at the steady spin is not positive definite");
    // M^-1 of Q's derivatives: qdd = M^-1 (Qq dq + Qqd dqd + Qu du) about the steady state (its qdd is 0, so
    // dM/dq does not enter).
    const Eigen::MatrixXd Aq = llt.solve(J.q), Aqd = llt.solve(J.qd), Au = llt.solve(J.u);
    StateSpace ss;
    ss.A = Eigen::MatrixXd::Zero(2 * m, 2 * m);
    ss.B = Eigen::MatrixXd::Zero(2 * m, 1);
    ss.A.topRightCorner(m, m).setIdentity();
    const auto model_index = [&](int c) { return hubbeam::model_index(torque, c); };
    const int dv_theta_dot = static_cast<int>(DriveValue::theta_dot);
    for (int r = 0; r < m; ++r) {
        const int i = model_index(r);
        if (i < 0) continue;  // theta_ddot of a prescribed hub is the input itself
        for (int c = 0; c < m; ++c) {
            const int k = model_index(c);
            if (k >= 0) {
                ss.A(m + r, c) = Aq(i, k);
                ss.A(m + r, m + c) = Aqd(i, k);
            } else {  // a prescribed hub's rate enters through the drive
                ss.A(m + r, m + c) = Au(i, dv_theta_dot);
            }
        }
        ss.B(m + r, 0) =
            torque ? Au(i, static_cast<int>(DriveValue::tau)) : Au(i, static_cast<int>(DriveValue::theta_ddot));
    }
    if (!torque) ss.B(m, 0) = 1.0;  // theta_ddot = v
    if (reads_driven_angle(key)) {
        // A prescribed hub's angle is an input of the weight's and a moving hub's terms: its column is
        // M^-1 dQ/dtheta (dM/dtheta qdd is nothing at the equilibrium, qdd = 0).
        std::vector<double> dtheta(static_cast<std::size_t>(n));
        model.forces_theta(s.u, s.q.data(), s.qd.data(), dtheta.data());
        const Eigen::VectorXd column = llt.solve(Eigen::Map<const Eigen::VectorXd>(dtheta.data(), n));
        for (int r = 1; r < m; ++r) ss.A(m + r, 0) = column[model_index(r)];
    }
    add_outputs(ss, model, s, m);
    name_states(ss, model);
    ss.inputs = {torque ? "tau" : "theta_ddot"};
    return ss;
}

namespace {

/// X's entries at rows x cols.
Eigen::MatrixXd submatrix(const Eigen::MatrixXd& X, const std::vector<int>& rows, const std::vector<int>& cols)
{
    Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (std::size_t j = 0; j < cols.size(); ++j)
            out(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = X(rows[i], cols[j]);
    return out;
}

/// Whether R's first coordinate is a free hub's angle: cyclic, its position left out of the state.
Eigen::Index cyclic_angle(const Model& model, const std::vector<int>& R)
{
    return model.key().drive == Drive::torque && !R.empty() && R.front() == 0 ? 1 : 0;
}

/// The Cholesky factorization of a mass matrix at a steady spin (M = L L^T = U^T U): the solves of the linearized
/// equations, and the weight of the modes' shapes. Throws std::runtime_error if M is not positive definite.
Eigen::LLT<Eigen::MatrixXd> mass_factor(const Eigen::MatrixXd& M)
{
    Eigen::LLT<Eigen::MatrixXd> llt(M);
    if (llt.info() != Eigen::Success)
        throw std::runtime_error("the mass matrix at the steady spin is not positive definite");
    return llt;
}

/// The linearized equations M x'' = Qq x + Qqd x' over the kept coordinates R as a first-order system x' = X x: the
/// positions of R but a free hub's angle (cyclic, first of R when first is 1), then all rates of R (a free hub's
/// rate couples to the beam's): X = [[select, 0], [M^-1 Qq(:, positions), M^-1 Qqd]]. llt is the Cholesky
/// factorization of M over R (mass_factor). Damping is in Qqd: X's eigenproblem is the damped (quadratic) one in
/// first-order form.
Eigen::MatrixXd linearized_system(const LinearEquations& e, const Eigen::LLT<Eigen::MatrixXd>& llt,
                                  const std::vector<int>& R, Eigen::Index first)
{
    const Eigen::MatrixXd Qq = submatrix(e.Qq, R, R), Qqd = submatrix(e.Qqd, R, R);
    const auto r = static_cast<Eigen::Index>(R.size());
    const Eigen::Index p = r - first;
    const Eigen::MatrixXd Aq = llt.solve(Qq), Aqd = llt.solve(Qqd);
    Eigen::MatrixXd X = Eigen::MatrixXd::Zero(p + r, p + r);
    for (Eigen::Index i = 0; i < p; ++i) X(i, p + first + i) = 1.0;
    X.bottomLeftCorner(r, p) = Aq.rightCols(p);
    X.bottomRightCorner(r, r) = Aqd;
    return X;
}

}  // namespace

/// NaturalMode::shape of a mode with these rates: U rates with U the upper Cholesky factor of M over the same
/// coordinates (mass_factor: M = U^T U), scaled to unit length.
Eigen::VectorXcd weighted_shape(const Eigen::MatrixXd& U, const Eigen::VectorXcd& rates)
{
    // Real and imaginary parts apart: a real matrix times a real vector twice, not U cast to complex (a copy of U and
    // a complex product per mode, a third of a Campbell table's time at Ny = 64).
    const auto upper = U.triangularView<Eigen::Upper>();
    const Eigen::VectorXd re = upper * rates.real(), im = upper * rates.imag();
    Eigen::VectorXcd w(re.size());
    w.real() = re;
    w.imag() = im;
    const double length = w.norm();
    return length > 0.0 ? Eigen::VectorXcd(w / length) : w;
}


namespace {

/// The eigenvalues of the linearized equations over R and each one's rates over R (columns), with the index of a free
/// hub's conserved momentum (-1 if none).
struct LinearEigen {
    Eigen::VectorXcd lambda;
    Eigen::MatrixXcd rates;
    Eigen::Index momentum = -1;
};

/// How the linearized equations over R are solved: as the symmetric K x = omega^2 M x where no rate enters a force
/// (Qqd over R is zero: no damping, no Coriolis coupling), as a Hermitian problem where the rates enter by Coriolis
/// terms alone (Qqd skew to round-off, the equations undamped), else in first-order form. Both special forms need a
/// stiffness symmetric to round-off and no free hub's angle among R.
enum class LinearForm { first_order, symmetric, gyroscopic };

LinearForm linear_form(const Eigen::MatrixXd& Qq, const Eigen::MatrixXd& Qqd, Eigen::Index cyclic, bool damped)
{
    if (cyclic != 0 || (Qq - Qq.transpose()).cwiseAbs().maxCoeff() > 1e-12 * Qq.cwiseAbs().maxCoeff())
        return LinearForm::first_order;
    if (Qqd.isZero(0.0)) return LinearForm::symmetric;
    const bool skew = (Qqd + Qqd.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * Qqd.cwiseAbs().maxCoeff();
    return skew && !damped ? LinearForm::gyroscopic : LinearForm::first_order;
}

/// The modes of K x = omega^2 M x, K symmetric, M = U^T U, as a symmetric eigenproblem. Where K is positive
/// definite (K = L L^T), its inverse form M x = omega^-2 K x, the symmetric L^-1 M L^-T: its eigenvalues err by eps
/// times the largest, 1 / omega_1^2, so that the low modes keep every digit and a mode k loses
/// (omega_k / omega_1)^2 eps. (The first-order form's err by eps omega_max^2 absolutely, in omega: 8e-8 of a blade's
/// first modes at FEM 32; the direct U^-T K U^-1, by eps omega_max^2 in omega^2.) Otherwise (a divergent mode, or a
/// neutral one) the direct form. lambda is the first-order form's eigenvalue, i omega or, for omega^2 < 0, the
/// divergent sqrt(-omega^2); the rates are the vectors' positions (their phase is arbitrary).
LinearEigen symmetric_eigen(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const Eigen::MatrixXd& U)
{
    const Eigen::LLT<Eigen::MatrixXd> stiffness(K);
    const bool inverse = stiffness.info() == Eigen::Success;
    const Eigen::MatrixXd L = inverse ? Eigen::MatrixXd(stiffness.matrixL()) : Eigen::MatrixXd(U.transpose());
    const auto lower = L.triangularView<Eigen::Lower>();
    // The pencil's matrix A (M, or K) turned by the other's factor: S = L^-1 A L^-T.
    Eigen::MatrixXd S = lower.solve(inverse ? M : K);
    S = lower.solve(Eigen::MatrixXd(S.transpose()));
    const SymmetricPairs eig = symmetric_pairs(0.5 * (S + S.transpose()));
    if (!eig.converged) throw std::runtime_error("the eigenvalues of the linearized equations did not converge");
    LinearEigen out;
    out.lambda.resize(eig.values.size());
    for (Eigen::Index k = 0; k < eig.values.size(); ++k) {
        const double w2 = inverse ? 1.0 / eig.values[k] : eig.values[k];
        out.lambda[k] = w2 >= 0.0 ? std::complex<double>(0.0, std::sqrt(w2)) : std::complex<double>(std::sqrt(-w2));
    }
    out.rates = lower.transpose().solve(eig.vectors).cast<std::complex<double>>();
    return out;
}

/// The modes of M x'' + G x' + K x = 0 with G = -Qqd skew (Coriolis) and K symmetric positive definite: in first-order
/// form B z' = A z, B = [[K, 0], [0, M]] positive definite and A = [[0, K], [-K, -G]] skew, so that -i A z = omega B z
/// is a Hermitian pencil with real omega (in pairs +-omega). Its matrix L_B^-1 (-i A) L_B^-H has entries of the size of
/// the frequencies, not of their squares as the first-order form's: each omega errs by eps omega_max, not
/// eps omega_max^2. Returns nothing where K is not positive definite (a divergent or neutral mode).
std::optional<LinearEigen> gyroscopic_eigen(const Eigen::MatrixXd& K, const Eigen::MatrixXd& Qqd,
                                            const Eigen::MatrixXd& M)
{
    const Eigen::Index n = M.rows();
    const Eigen::MatrixXd G = -0.5 * (Qqd - Qqd.transpose());
    if (Eigen::LLT<Eigen::MatrixXd>(K).info() != Eigen::Success) return std::nullopt;
    const std::complex<double> i(0.0, 1.0);
    Eigen::MatrixXcd H = Eigen::MatrixXcd::Zero(2 * n, 2 * n), B = Eigen::MatrixXcd::Zero(2 * n, 2 * n);
    H.topRightCorner(n, n) = -i * K;
    H.bottomLeftCorner(n, n) = i * K;
    H.bottomRightCorner(n, n) = i * G;
    B.topLeftCorner(n, n) = K;
    B.bottomRightCorner(n, n) = M;
    HermitianPairs eig = hermitian_pairs(H, B);
    if (!eig.converged) return std::nullopt;
    LinearEigen out;
    out.lambda = i * eig.values.cast<std::complex<double>>();
    out.rates = eig.vectors.bottomRows(n);
    return out;
}

/// The first-order form's eigenvalues and rates (linearized_system), for any linearized equations.
LinearEigen first_order_eigen(const Model& model, const LinearEquations& e, const Eigen::LLT<Eigen::MatrixXd>& llt,
                              const std::vector<int>& R)
{
    const Eigen::Index cyclic = cyclic_angle(model, R);
    EigenPairs eig = eigen_pairs(linearized_system(e, llt, R, cyclic));
    if (!eig.converged) throw std::runtime_error("the eigenvalues of the linearized equations did not converge");
    LinearEigen out;
    out.lambda = std::move(eig.values);
    const auto r = static_cast<Eigen::Index>(R.size());
    const Eigen::Index first_rate = r - cyclic;  // the rates follow the positions
    // The free hub's conserved angular momentum: one zero eigenvalue, the smallest (damping acts on the elastic
    // rates relative to the hub, so it conserves it too).
    if (cyclic == 1) out.lambda.cwiseAbs().minCoeff(&out.momentum);
    out.rates = eig.vectors.bottomRows(eig.vectors.rows() - first_rate).topRows(r);
    return out;
}

}  // namespace

std::vector<NaturalMode> eigen_modes(const Model& model, const LinearEquations& e, const std::vector<int>& R,
                                     const ModeNaming& naming)
{
    const bool damped = dissipates(model) && naming.damped;
    const Eigen::MatrixXd M = submatrix(e.M, R, R), Qq = submatrix(e.Qq, R, R);
    const Eigen::LLT<Eigen::MatrixXd> llt = mass_factor(M);
    const Eigen::MatrixXd U = llt.matrixU();
    const Eigen::MatrixXd Qqd = submatrix(e.Qqd, R, R);
    const LinearForm form = linear_form(Qq, Qqd, cyclic_angle(model, R), damped);
    const Eigen::MatrixXd K = -0.5 * (Qq + Qq.transpose());  // symmetric to round-off where a special form is taken
    std::optional<LinearEigen> gyroscopic;
    if (form == LinearForm::gyroscopic) gyroscopic = gyroscopic_eigen(K, Qqd, M);
    LinearEigen eig = form == LinearForm::symmetric ? symmetric_eigen(K, M, U)
                      : gyroscopic                  ? std::move(*gyroscopic)
                                                    : first_order_eigen(model, e, llt, R);
    const Eigen::VectorXcd& lambda = eig.lambda;
    const Eigen::Index momentum = eig.momentum;
    Eigen::MatrixXcd& rates_of = eig.rates;
    if (naming.separate) naming.separate(lambda, rates_of);
    std::vector<NaturalMode> modes;
    for (Eigen::Index k = 0; k < lambda.size(); ++k) {
        const std::complex<double> l = lambda[k];
        if (k == momentum) continue;
        const double scale = std::max(1.0, std::abs(l));
        const bool oscillating = l.imag() > 1e-9 * scale, real = std::abs(l.imag()) <= 1e-9 * scale;
        const bool divergent = real && l.real() > 0.0, overdamped = damped && real && l.real() < 0.0;
        if (!oscillating && !divergent && !overdamped)
            continue;  // the conjugate, or the stable twin of a divergent pair
        const Eigen::VectorXcd rates = rates_of.col(k);
        NaturalMode mode;
        set_rates(mode, oscillating ? l.imag() : 0.0, l.real(), std::abs(l), damped);
        mode.kind = overdamped ? std::string(overdamped_kind) : naming.kind(rates, mode.rad_s);
        mode.shape = weighted_shape(U, rates);
        modes.push_back(std::move(mode));
    }
    return modes;
}

void set_rates(NaturalMode& mode, double rad_s, double real, double modulus, bool damped)
{
    const double growth = !damped && std::abs(real) <= 1e-6 * std::max(1.0, modulus) ? 0.0 : real;
    const double magnitude = std::hypot(growth, rad_s);
    mode.rad_s = rad_s;
    mode.growth = growth;
    mode.undamped_rad_s = magnitude;
    mode.damping_ratio = magnitude > 0.0 ? -growth / magnitude : 0.0;
}

bool mode_before(const NaturalMode& a, const NaturalMode& b, bool damped)
{
    const auto frequency = [damped](const NaturalMode& m) {
        return !damped || (m.rad_s == 0.0 && m.growth > 0.0) ? m.rad_s : m.undamped_rad_s;
    };
    return frequency(a) != frequency(b) ? frequency(a) < frequency(b) : a.growth > b.growth;
}

void sort_modes(std::vector<NaturalMode>& modes, bool damped)
{
    std::sort(modes.begin(), modes.end(),
              [damped](const NaturalMode& a, const NaturalMode& b) { return mode_before(a, b, damped); });
}

std::vector<NaturalMode> natural_modes(const Model& model, const SteadySpin& s, Axial axial)
{
    // The coordinates that keep their inertia: all, or with quasi-static axial coordinates all but A. A then
    // follows its own rows with A_dot = A_ddot = 0 (docs/model.md section 9), and the other rows drop A's rates;
    // they do not depend on A itself at the straight beam (Q_B is odd in B, Q_theta holds A only with rates), so
    // A's deviation drops out of them and the condensed equations are R's rows and columns alone. A held hub's
    // angle is not among them.
    const std::vector<int> R = modal_coordinates(model, s, axial);
    const ForceJacobians J = force_jacobians(model, s.u, s.q, s.qd);
    const LinearEquations e{mass_at(model, s.u, s.q), J.q, J.qd};
    ModeNaming naming;
    if (model.key().out_of_plane())
        naming.separate = [&](const Eigen::VectorXcd& lambda, Eigen::MatrixXcd& rates) {
            separate_repeated(model, e.M, R, lambda, rates);
        };
    naming.kind = [&](const Eigen::VectorXcd& rates, double) {
        return std::string(mode_kind(dominant_field(model, e.M, R, rates), model.key()));
    };
    std::vector<NaturalMode> modes = eigen_modes(model, e, R, naming);
    sort_modes(modes, dissipates(model.key()));
    return modes;
}

StateSpace closed_loop(const StateSpace& open, const Control& control)
{
    if (open.inputs.size() != 1 || open.inputs[0] != "tau")
        throw std::invalid_argument("a closed loop needs the open loop of a free hub (input tau)");
    const Eigen::Index n = open.A.rows(), m = n / 2;  // states (theta, q_f, theta_dot, q_f_dot)
    // tau = K x: the gains on theta (state 0), theta_dot (state m) and tip_uy (output row 0, through C).
    Eigen::RowVectorXd K = -control.k_tip * open.C.row(0);
    K(0) -= control.kp;
    K(m) -= control.kd;
    const bool integral = control.ki != 0.0;
    const Eigen::Index N = n + (integral ? 1 : 0);
    StateSpace cl;
    cl.A = Eigen::MatrixXd::Zero(N, N);
    cl.A.topLeftCorner(n, n) = open.A + open.B * K;
    cl.B = Eigen::MatrixXd::Zero(N, 1);
    cl.B.topRows(n) = open.B;
    cl.C = Eigen::MatrixXd::Zero(open.C.rows(), N);
    cl.C.leftCols(n) = open.C;
    cl.D = open.D;
    cl.states = open.states;
    if (integral) {
        cl.A.block(0, n, n, 1) = -control.ki * open.B;  // tau's integral term
        cl.A(n, 0) = 1.0;                               // z' = theta (deviation from the reference)
        cl.states.emplace_back("controller_integral");
    }
    cl.inputs = {"tau_disturbance"};
    cl.outputs = open.outputs;
    return cl;
}

std::vector<NaturalMode> closed_loop_modes(const Model& model, const SteadySpin& s, const Control& control)
{
    const StateSpace cl = closed_loop(state_space(model, s), control);
    const EigenPairs eig = eigen_pairs(cl.A);
    if (!eig.converged) throw std::runtime_error("the eigenvalues of the closed loop did not converge");
    const Eigen::MatrixXd M = mass_at(model, s.u, s.q);
    const Eigen::MatrixXd U = mass_factor(M).matrixU();
    const Eigen::Index m = M.rows();  // the state holds theta and the flexible coordinates, as q does under torque
    std::vector<int> all(static_cast<std::size_t>(m));
    std::iota(all.begin(), all.end(), 0);
    std::vector<NaturalMode> modes;
    for (Eigen::Index k = 0; k < eig.values.size(); ++k) {
        const std::complex<double> l = eig.values[k];
        const double magnitude = std::abs(l), scale = std::max(1.0, magnitude);
        if (l.imag() < -1e-9 * scale || magnitude <= 1e-9) continue;  // a conjugate, or a neutral direction
        // The kind whose coordinates hold most of the mode's kinetic energy (the state's rates are q's, all of them).
        const Eigen::VectorXcd rates = eig.vectors.col(k).segment(m, m);
        const std::vector<double> energy = energy_by_field(model, M, all, rates);
        const auto most = std::max_element(energy.begin(), energy.end()) - energy.begin();
        const bool oscillating = l.imag() > 1e-9 * scale;
        const FieldKind kind = model.coordinates().fields[static_cast<std::size_t>(most)].kind;
        const bool overdamped = !oscillating && l.real() < 0.0;  // a real root of the loop that decays
        modes.push_back({oscillating ? l.imag() : 0.0, l.real(),
                         overdamped ? overdamped_kind : mode_kind(kind, model.key()), magnitude,
                         -l.real() / magnitude, weighted_shape(U, rates)});
    }
    std::sort(modes.begin(), modes.end(),
              [](const NaturalMode& a, const NaturalMode& b) { return a.undamped_rad_s < b.undamped_rad_s; });
    return modes;
}

double mac(const NaturalMode& a, const NaturalMode& b)
{
    if (a.shape.size() != b.shape.size()) throw std::invalid_argument("mac: shapes of different sizes");
    return std::norm(a.shape.dot(b.shape));  // dot conjugates a: a^H b
}

namespace {

/// Whether the modes of model in frame are multiblade_modes (no control: a controller may feed back blade 1's tip).
bool multiblade(const Model& model, const Control* control, Frame frame)
{
    return frame == Frame::fixed && control == nullptr && multiblade_refusal(model).empty();
}

/// The modes about the steady spin at omega, as campbell takes them.
std::vector<NaturalMode> modes_at(const Model& model, double omega, Axial axial, double theta, const Control* control,
                                  Frame frame)
{
    if (multiblade(model, control, frame)) return multiblade_modes(model, steady_spin(model, omega, theta), axial);
    // Under weight in the plane of rotation a spin has no steady state: its modes are the periodic motion's (Floquet).
    if (control == nullptr && !unsteady_spin(model.key(), model.parameters(), omega).empty())
        return floquet_modes(model, omega, axial);
    const SteadySpin s = steady_spin(model, omega, theta);
    return control ? closed_loop_modes(model, s, *control) : natural_modes(model, s, axial);
}

/// Above this MAC with a line's shape a mode is the line's: no other mode can have as large a MAC (their squared
/// projections on a shape of unit length sum to at most about 1 where the shapes are nearly orthogonal in the mass).
constexpr double followed_mac = 0.5;

/// Above this damping ratio a mode is nearly critically damped: its damped frequency below 4.5 % of |lambda|.
constexpr double nearly_critical = 0.999;

/// A mode's eigenvalue growth + i rad_s (the one of positive frequency of its pair).
std::complex<double> eigenvalue(const NaturalMode& m)
{
    return {m.growth, m.rad_s};
}

/// The open loop's linearized equations about a steady spin as the quadratic pencil of the modal coordinates R:
/// lambda^2 M x = K x + lambda C x with K = dQ/dq, C = dQ/dqd over R (linearized_system's eigenproblem without its
/// M^-1), and U with M = U^T U, the weight of a mode's shape.
struct Pencil {
    Eigen::MatrixXd M, C, K, U;
};

Pencil pencil_at(const Model& model, const SteadySpin& s, Axial axial)
{
    const std::vector<int> R = modal_coordinates(model, s, axial);
    const ForceJacobians J = force_jacobians(model, s.u, s.q, s.qd);
    Pencil p{submatrix(mass_at(model, s.u, s.q), R, R), submatrix(J.qd, R, R), submatrix(J.q, R, R), {}};
    // A free hub's angle is cyclic: linearized_system leaves its column of K out (its zero eigenvalue is the
    // conserved momentum's), and so does the pencil.
    if (cyclic_angle(model, R) == 1) p.K.col(0).setZero();
    p.U = mass_factor(p.M).matrixU();
    return p;
}

/// The open loop's modes about a steady spin near a predicted eigenvalue, one factorization per shift: the
/// eigenproblem is the companion pencil A - lambda B, A = [[0, I], [K, C]], B = diag(I, M), of the state
/// z = (x, lambda x) (Pencil), shifted and inverted, (A - sigma B)^-1 B, whose solves are those of the r x r matrix
/// P(sigma) = sigma^2 M - sigma C - K. Where natural_modes finds every eigenvalue of 2r x 2r with its vector, this
/// factors r x r once and solves with it.
class ModesNear {
public:
    ModesNear(const Model& model, double omega, Axial axial, double theta)
        : p_(pencil_at(model, steady_spin(model, omega, theta), axial)),
          M_(p_.M.cast<cd>()), C_(p_.C.cast<cd>()), K_(p_.K.cast<cd>())
    {
    }

    /// The mode nearest guess (growth + i rad_s) of the line whose shape is reference, the iteration started at start
    /// (a shape of the line): inverse iteration, the shift moved onto the estimate where it is slow (Rayleigh
    /// quotient iteration). Empty where it does not converge or finds another mode (MAC with reference at most
    /// followed_mac: in a cluster of nearly equal eigenvalues, such as the slow roots of overdamped modes about
    /// -1/beta, the nearest eigenvalue need not be the line's).
    std::optional<NaturalMode> line_mode(std::complex<double> guess, const Eigen::VectorXcd& start,
                                         const Eigen::VectorXcd& reference) const
    {
        if (start.size() != p_.M.rows() || reference.size() != p_.M.rows()) return std::nullopt;
        std::optional<NaturalMode> m = polished(guess, positions(start));
        return m && std::norm(reference.dot(m->shape)) > followed_mac ? m : std::nullopt;
    }

private:
    using cd = std::complex<double>;

    /// The positions x of a shape's rates (U^-1 shape, the same direction).
    Eigen::VectorXcd positions(const Eigen::VectorXcd& shape) const
    {
        const auto upper = p_.U.triangularView<Eigen::Upper>();
        Eigen::VectorXcd x(shape.size());
        x.real() = upper.solve(Eigen::VectorXd(shape.real()));
        x.imag() = upper.solve(Eigen::VectorXd(shape.imag()));
        return x;
    }

    /// NaturalMode::shape of the eigenpair (lambda, x): its rates lambda x weighted by U.
    Eigen::VectorXcd shape(cd lambda, const Eigen::VectorXcd& x) const { return weighted_shape(p_.U, lambda * x); }

    /// P(sigma)'s LU.
    Eigen::PartialPivLU<Eigen::MatrixXcd> factor(cd sigma) const
    {
        return Eigen::PartialPivLU<Eigen::MatrixXcd>(sigma * sigma * M_ - sigma * C_ - K_);
    }

    /// (A - sigma B)^-1 B z for the states z = (x, y), columns of X and Y: P(sigma) w_x = C x - M (sigma x + y),
    /// w_y = x + sigma w_x.
    void apply(const Eigen::PartialPivLU<Eigen::MatrixXcd>& lu, cd sigma, Eigen::MatrixXcd& X,
               Eigen::MatrixXcd& Y) const
    {
        const Eigen::MatrixXcd wx = lu.solve(C_ * X - M_ * (sigma * X + Y));
        Y = X + sigma * wx;
        X = wx;
    }

    /// The root of a l^2 - b l - c = 0 nearest near, a, b, c the pencil's quadratic forms of x: the eigenvalue whose
    /// vector x is (the quadratic Rayleigh quotient).
    cd rayleigh(const Eigen::VectorXcd& x, cd near) const
    {
        const cd a = x.dot(M_ * x), b = x.dot(C_ * x), c = x.dot(K_ * x);
        const cd root = std::sqrt(b * b + 4.0 * a * c);
        const cd l1 = (b + root) / (2.0 * a), l2 = (b - root) / (2.0 * a);
        return std::abs(l1 - near) <= std::abs(l2 - near) ? l1 : l2;
    }

    /// The eigenpair nearest guess from the positions x0 by inverse iteration, as a mode; empty if it does not
    /// converge to round-off (its residual P(lambda) x against the pencil's scale).
    std::optional<NaturalMode> polished(cd guess, const Eigen::VectorXcd& x0) const
    {
        Eigen::MatrixXcd x = x0, y = guess * x0;
        cd sigma = guess, lambda = guess;
        bool converged = false;
        // A few steps at the predicted shift bring x near the mode's vector; then the shift moves onto the estimate
        // (Rayleigh quotient iteration), where each step gains many digits.
        for (int shift = 0; shift < 5 && !converged; ++shift) {
            const Eigen::PartialPivLU<Eigen::MatrixXcd> lu = factor(sigma);
            double step = HUGE_VAL;  // the estimate's last move, relative to it
            for (int iteration = 0; iteration < (shift == 0 ? 3 : 8) && !converged; ++iteration) {
                apply(lu, sigma, x, y);
                const double size = std::sqrt(x.squaredNorm() + y.squaredNorm());
                if (!(size > 0.0) || !std::isfinite(size)) return std::nullopt;
                x /= size;
                y /= size;
                const cd next = rayleigh(x.col(0), lambda);
                // Converged when the estimate moves by round-off; or, once the shift is the estimate (each step
                // then gains digits), when its moves stop shrinking at a level that is round-off of the pencil's
                // quadratic forms: 1e-11 of |lambda| for FEM Ny = Nz = 64, whose K spans twelve orders of
                // magnitude. At the predicted shift the moves may shrink slowly, and stopping there would not be
                // converged.
                const double moved = std::abs(next - lambda) / std::abs(next);
                converged = iteration > 0 && (moved <= 1e-14 || (shift > 0 && moved <= 1e-9 && moved > 0.5 * step));
                step = moved;
                lambda = next;
            }
            sigma = lambda;
        }
        Eigen::VectorXcd v = x.col(0);
        const Eigen::VectorXcd residual = lambda * lambda * (M_ * v) - lambda * (C_ * v) - K_ * v;
        const double scale = std::norm(lambda) * p_.M.norm() + std::abs(lambda) * p_.C.norm() + p_.K.norm();
        if (!converged || !(residual.norm() <= 1e-8 * scale * v.norm())) return std::nullopt;
        if (lambda.imag() < 0.0) {  // the conjugate of the mode's eigenvalue: its pair's other member
            lambda = std::conj(lambda);
            v = v.conjugate();
        }
        const bool oscillating = lambda.imag() > 1e-9 * std::max(1.0, std::abs(lambda));
        const double rad_s = oscillating ? lambda.imag() : 0.0, magnitude = std::hypot(lambda.real(), rad_s);
        return NaturalMode{rad_s, lambda.real(), "", magnitude, magnitude > 0.0 ? -lambda.real() / magnitude : 0.0,
                           shape(lambda, v)};
    }

    Pencil p_;
    Eigen::MatrixXcd M_, C_, K_;
};

}  // namespace

std::vector<int> best_assignment(const Eigen::MatrixXd& score)
{
    const auto rows = static_cast<int>(score.rows()), cols = static_cast<int>(score.cols());
    const int n = std::max(rows, cols);
    const auto cost = [&](int i, int j) { return i < rows && j < cols ? -score(i, j) : 0.0; };  // 0-based
    // Potentials u (rows) and v (columns), 1-based with 0 a sentinel; owner[j]: the row matched to column j.
    const double infinity = std::numeric_limits<double>::infinity();
    std::vector<double> u(static_cast<std::size_t>(n) + 1), v(static_cast<std::size_t>(n) + 1);
    std::vector<int> owner(static_cast<std::size_t>(n) + 1), way(static_cast<std::size_t>(n) + 1);
    const auto at = [](auto& x, int i) -> auto&
    {
        return x[static_cast<std::size_t>(i)];
    };
    for (int i = 1; i <= n; ++i) {
        at(owner, 0) = i;
        int j0 = 0;
        std::vector<double> slack(static_cast<std::size_t>(n) + 1, infinity);
        std::vector<char> used(static_cast<std::size_t>(n) + 1, 0);
        do {  // grow an alternating tree from row i until it reaches a free column
            at(used, j0) = 1;
            const int i0 = at(owner, j0);
            double delta = infinity;
            int j1 = 0;
            for (int j = 1; j <= n; ++j) {
                if (at(used, j)) continue;
                const double reduced = cost(i0 - 1, j - 1) - at(u, i0) - at(v, j);
                if (reduced < at(slack, j)) at(slack, j) = reduced, at(way, j) = j0;
                if (at(slack, j) < delta) delta = at(slack, j), j1 = j;
            }
            for (int j = 0; j <= n; ++j)
                if (at(used, j))
                    at(u, at(owner, j)) += delta, at(v, j) -= delta;
                else
                    at(slack, j) -= delta;
            j0 = j1;
        } while (at(owner, j0) != 0);
        do {  // augment along the path
            const int j1 = at(way, j0);
            at(owner, j0) = at(owner, j1);
            j0 = j1;
        } while (j0 != 0);
    }
    std::vector<int> column(static_cast<std::size_t>(rows), -1);
    for (int j = 1; j <= n; ++j)
        if (at(owner, j) <= rows && j <= cols) column[static_cast<std::size_t>(at(owner, j) - 1)] = j - 1;
    return column;
}

std::vector<SpinMode> campbell(const Model& model, const std::vector<double>& omegas, Axial axial, double theta,
                               const Control* control, const std::function<void()>& check, Frame frame)
{
    std::vector<std::vector<SpinMode>> at_rate;  // per rate of omegas, its modes by frequency
    for (const double omega : omegas) {
        if (check) check();
        std::vector<SpinMode>& rate = at_rate.emplace_back();
        int number = 0;
        for (NaturalMode& mode : modes_at(model, omega, axial, theta, control, frame))
            rate.push_back({omega, ++number, std::move(mode), "", std::numeric_limits<double>::quiet_NaN()});
    }
    // Tracked in increasing omega: each rate's modes paired with the previous rate's by their MACs; a mode left
    // unpaired begins a line labelled by its kind and how many lines of that kind began before it.
    std::vector<std::size_t> order(omegas.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return omegas[a] < omegas[b]; });
    std::map<std::string, int> lines_of_kind;
    const std::vector<SpinMode>* previous = nullptr;
    for (const std::size_t k : order) {
        std::vector<SpinMode>& current = at_rate[k];
        if (previous != nullptr) {
            Eigen::MatrixXd score(static_cast<Eigen::Index>(previous->size()),
                                  static_cast<Eigen::Index>(current.size()));
            for (std::size_t i = 0; i < previous->size(); ++i)
                for (std::size_t j = 0; j < current.size(); ++j)
                    score(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
                        mac((*previous)[i].mode, current[j].mode);
            const std::vector<int> paired = best_assignment(score);
            for (std::size_t i = 0; i < paired.size(); ++i) {
                if (paired[i] < 0) continue;  // the line ends here
                SpinMode& next = current[static_cast<std::size_t>(paired[i])];
                next.label = (*previous)[i].label;
                next.mac = score(static_cast<Eigen::Index>(i), paired[i]);
            }
        }
        for (SpinMode& m : current)
            if (m.label.empty()) m.label = m.mode.kind + " " + std::to_string(++lines_of_kind[m.mode.kind]);
        previous = &current;
    }
    std::vector<SpinMode> rows;
    for (std::vector<SpinMode>& rate : at_rate) std::move(rate.begin(), rate.end(), std::back_inserter(rows));
    return rows;
}

namespace {

/// How critical_speeds finds a line's modes at a rate it tries: the model, and what modes_at takes.
struct CrossingSearch {
    const Model& model;
    Axial axial;
    double theta;
    const Control* control;
    const std::function<void()>& check;
    Frame frame;

    /// The rate in [a.omega, b.omega] where the line of modes a, b (consecutive rates) meets n Omega, if it does;
    /// first: a is the line's first rate (a meeting at a belongs to the interval before it otherwise).
    std::optional<double> operator()(const SpinMode& a, const SpinMode& b, int n, bool first) const;
};

std::optional<double> CrossingSearch::operator()(const SpinMode& a, const SpinMode& b, int n, bool first) const
{
    // A line that passes to a mode of another shape between a and b (their MAC 1/2 or less: a cluster
    // of nearly equal eigenvalues, the slow roots of overdamped modes about -1/beta) follows no one mode
    // there: its change of sign is between two modes, not a crossing of one.
    if (!(b.mac > followed_mac)) return std::nullopt;
    // Nearly critically damped at both rates: the damped frequency of so nearly defective a pair is fixed
    // by the eigenvalues only to about the square root of round-off of |lambda| (1e-5 of it), and lies
    // in a cluster of the overdamped modes' roots, so no crossing with it can be refined; nor does a
    // mode so damped resonate.
    if (a.mode.damping_ratio > nearly_critical && b.mode.damping_ratio > nearly_critical) return std::nullopt;
    double lo = a.omega, hi = b.omega;
    double g_lo = a.mode.rad_s - n * lo, g_hi = b.mode.rad_s - n * hi;
    // A mode of frequency 0 (overdamped or divergent) meets no excitation line: it lies below every
    // line n Omega > 0, and at rest, where the line is 0 as well, it is below too, not on it (a
    // critical speed is where a mode that oscillates has the line's frequency). Its gap at rest is 0 by
    // the formula: that end counts as below, with no value, and the bracket is halved until it has one.
    const bool below_at_rest = a.mode.rad_s == 0.0 && g_lo == 0.0;
    if (g_lo == 0.0 && !below_at_rest && !first) return std::nullopt;  // met at a, the previous interval's end
    const double sign_lo = below_at_rest ? -1.0 : g_lo;
    if (!(sign_lo * g_hi <= 0.0) || (sign_lo == 0.0 && g_hi == 0.0)) return std::nullopt;
    // The line's eigenvalue and shape at the bracket's ends: the next rate's is predicted between them.
    std::complex<double> l_lo = eigenvalue(a.mode), l_hi = eigenvalue(b.mode);
    const Eigen::VectorXcd *shape_lo = &a.mode.shape, *shape_hi = &b.mode.shape;
    std::deque<NaturalMode> tried;  // the modes found inside the bracket (the ends' shapes point here)
    // The mode's frequency minus the excitation's at omega, the mode there being the line's: the mode
    // nearest the eigenvalue interpolated between the bracket's ends (mode_near, one factorization),
    // taken when its MAC with the line's mode at a is above 1/2 (then no other mode's is as large); else,
    // under control, and at a periodic spin (Floquet's modes), the mode of largest MAC among all the modes
    // there.
    const auto gap = [&](double omega) {
        if (check) check();
        const double t = hi > lo ? (omega - lo) / (hi - lo) : 0.5;
        std::optional<NaturalMode> near;
        if (control == nullptr && unsteady_spin(model.key(), model.parameters(), omega).empty() &&
            !multiblade(model, control, frame))
            near = ModesNear(model, omega, axial, theta)
                       .line_mode(l_lo + t * (l_hi - l_lo), t < 0.5 ? *shape_lo : *shape_hi, a.mode.shape);
        if (!near) {
            double best = -1.0;
            for (NaturalMode& m : modes_at(model, omega, axial, theta, control, frame))
                if (const double x = mac(a.mode, m); x > best) best = x, near = std::move(m);
        }
        tried.push_back(std::move(*near));
        return tried.back().rad_s - n * omega;
    };
    // Regula falsi with Illinois' halving of the stale end's value: superlinear, and never leaves the
    // bracket.
    double omega = g_lo == 0.0 && !below_at_rest ? lo : hi;
    bool halving = below_at_rest && g_hi != 0.0;  // the low end has no value yet
    int stale = 0;
    for (int iteration = 0; iteration < 100 && (g_lo != 0.0 || halving) && g_hi != 0.0; ++iteration) {
        omega = halving ? 0.5 * (lo + hi) : (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
        if (hi - lo <= 1e-10 * std::max(1.0, std::abs(omega))) break;
        const double g = gap(omega);
        if (std::abs(g) <= 1e-13 * std::max(1.0, n * omega)) {  // the eigenvalues' round-off
            halving = false;
            break;
        }
        const NaturalMode& found = tried.back();
        if ((g < 0.0) != (g_hi < 0.0)) {  // on the low end's side (the ends' signs differ)
            lo = omega, g_lo = g, l_lo = eigenvalue(found), shape_lo = &found.shape;
            halving = false;
            if (stale == -1) g_hi /= 2.0;
            stale = -1;
        } else {
            hi = omega, g_hi = g, l_hi = eigenvalue(found), shape_hi = &found.shape;
            if (stale == 1) g_lo /= 2.0;
            stale = 1;
        }
    }
    // Halved onto rest with the mode above the line at every rate tried: it leaves rest above the
    // line, and never meets it in this interval.
    if (halving) return std::nullopt;
    return omega;
}

}  // namespace

std::vector<CriticalSpeed> critical_speeds(const Model& model, const std::vector<SpinMode>& rows,
                                           const std::vector<int>& harmonics, Axial axial, double theta,
                                           const Control* control, const std::function<void()>& check, Frame frame)
{
    // Each line's rows in increasing omega.
    std::map<std::string, std::vector<const SpinMode*>> lines;
    for (const SpinMode& r : rows) lines[r.label].push_back(&r);
    const CrossingSearch crossing{model, axial, theta, control, check, frame};
    std::vector<CriticalSpeed> speeds;
    for (auto& [label, line] : lines) {
        std::stable_sort(line.begin(), line.end(),
                         [](const SpinMode* a, const SpinMode* b) { return a->omega < b->omega; });
        for (const int n : harmonics)
            for (std::size_t i = 0; i + 1 < line.size(); ++i)
                if (const std::optional<double> omega = crossing(*line[i], *line[i + 1], n, i == 0))
                    speeds.push_back({label, n, *omega, n * *omega});
    }
    std::sort(speeds.begin(), speeds.end(), [](const CriticalSpeed& x, const CriticalSpeed& y) {
        return std::tie(x.omega, x.harmonic, x.label) < std::tie(y.omega, y.harmonic, y.label);
    });
    return speeds;
}

double frequency_unit(const Parameters& p)
{
    return std::sqrt(p.E * p.I / (p.rho * p.S * std::pow(p.L, 4)));
}

void classify_mode(const Model& model, const Eigen::MatrixXd& M, const Eigen::MatrixXd& U, const std::vector<int>& R,
                   const Eigen::VectorXcd& rates, bool overdamped, NaturalMode& mode)
{
    mode.kind = overdamped ? overdamped_kind : mode_kind(dominant_field(model, M, R, rates), model.key());
    mode.shape = weighted_shape(U, rates);
}

}  // namespace hubbeam
