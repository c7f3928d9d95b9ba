// The linearization about a periodic motion (docs/model.md section 10.1): under weight in the plane of rotation a
// spin at a constant rate has no steady state, and its modes are Floquet's. The periodic motion by harmonic balance,
// the monodromy matrix by a commutator-free Magnus integrator, the Floquet exponents and the harmonic that fixes each
// frequency.
#include <hubbeam/linearize.hpp>
#include <hubbeam/shortest.hpp>

#include "analysis/modal_coordinates.hpp"
#include "linalg/eigen_solvers.hpp"
#include "linalg/factorizations.hpp"
#include "models/modal_damping.hpp"
#include "models/model_operations.hpp"
#include "terms.hpp"

#include <unsupported/Eigen/FFT>
#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>

namespace hubbeam {

namespace {

using cd = std::complex<double>;

/// The coordinates a periodic motion moves: every elastic one (the hub turns at the constant rate, its angle no
/// degree of freedom under either drive).
std::vector<int> moving_coordinates(const Model& model)
{
    std::vector<int> R(static_cast<std::size_t>(model.nq() - model.coordinates().first_elastic()));
    std::iota(R.begin(), R.end(), model.coordinates().first_elastic());
    return R;
}

/// The model's q, qd and drive at time t of a spin at omega, the moving coordinates R at qR, qdR: theta = omega t,
/// theta_dot = omega, theta_ddot = 0 (a prescribed drive's inputs; a torque drive's q[0] and qd[0]).
void fill_state(bool torque, double omega, double t, const std::vector<int>& R, const double* qR, const double* qdR,
                std::vector<double>& q, std::vector<double>& qd, HubInput& u)
{
    u = HubInput{};
    if (torque) {
        q[0] = omega * t;
        qd[0] = omega;
    } else {
        u.theta_dot = omega;
        u.theta = omega * t;
    }
    for (std::size_t i = 0; i < R.size(); ++i) {
        q[static_cast<std::size_t>(R[i])] = qR[i];
        qd[static_cast<std::size_t>(R[i])] = qdR[i];
    }
}

/// X's entries at rows x cols.
Eigen::MatrixXd block_of(const Eigen::MatrixXd& X, const std::vector<int>& rows, const std::vector<int>& cols)
{
    Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (std::size_t j = 0; j < cols.size(); ++j)
            out(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = X(rows[i], cols[j]);
    return out;
}

/// sum_j dM_ij/dq_k v_j (nq x nq): the model's exact product where it has one, zero for a constant M, else central
/// differences of M v.
Eigen::MatrixXd mass_derivative_product(const Model& model, const HubInput& u, const std::vector<double>& q,
                                        const std::vector<double>& v)
{
    const int n = model.nq();
    if (model.mass_is_constant()) return Eigen::MatrixXd::Zero(n, n);
    if (const ExactJacobian* exact = model.jacobian()) {
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> dMv(n, n);
        exact->mass_q_product(u, q.data(), v.data(), dMv.data());
        return dMv;
    }
    const Eigen::Map<const Eigen::VectorXd> vv(v.data(), n);
    Eigen::MatrixXd out(n, n);
    for (int k = 0; k < n; ++k) {
        const double h = 6e-6 * std::max(1.0, std::abs(q[static_cast<std::size_t>(k)]));
        std::vector<double> plus = q, minus = q;
        plus[static_cast<std::size_t>(k)] += h;
        minus[static_cast<std::size_t>(k)] -= h;
        out.col(k) = (mass_at(model, u, plus) - mass_at(model, u, minus)) * vv / (2.0 * h);
    }
    return out;
}

/// The Fourier differentiation matrix of 2H + 1 equally spaced samples over one period of a spin at omega: the
/// rates at the samples of their trigonometric interpolant (Trefethen, Spectral Methods in MATLAB, ch. 3: odd count).
Eigen::MatrixXd fourier_derivative(int count, double omega)
{
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(count, count);
    for (int j = 0; j < count; ++j)
        for (int l = 0; l < count; ++l)
            if (j != l) {
                const int d = j - l;
                D(j, l) = omega * 0.5 * ((d % 2 == 0) ? 1.0 : -1.0) / std::sin(M_PI * d / count);
            }
    return D;
}

/// The Fourier coefficients c_0 .. c_H of samples (columns, 2H + 1 over a period), q(t) = c_0 + 2 Re sum c_k e^{ikwt}.
Eigen::MatrixXcd coefficients_of(const Eigen::MatrixXd& samples)
{
    const auto count = samples.cols(), H = (count - 1) / 2;
    Eigen::MatrixXcd c = Eigen::MatrixXcd::Zero(samples.rows(), H + 1);
    for (Eigen::Index k = 0; k <= H; ++k)
        for (Eigen::Index j = 0; j < count; ++j)
            c.col(k) += samples.col(j).cast<cd>() *
                        std::polar(1.0 / static_cast<double>(count), -2.0 * M_PI * static_cast<double>(k * j) /
                                                                         static_cast<double>(count));
    c.col(0) = c.col(0).real().cast<cd>();
    return c;
}

/// The steady state of the spin without the weight in the plane, the harmonic balance's start: Newton on the moving
/// rows of the forces averaged over four angles a quarter turn apart, with the rates 0. The weight's terms are
/// linear in sin theta and cos theta (docs/model.md section 11.3) and cancel in that average, so that the average is
/// the spin's forces without them, whatever the order.
Eigen::VectorXd steady_without_weight(const Model& model, double omega, bool torque, const std::vector<int>& R)
{
    const auto r = static_cast<Eigen::Index>(R.size());
    const int n = model.nq();
    Eigen::VectorXd x = Eigen::VectorXd::Zero(r);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(r);
    std::vector<double> q(static_cast<std::size_t>(n)), qd(q), Q(q);
    HubInput u;
    double previous = HUGE_VAL;
    for (int iteration = 0; iteration < 50 && r > 0; ++iteration) {
        Eigen::VectorXd F = Eigen::VectorXd::Zero(r);
        Eigen::MatrixXd K = Eigen::MatrixXd::Zero(r, r);
        for (int a = 0; a < 4; ++a) {
            // A quarter turn apart in time at the spin's rate: theta = omega t.
            fill_state(torque, omega, 0.5 * M_PI * a / omega, R, x.data(), zero.data(), q, qd, u);
            model.forces(u, q.data(), qd.data(), Q.data());
            for (Eigen::Index i = 0; i < r; ++i) F[i] += 0.25 * Q[static_cast<std::size_t>(R[static_cast<std::size_t>(i)])];
            K += 0.25 * block_of(force_q_jacobian(model, u, q, qd), R, R);
        }
        const Eigen::VectorXd dx = K.partialPivLu().solve(-F);
        if (!dx.allFinite()) throw std::runtime_error("the steady state of the spin without its weight has no solution");
        x += dx;
        const double step = dx.cwiseAbs().maxCoeff(), size = x.cwiseAbs().maxCoeff();
        if (step <= 1e-14 * std::max(size, 1e-300) || (step <= 1e-10 * size && step >= 0.5 * previous)) break;
        previous = step;
    }
    return x;
}

/// The equations of motion at the samples Z of a periodic motion (r x count, column j at t_j = j T / count, count
/// = 2H + 1 odd), their rates and accelerations those of the samples' trigonometric interpolant: the residuals
/// M(q_j) qdd_j - Q(t_j, q_j, qd_j) over the moving rows (harmonic balance by collocation), and their derivatives.
class Balance {
public:
    Balance(const Model& model, double omega, bool torque, const std::vector<int>& R, Eigen::Index count)
        : model_(model), omega_(omega), torque_(torque), R_(R), r_(static_cast<Eigen::Index>(R.size())),
          count_(count), D_(fourier_derivative(static_cast<int>(count), omega)), D2_(D_ * D_)
    {
    }

    /// The residuals at Z (r x count); with blocks, each sample's K_j = dM/dq qdd_j - dQ/dq, M_j and C_j = dQ/dqd
    /// over the moving coordinates. Returns the size of the terms the residuals are made of, against which they are
    /// round-off when converged: the largest |M qdd| and |Q|, and the largest |K_j| |q| (the elastic forces' sum).
    double residuals(const Eigen::MatrixXd& Z, Eigen::MatrixXd& out, std::vector<Eigen::MatrixXd>* K = nullptr,
                     std::vector<Eigen::MatrixXd>* M = nullptr, std::vector<Eigen::MatrixXd>* C = nullptr) const
    {
        const int n = model_.nq();
        const Eigen::MatrixXd V = Z * D_.transpose(), A = Z * D2_.transpose();
        std::vector<double> q(static_cast<std::size_t>(n), 0.0), qd(q), Q(q), qdd(q);
        HubInput u;
        out.resize(r_, count_);
        double terms = 0.0;
        for (Eigen::Index j = 0; j < count_; ++j) {
            const Eigen::VectorXd v = V.col(j);
            fill_state(torque_, omega_, period() * static_cast<double>(j) / static_cast<double>(count_), R_,
                       Z.col(j).data(), v.data(), q, qd, u);
            model_.forces(u, q.data(), qd.data(), Q.data());
            const Eigen::MatrixXd MR = block_of(mass_at(model_, u, q), R_, R_);
            const Eigen::VectorXd Ma = MR * A.col(j);
            for (Eigen::Index i = 0; i < r_; ++i) {
                const double Qi = Q[static_cast<std::size_t>(R_[static_cast<std::size_t>(i)])];
                out(i, j) = Ma[i] - Qi;
                terms = std::max({terms, std::abs(Ma[i]), std::abs(Qi)});
            }
            if (K == nullptr) continue;
            std::fill(qdd.begin(), qdd.end(), 0.0);
            for (Eigen::Index i = 0; i < r_; ++i) qdd[static_cast<std::size_t>(R_[static_cast<std::size_t>(i)])] = A(i, j);
            const ForceJacobians J = force_jacobians(model_, u, q, qd);
            K->push_back(block_of(mass_derivative_product(model_, u, q, qdd) - J.q, R_, R_));
            M->push_back(MR);
            C->push_back(block_of(J.qd, R_, R_));
            terms = std::max(terms, K->back().cwiseAbs().maxCoeff() * Z.col(j).cwiseAbs().maxCoeff());
        }
        return terms;
    }

    /// The dense Jacobian of the residuals (stacked by sample) from the samples' blocks: delta_jl K_j + D2_jl M_j -
    /// D_jl C_j.
    Eigen::MatrixXd jacobian(const std::vector<Eigen::MatrixXd>& K, const std::vector<Eigen::MatrixXd>& M,
                             const std::vector<Eigen::MatrixXd>& C) const
    {
        Eigen::MatrixXd G = Eigen::MatrixXd::Zero(r_ * count_, r_ * count_);
        for (Eigen::Index j = 0; j < count_; ++j) {
            const auto js = static_cast<std::size_t>(j);
            G.block(j * r_, j * r_, r_, r_) += K[js];
            for (Eigen::Index l = 0; l < count_; ++l)
                G.block(j * r_, l * r_, r_, r_) += D2_(j, l) * M[js] - D_(j, l) * C[js];
        }
        return G;
    }

    double period() const { return 2.0 * M_PI / omega_; }

private:
    const Model& model_;
    double omega_;
    bool torque_;
    const std::vector<int>& R_;
    Eigen::Index r_, count_;
    Eigen::MatrixXd D_, D2_;
};

/// The mean of matrices.
Eigen::MatrixXd mean_of(const std::vector<Eigen::MatrixXd>& X)
{
    Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(X.front().rows(), X.front().cols());
    for (const Eigen::MatrixXd& x : X) sum += x;
    return sum / static_cast<double>(X.size());
}

/// Harmonic balance from the samples Z (r x count, column j at t_j = j T / count): the residuals of Balance driven
/// to round-off of their terms. First by the average system's Jacobian, which the DFT turns into one r x r matrix per
/// harmonic k, K - (k omega)^2 M - i k omega C (K, M, C averaged over the period): the full Jacobian differs from it
/// only by the coefficients' variation over the period (the weight's stiffness, small against the beam's, and the
/// motion's at order full), so that each step contracts the error by about that ratio, at the cost of r x r solves,
/// and where the harmonics' solves keep the round-off of a large steady deflection out of the small high harmonics.
/// Where a step contracts the error by less than half, Newton with the dense Jacobian of all samples. Returns the
/// steps taken and sets noise to the last step's size (the round-off of the motion where the steps stalled); throws
/// std::runtime_error where neither converges.
int balance(const Model& model, double omega, bool torque, const std::vector<int>& R, Eigen::MatrixXd& Z,
            double& noise)
{
    const Eigen::Index r = Z.rows(), count = Z.cols(), H = (count - 1) / 2;
    const Balance equations(model, omega, torque, R, count);
    const double period = equations.period();
    std::vector<Eigen::MatrixXd> K, M, C;
    Eigen::MatrixXd residual;
    double terms = equations.residuals(Z, residual, &K, &M, &C);
    // Converged where the residuals are round-off of their terms, or the steps stopped shrinking at round-off of
    // the motion. A motion that is nothing (a balanced rotor's hub at rest, a straight blade) has residuals and
    // steps of round-off alone: they are measured against the beam's length.
    const double length = model.parameters()[index(Param::L)];
    const auto converged = [&](double moved, double previous) {
        const double motion = Z.cwiseAbs().maxCoeff();
        noise = moved;
        return residual.cwiseAbs().maxCoeff() <= 1e-13 * terms || moved <= 1e-15 * std::max(motion, length) ||
               (moved <= 1e-8 * motion && moved >= 0.5 * previous);
    };
    // The average system's matrix at each harmonic, factored once.
    const Eigen::MatrixXcd Kc = mean_of(K).cast<cd>(), Mc = mean_of(M).cast<cd>(), Cc = mean_of(C).cast<cd>();
    std::vector<Eigen::PartialPivLU<Eigen::MatrixXcd>> harmonic;
    for (Eigen::Index k = 0; k <= H; ++k) {
        const double w = static_cast<double>(k) * omega;
        harmonic.emplace_back(Eigen::MatrixXcd(Kc - w * w * Mc - cd(0.0, w) * Cc));
    }
    double previous = HUGE_VAL;
    int steps = 0;
    for (; steps < 100; ++steps) {
        // The residuals' harmonics, each solved with its matrix, and the correction back at the samples.
        Eigen::MatrixXd dz = Eigen::MatrixXd::Zero(r, count);
        for (Eigen::Index k = 0; k <= H; ++k) {
            Eigen::VectorXcd rk = Eigen::VectorXcd::Zero(r);
            for (Eigen::Index j = 0; j < count; ++j)
                rk += residual.col(j).cast<cd>() * std::polar(1.0 / static_cast<double>(count),
                                                              -omega * static_cast<double>(k) * period *
                                                                  static_cast<double>(j) / static_cast<double>(count));
            const Eigen::VectorXcd xk = harmonic[static_cast<std::size_t>(k)].solve(-rk);
            for (Eigen::Index j = 0; j < count; ++j) {
                const cd e = std::polar(k == 0 ? 1.0 : 2.0, omega * static_cast<double>(k) * period *
                                                                static_cast<double>(j) / static_cast<double>(count));
                dz.col(j) += (xk * e).real();
            }
        }
        if (!dz.allFinite()) break;
        Z += dz;
        terms = equations.residuals(Z, residual);
        const double moved = dz.cwiseAbs().maxCoeff();
        if (converged(moved, previous)) return steps + 1;
        if (moved > 0.5 * previous) break;  // contracts too slowly: the coefficients vary too much over the period
        previous = moved;
    }
    // Newton with the dense Jacobian.
    previous = HUGE_VAL;
    for (int step = 1; step <= 30; ++step) {
        K.clear(), M.clear(), C.clear();
        equations.residuals(Z, residual, &K, &M, &C);
        const Eigen::VectorXd dz =
            equations.jacobian(K, M, C).partialPivLu().solve(-Eigen::Map<const Eigen::VectorXd>(residual.data(), r * count));
        if (!dz.allFinite()) break;
        Z += Eigen::Map<const Eigen::MatrixXd>(dz.data(), r, count);
        terms = equations.residuals(Z, residual);
        const double moved = dz.cwiseAbs().maxCoeff();
        if (converged(moved, previous)) return steps + step;
        previous = moved;
    }
    throw std::runtime_error("the periodic motion of the spin was not found (harmonic balance did not converge)");
}

/// The variational equations x' = J(t) x over the orbit's coordinates and their rates, J = [[0, I], [A, B]] with
/// A = M^-1 (dQ/dq - dM/dq qdd) and B = M^-1 dQ/dqd over the orbit's coordinates, integrated in coordinates where J is
/// well scaled: y = T^-1 x with T = diag(P W^-1, P), P the undamped modes of the average system (the symmetric part
/// of its stiffness against M at t = 0, M-orthonormal) and W their frequencies. There J = [[0, W], [S A P W^-1,
/// S B P]] (S = P^T M) is near [[0, W], [-W, C]]: its norm is the highest frequency, where in q and qd it is that
/// frequency's square (and its units mixed), and the matrix exponential's squarings of so large and non-normal a
/// matrix would lose six digits and more. The multipliers do not depend on the coordinates.
class Variational {
public:
    Variational(const Model& model, const PeriodicOrbit& orbit) : model_(model), orbit_(orbit)
    {
        const std::vector<int>& R = orbit.coordinates;
        r_ = static_cast<Eigen::Index>(R.size());
        if (model.mass_is_constant()) {
            std::vector<double> q, qd;
            HubInput u;
            orbit.state(0.0, q, qd, u);
            constant_mass_ = std::make_unique<Eigen::LLT<Eigen::MatrixXd>>(factor(block_of(mass_at(model, u, q), R, R)));
        }
        // The average of A over the period at 16 instants and the mass at t = 0: the undamped modes of the average.
        std::vector<double> q, qd;
        HubInput u;
        orbit.state(0.0, q, qd, u);
        mass_ = block_of(mass_at(model, u, q), R, R);
        Eigen::MatrixXd A = Eigen::MatrixXd::Zero(r_, r_), B = A;
        for (int j = 0; j < 16; ++j) {
            Eigen::MatrixXd Aj, Bj;
            blocks(orbit.period * j / 16.0, Aj, Bj);
            A += Aj / 16.0;
            B += Bj / 16.0;
        }
        const Eigen::MatrixXd K = -mass_ * A;
        const SymmetricPairs modes = symmetric_pairs(0.5 * (K + K.transpose()), mass_);
        if (!modes.converged) throw std::runtime_error("the modes of the average system did not converge");
        P_ = modes.vectors;
        const Eigen::VectorXd w2 = modes.values.cwiseAbs();
        const double floor = std::max({orbit.omega, 1e-6 * std::sqrt(w2.maxCoeff()), 1e-300});
        w_ = w2.cwiseSqrt().cwiseMax(floor);
        S_ = P_.transpose() * mass_;
        average_ = scaled(A, B);
    }

    Eigen::Index size() const { return 2 * r_; }
    /// J at the orbit's time t, in the scaled coordinates.
    Eigen::MatrixXd at(double t) const
    {
        Eigen::MatrixXd A, B;
        blocks(t, A, B);
        return scaled(A, B);
    }
    /// J averaged over the period at 16 instants (exact for its harmonics up to 15), scaled: whose eigenvalues say how
    /// fast the modes that one revolution can resolve turn.
    const Eigen::MatrixXd& average() const { return average_; }
    /// A state (column) in the scaled coordinates back in q and qd: T y.
    Eigen::MatrixXcd original(const Eigen::MatrixXcd& y) const
    {
        Eigen::MatrixXcd x(2 * r_, y.cols());
        x.topRows(r_) = P_ * (w_.cwiseInverse().asDiagonal() * y.topRows(r_));
        x.bottomRows(r_) = P_ * y.bottomRows(r_);
        return x;
    }
    /// A matrix over the scaled coordinates in q and qd: T X T^-1.
    Eigen::MatrixXd original_matrix(const Eigen::MatrixXd& X) const
    {
        Eigen::MatrixXd T = Eigen::MatrixXd::Zero(2 * r_, 2 * r_), inverse = T;
        T.topLeftCorner(r_, r_) = P_ * w_.cwiseInverse().asDiagonal();
        T.bottomRightCorner(r_, r_) = P_;
        inverse.topLeftCorner(r_, r_) = w_.asDiagonal() * S_;
        inverse.bottomRightCorner(r_, r_) = S_;
        return T * X * inverse;
    }
    /// M over the orbit's coordinates at t = 0.
    const Eigen::MatrixXd& mass() const { return mass_; }

    /// The transition matrices Phi(t_n) in the scaled coordinates, t_n = n T / N for n = 0 .. N (Phi(t_0) = I,
    /// Phi(t_N) the monodromy matrix; with all false Phi(t_N) alone), by the fourth-order commutator-free Magnus
    /// integrator (Blanes and Moan 2006): per step exp(h (a2 J1 + a1 J2)) exp(h (a1 J1 + a2 J2)), J1 and J2 at the
    /// step's Gauss points t_n + (1/2 -+ sqrt(3)/6) h, a1,2 = 1/4 +- sqrt(3)/6. Exact for a constant J whatever the
    /// step, so that a mode of any frequency and any damping is propagated as it is, and of fourth order in h where
    /// J varies over the period.
    std::vector<Eigen::MatrixXd> transition(int steps, bool all) const
    {
        const double h = orbit_.period / steps, c = std::sqrt(3.0) / 6.0, a1 = 0.25 + c, a2 = 0.25 - c;
        std::vector<Eigen::MatrixXd> phi;
        phi.reserve(all ? static_cast<std::size_t>(steps) + 1 : 1);
        phi.push_back(Eigen::MatrixXd::Identity(2 * r_, 2 * r_));
        for (int s = 0; s < steps; ++s) {
            const double t = orbit_.period * s / steps;
            const Eigen::MatrixXd J1 = at(t + (0.5 - c) * h), J2 = at(t + (0.5 + c) * h);
            const Eigen::MatrixXd first = (h * (a1 * J1 + a2 * J2)).exp(), second = (h * (a2 * J1 + a1 * J2)).exp();
            Eigen::MatrixXd next = second * (first * phi.back());
            if (!next.allFinite())
                throw std::runtime_error("the variational equations over the periodic motion did not integrate");
            if (all)
                phi.push_back(std::move(next));
            else
                phi.back() = std::move(next);
        }
        return phi;
    }

private:
    static Eigen::LLT<Eigen::MatrixXd> factor(const Eigen::MatrixXd& M)
    {
        Eigen::LLT<Eigen::MatrixXd> llt(M);
        if (llt.info() != Eigen::Success)
            throw std::runtime_error("the mass matrix on the periodic motion is not positive definite");
        return llt;
    }

    /// A and B at the orbit's time t.
    void blocks(double t, Eigen::MatrixXd& A, Eigen::MatrixXd& B) const
    {
        const std::vector<int>& R = orbit_.coordinates;
        std::vector<double> q, qd, qdd;
        HubInput u;
        orbit_.state(t, q, qd, u, &qdd);
        const ForceJacobians J = force_jacobians(model_, u, q, qd);
        const Eigen::LLT<Eigen::MatrixXd> varying =
            constant_mass_ ? Eigen::LLT<Eigen::MatrixXd>() : factor(block_of(mass_at(model_, u, q), R, R));
        const Eigen::LLT<Eigen::MatrixXd>& llt = constant_mass_ ? *constant_mass_ : varying;
        A = llt.solve(block_of(J.q - mass_derivative_product(model_, u, q, qdd), R, R));
        B = llt.solve(block_of(J.qd, R, R));
    }

    /// T^-1 [[0, I], [A, B]] T.
    Eigen::MatrixXd scaled(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) const
    {
        Eigen::MatrixXd X = Eigen::MatrixXd::Zero(2 * r_, 2 * r_);
        X.topRightCorner(r_, r_) = w_.asDiagonal();
        X.bottomLeftCorner(r_, r_) = S_ * A * P_ * w_.cwiseInverse().asDiagonal();
        X.bottomRightCorner(r_, r_) = S_ * B * P_;
        return X;
    }

    const Model& model_;
    const PeriodicOrbit& orbit_;
    Eigen::Index r_ = 0;
    std::unique_ptr<Eigen::LLT<Eigen::MatrixXd>> constant_mass_;
    Eigen::MatrixXd mass_, P_, S_, average_;
    Eigen::VectorXd w_;
};

/// The smallest multiplier whose mode is reported (it decays by 1e10 in one revolution), and the one at and above
/// which every mode must be resolved before the step count is accepted.
constexpr double smallest_multiplier = 1e-10, resolved_multiplier = 1e-6;
/// The least |mu| T |lambda| of a mode reported: the round-off of Phi(T) (1e-15 of its size) moves its exponent by
/// 1e-9 of |lambda| or less.
constexpr double resolution = 1e-6;
/// Two step counts agree on an exponent to this fraction of its size (or of the spin rate, the larger).
constexpr double exponent_agreement = 1e-9;
/// The most integration steps over a period, whatever the state's size.
constexpr int max_steps = 16384;

/// A candidate mode of one step count: its multiplier, exponent, harmonic and its periodic eigenvector's harmonic
/// of the rates (the shape), from the transition matrices phi over one period.
struct Candidate {
    cd multiplier, exponent;
    int harmonic = 0;
    double rad_s = 0.0;  // Im(exponent) + harmonic omega (a real multiplier's taken >= 0)
    Eigen::VectorXcd vector, rates;  // the eigenvector v of Phi(T), and the rates' k-th harmonic of p(t)
};

/// The dominant harmonic of the periodic eigenvector p(t_n) = exp(-lambda t_n) Phi(t_n) v, n = 0 .. N - 1 (phi and v
/// in the scaled coordinates, p taken back to q and qd): the harmonic k in (-N/2, N/2] whose |DFT|^2 summed over the
/// displacement coordinates q (unweighted) is largest (ties: the smaller |k|, then k > 0); and the rates' DFT at that
/// harmonic.
int dominant_harmonic(const Variational& system, const std::vector<Eigen::MatrixXd>& phi, cd lambda, double period,
                      const Eigen::VectorXcd& v, Eigen::VectorXcd& rates)
{
    const auto N = static_cast<int>(phi.size()) - 1;
    const Eigen::Index r = system.size() / 2;
    Eigen::MatrixXcd y(system.size(), N);  // p(t_n) in the scaled coordinates, column n
    for (int n = 0; n < N; ++n) y.col(n) = std::exp(-lambda * (period * n / N)) * (phi[static_cast<std::size_t>(n)] * v);
    const Eigen::MatrixXcd p = system.original(y);
    Eigen::FFT<double> fft;
    std::vector<double> energy(static_cast<std::size_t>(N), 0.0);
    std::vector<cd> samples(static_cast<std::size_t>(N)), spectrum;
    std::vector<std::vector<cd>> spectra(static_cast<std::size_t>(2 * r));
    for (Eigen::Index i = 0; i < 2 * r; ++i) {
        for (int n = 0; n < N; ++n) samples[static_cast<std::size_t>(n)] = p(i, n);
        fft.fwd(spectrum, samples);  // spectrum[m] = sum_n p_n e^{-2 pi i m n / N}: harmonic m (mod N)
        if (i < r)
            for (int m = 0; m < N; ++m) energy[static_cast<std::size_t>(m)] += std::norm(spectrum[static_cast<std::size_t>(m)]);
        spectra[static_cast<std::size_t>(i)] = spectrum;
    }
    const auto signed_harmonic = [N](int m) { return m > N / 2 ? m - N : m; };
    int best = 0;
    for (int m = 1; m < N; ++m) {
        const double e = energy[static_cast<std::size_t>(m)], b = energy[static_cast<std::size_t>(best)];
        const int k = signed_harmonic(m), kb = signed_harmonic(best);
        if (e > b || (e == b && (std::abs(k) < std::abs(kb) || (std::abs(k) == std::abs(kb) && k > kb)))) best = m;
    }
    rates.resize(r);
    for (Eigen::Index i = 0; i < r; ++i)
        rates[i] = spectra[static_cast<std::size_t>(r + i)][static_cast<std::size_t>(best)] / static_cast<double>(N);
    return signed_harmonic(best);
}

/// The candidates of the transition matrices phi: the multipliers of size smallest_multiplier or more, each with its
/// exponent, harmonic, frequency and eigenvector (in q and qd); multipliers gets all of them.
std::vector<Candidate> candidates(const Variational& system, const std::vector<Eigen::MatrixXd>& phi, double omega,
                                  double period, Eigen::VectorXcd& multipliers)
{
    EigenPairs eig = eigen_pairs(phi.back());
    if (!eig.converged) throw std::runtime_error("the eigenvalues of the monodromy matrix did not converge");
    multipliers = eig.values;
    const Eigen::MatrixXcd vectors = std::move(eig.vectors);
    std::vector<Candidate> out;
    for (Eigen::Index k = 0; k < multipliers.size(); ++k) {
        const cd mu = multipliers[k];
        if (!(std::abs(mu) >= smallest_multiplier)) continue;
        Candidate c;
        c.multiplier = mu;
        c.exponent = std::log(mu) / period;  // the principal branch: Im in (-omega/2, omega/2]
        c.vector = system.original(vectors.col(k));
        c.harmonic = dominant_harmonic(system, phi, c.exponent, period, vectors.col(k), c.rates);
        c.rad_s = c.exponent.imag() + c.harmonic * omega;
        // A real multiplier's eigenvector is real: its harmonics k and -k (about Im(exponent)) weigh alike, and its one
        // mode has the frequency of either, taken >= 0. Of a conjugate pair, the mode of frequency > 0.
        if (mu.imag() == 0.0) {
            if (c.rad_s < 0.0) {
                c.harmonic = -c.harmonic - (mu.real() < 0.0 ? 1 : 0);
                c.rates = c.rates.conjugate().eval();
            }
            c.rad_s = std::abs(c.rad_s);
        }
        if (c.rad_s < 0.0 || (c.rad_s == 0.0 && mu.imag() != 0.0)) continue;
        // Resolved where the round-off of Phi(T), 1e-15 of its size, moves the exponent by 1e-9 of the mode's
        // |lambda| at most: d lambda = d mu / (mu T).
        if (std::abs(mu) * period * std::abs(cd(c.exponent.real(), c.rad_s)) < resolution) continue;
        out.push_back(std::move(c));
    }
    return out;
}

/// The candidate's complex frequency: growth + i rad_s.
cd eigenvalue_of(const Candidate& c)
{
    return {c.exponent.real(), c.rad_s};
}

}  // namespace

void PeriodicOrbit::state(double t, std::vector<double>& q, std::vector<double>& qd, HubInput& u,
                          std::vector<double>* qdd) const
{
    const auto r = static_cast<Eigen::Index>(coordinates.size());
    Eigen::VectorXd x = coefficients.col(0).real(), v = Eigen::VectorXd::Zero(r), a = Eigen::VectorXd::Zero(r);
    for (Eigen::Index k = 1; k < coefficients.cols(); ++k) {
        const double w = static_cast<double>(k) * omega;
        const cd e = std::polar(2.0, w * t);
        const Eigen::VectorXcd ce = coefficients.col(k) * e;
        x += ce.real();
        v += (ce * cd(0.0, w)).real();
        a -= w * w * ce.real();
    }
    q.assign(static_cast<std::size_t>(nq), 0.0);
    qd.assign(static_cast<std::size_t>(nq), 0.0);
    fill_state(torque, omega, t, coordinates, x.data(), v.data(), q, qd, u);
    if (qdd != nullptr) {
        qdd->assign(static_cast<std::size_t>(nq), 0.0);
        for (Eigen::Index i = 0; i < r; ++i) (*qdd)[static_cast<std::size_t>(coordinates[static_cast<std::size_t>(i)])] = a[i];
    }
}

PeriodicOrbit periodic_orbit(const Model& model, double omega)
{
    if (!(omega > 0.0) || !std::isfinite(omega))
        throw std::invalid_argument("a periodic motion needs a spin rate > 0, got " + shortest(omega));
    PeriodicOrbit orbit;
    orbit.omega = omega;
    orbit.period = 2.0 * M_PI / omega;
    orbit.coordinates = moving_coordinates(model);
    orbit.nq = model.nq();
    orbit.torque = model.key().drive == Drive::torque;
    const auto r = static_cast<Eigen::Index>(orbit.coordinates.size());
    const Eigen::VectorXd start = steady_without_weight(model, omega, orbit.torque, orbit.coordinates);
    // Harmonic balance with H = 6, 12, 24, ..., each started from the last one's interpolant, until the highest
    // harmonics hold round-off of the motion: the weight's once-per-revolution load excites harmonics that decay
    // geometrically (the parametric coupling through the foreshortening), so a few suffice.
    Eigen::MatrixXd Z = start.replicate(1, 13);
    for (int H = 6;; H *= 2) {
        if (H > 6) {
            const auto count = 2 * H + 1;
            Eigen::MatrixXd finer(r, count);
            std::vector<double> q, qd;
            HubInput u;
            for (int j = 0; j < count; ++j) {
                orbit.state(orbit.period * j / count, q, qd, u);
                for (Eigen::Index i = 0; i < r; ++i) finer(i, j) = q[static_cast<std::size_t>(orbit.coordinates[static_cast<std::size_t>(i)])];
            }
            Z = finer;
        }
        double noise = 0.0;
        orbit.newton_steps = balance(model, omega, orbit.torque, orbit.coordinates, Z, noise);
        orbit.coefficients = coefficients_of(Z);
        const double size = orbit.coefficients.cwiseAbs().maxCoeff();
        const double top = orbit.coefficients.rightCols(2).cwiseAbs().maxCoeff();
        // Resolved where the highest harmonics are round-off of the motion, or of the solution's own round-off (the
        // residuals' round-off through an ill-conditioned stiffness: a fine mesh's).
        if (top <= std::max(1e-13 * size, 10.0 * noise) || size == 0.0) break;
        if (H >= 96)
            throw std::runtime_error("the periodic motion of the spin needs more than 96 harmonics (its highest holds " +
                                     shortest(top / size) + " of the motion)");
    }
    return orbit;
}

namespace {

/// The most steps of the finer count, 2N steps times the state's size cubed being the cost of their matrix
/// exponentials: 2048 steps of 68 states, and 256 whatever the size.
int most_steps(Eigen::Index r)
{
    const double size = static_cast<double>(2 * r);
    int most = 256;
    while (most < max_steps && 2.0 * most * size * size * size <= 2048.0 * 68.0 * 68.0 * 68.0) most *= 2;
    return most;
}

/// The average system's modes: how fast the modes that one revolution resolves turn (fastest), so that the steps
/// sample them; and where a budget of steps cannot, which modes are beyond the band the steps sample (their harmonics
/// are aliased there: such a mode is known by its shape, the average mode it resembles most).
struct AverageModes {
    Eigen::VectorXcd lambda;
    std::vector<Eigen::VectorXcd> shapes;  // weighted by the mass at t = 0, of unit length
    double fastest = 0.0;
};

/// A mode's shape from its rates: U rates of unit length.
Eigen::VectorXcd unit_shape(const Eigen::MatrixXd& U, const Eigen::VectorXcd& rates)
{
    const Eigen::VectorXcd w = U.triangularView<Eigen::Upper>() * rates;
    return w / std::max(w.norm(), 1e-300);
}

AverageModes average_modes(const Variational& system, const Eigen::MatrixXd& U, double period, Eigen::Index r)
{
    const EigenPairs average = eigen_pairs(system.average());
    if (!average.converged) throw std::runtime_error("the eigenvalues of the average system did not converge");
    AverageModes a{average.values, {}, 0.0};
    for (Eigen::Index k = 0; k < a.lambda.size(); ++k)
        if (std::exp(a.lambda[k].real() * period) >= smallest_multiplier)
            a.fastest = std::max(a.fastest, std::abs(a.lambda[k].imag()));
    const Eigen::MatrixXcd vectors = system.original(average.vectors);
    for (Eigen::Index k = 0; k < a.lambda.size(); ++k) a.shapes.push_back(unit_shape(U, vectors.col(k).tail(r)));
    return a;
}

/// The exponents of every multiplier of size smallest_multiplier or more (both of each conjugate pair).
std::vector<cd> exponents(const Eigen::VectorXcd& multipliers, double period)
{
    std::vector<cd> out;
    for (const cd mu : multipliers)
        if (std::abs(mu) >= smallest_multiplier) out.push_back(std::log(mu) / period);
    return out;
}

/// Which candidates lie in the band the steps sample: all, unless the fastest average mode turns faster than band;
/// then each candidate is paired with the average mode its shape resembles most (the assignment of largest summed
/// MAC), and left out where that mode turns faster than the band.
std::vector<char> in_band(const std::vector<Candidate>& now, const AverageModes& average, const Eigen::MatrixXd& U,
                          Eigen::Index r, double band)
{
    std::vector<char> in(now.size(), 1);
    if (average.fastest <= band) return in;
    Eigen::MatrixXd score(static_cast<Eigen::Index>(now.size()), average.lambda.size());
    for (std::size_t i = 0; i < now.size(); ++i) {
        const Eigen::VectorXcd a = unit_shape(U, now[i].vector.tail(r));
        for (Eigen::Index k = 0; k < average.lambda.size(); ++k)
            score(static_cast<Eigen::Index>(i), k) = std::norm(a.dot(average.shapes[static_cast<std::size_t>(k)]));
    }
    const std::vector<int> paired = best_assignment(score);
    for (std::size_t i = 0; i < now.size(); ++i)
        in[i] = paired[i] >= 0 && std::abs(average.lambda[paired[i]].imag()) <= band;
    return in;
}

/// Each in-band exponent of the finer count against the coarser count's nearest, modulo i omega (the harmonics are
/// the finer count's: the coarser's samples need not resolve them); resolved is false where one that matters (a
/// multiplier of resolved_multiplier or more) does not agree.
std::vector<char> agreeing(const std::vector<Candidate>& now, const std::vector<char>& in, const std::vector<cd>& coarse,
                           double omega, bool& resolved)
{
    std::vector<char> agrees(now.size(), 0);
    resolved = true;
    for (std::size_t i = 0; i < now.size(); ++i) {
        if (!in[i]) continue;
        const cd l = eigenvalue_of(now[i]);
        double nearest = HUGE_VAL;
        for (const cd exponent : coarse) {
            const cd d = exponent - now[i].exponent;
            nearest = std::min(nearest, std::abs(cd(d.real(), d.imag() - omega * std::round(d.imag() / omega))));
        }
        agrees[i] = nearest <= exponent_agreement * std::max(std::abs(l), omega);
        if (!agrees[i] && std::abs(now[i].multiplier) >= resolved_multiplier) resolved = false;
    }
    return agrees;
}

}  // namespace

FloquetAnalysis floquet(const Model& model, double omega, Axial axial)
{
    if (axial == Axial::quasi_static && model.coordinates().count(FieldKind::axial) > 0)
        throw std::invalid_argument("the Floquet analysis of a periodic spin needs dynamic axial coordinates "
                                    "(model.axial = \"dynamic\")");
    FloquetAnalysis out;
    out.orbit = periodic_orbit(model, omega);
    const PeriodicOrbit& orbit = out.orbit;
    const double period = orbit.period;
    const auto r = static_cast<Eigen::Index>(orbit.coordinates.size());
    const Variational system(model, orbit);
    // The kinds and shapes are read under the mass matrix at t = 0.
    std::vector<double> q0, qd0;
    HubInput u0;
    orbit.state(0.0, q0, qd0, u0);
    const Eigen::MatrixXd M = mass_at(model, u0, q0);
    const Eigen::MatrixXd U = system.mass().llt().matrixU();
    const AverageModes average = average_modes(system, U, period, r);
    // The step counts N and 2N, the harmonics read from the finer's 2N samples: N at least the harmonics of the
    // fastest resolved mode and a margin of 8 for the spread of its periodic eigenvector's harmonics, a multiple of 8
    // and at least 32, within the budget.
    const int most = most_steps(r);
    const auto band = [omega](int steps) { return (steps - 8) * omega; };  // the frequencies 2N samples resolve
    int steps =
        std::clamp(8 * static_cast<int>(std::ceil(std::min(average.fastest / omega + 8.0, 1e6) / 8.0)), 32, most / 2);
    std::vector<cd> coarse = exponents(eigen_pairs(system.transition(steps, false).back(), false).values, period);
    const bool damped = dissipates(model);
    for (;;) {
        const std::vector<Eigen::MatrixXd> phi = system.transition(2 * steps, true);
        Eigen::VectorXcd multipliers;
        std::vector<Candidate> now = candidates(system, phi, omega, period, multipliers);
        bool resolved = true;
        const std::vector<char> agrees = agreeing(now, in_band(now, average, U, r, band(steps)), coarse, omega, resolved);
        if (!resolved) {
            if (4 * steps > most)
                throw std::runtime_error("the Floquet exponents at Omega = " + shortest(omega) +
                                         " rad/s did not converge by " + std::to_string(2 * steps) +
                                         " steps a revolution");
            steps *= 2;
            coarse = exponents(multipliers, period);
            continue;
        }
        out.steps = 2 * steps;
        out.monodromy = system.original_matrix(phi.back());
        out.multipliers = multipliers;
        int accounted = 0;
        for (std::size_t i = 0; i < now.size(); ++i) {
            if (!agrees[i]) continue;
            const Candidate& c = now[i];
            FloquetMode f;
            f.multiplier = c.multiplier;
            f.exponent = c.exponent;
            f.harmonic = c.harmonic;
            set_rates(f.mode, c.rad_s, c.exponent.real(), std::abs(eigenvalue_of(c)), damped);
            classify_mode(model, M, U, orbit.coordinates, c.rates, damped && c.rad_s == 0.0 && f.mode.growth < 0.0,
                          f.mode);
            accounted += c.multiplier.imag() == 0.0 ? 1 : 2;
            out.modes.push_back(std::move(f));
        }
        out.left_out = static_cast<int>(multipliers.size()) - accounted;
        break;
    }
    std::stable_sort(out.modes.begin(), out.modes.end(), [damped](const FloquetMode& a, const FloquetMode& b) {
        return mode_before(a.mode, b.mode, damped);
    });
    return out;
}

std::vector<NaturalMode> floquet_modes(const Model& model, double omega, Axial axial)
{
    FloquetAnalysis f = floquet(model, omega, axial);
    if (f.modes.empty())
        throw std::runtime_error("at Omega = " + shortest(omega) + " rad/s every mode decays too fast to be resolved " +
                                 "in one revolution (by more than about 1e8 in its period of " +
                                 shortest(f.orbit.period) + " s): the periodic motion has no mode to list");
    std::vector<NaturalMode> modes;
    for (FloquetMode& m : f.modes) modes.push_back(std::move(m.mode));
    return modes;
}

}  // namespace hubbeam
