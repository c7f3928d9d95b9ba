// The right-hand-side strategies of FirstOrderSystem: how dy/dt = (qd, qdd) with M(q) qdd = Q(t, q, qd) is computed,
// one small class per structure of the model (a constant M folded into the forces, the hub's row by its Schur
// complement, a mass solver, quasi-static axial coordinates), chosen once by make_right_hand_side from the model's data.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include "dynamics/integrate.hpp"
#include "dynamics/mass_solver.hpp"
#include "linalg/factorizations.hpp"

namespace hubbeam {

/// dy/dt of the first-order system at a drive value u, for one model.
class RightHandSide {
public:
    explicit RightHandSide(const Model& model) : model_(model), n_(model.nq()) {}
    virtual ~RightHandSide() = default;
    RightHandSide(const RightHandSide&) = delete;
    RightHandSide& operator=(const RightHandSide&) = delete;

    /// GSL_SUCCESS, or GSL_EBADFUNC when M is not positive definite or a result is not finite.
    virtual int derivative(const HubInput& u, const double* y, double* dydt) = 0;
    /// The model's q and qd (nq each) of a state y: y itself unless coordinates left the state. False if they
    /// cannot be found.
    virtual bool full_state(const HubInput& u, const double* y, double* q, double* qd);
    /// How accelerations are computed, for the summary.
    virtual std::string describe() const = 0;

    /// Records q as a state where M is not positive definite; returns GSL_EBADFUNC.
    int indefinite_mass_at(const double* q);
    /// u_y(L) of the last state so recorded (NaN if none).
    double indefinite_mass_tip() const { return indefinite_mass_tip_; }

protected:
    const Model& model_;
    int n_;

private:
    double indefinite_mass_tip_ = std::numeric_limits<double>::quiet_NaN();
};

/// The strategies over the full state y = (q, qd): each computes qdd its own way.
class Accelerations : public RightHandSide {
public:
    explicit Accelerations(const Model& model) : RightHandSide(model) {}
    int derivative(const HubInput& u, const double* y, double* dydt) final;
    /// qdd (nq) at (u, q, qd); GSL status as derivative(). qdd does not overlap q or qd.
    virtual int accelerations(const HubInput& u, const double* q, const double* qd, double* qdd) = 0;
};

/// W = M^-1 F (nq x K, column-major) for a constant M and Q = F m (docs/model.md section 5.3: the prescribed-rotation
/// M is constant), factored at the drive u0. Throws std::invalid_argument when M is not positive definite.
Eigen::MatrixXd folded_forces(const Model& model, const TermForces& terms, const HubInput& u0);

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// y = P m for a P (nq x K) fixed for the run and the monomials m of the state: by the model's generated kernel,
/// which holds P's structurally nonzero entries at fixed places, unrolled; else (no kernel, or one that disagrees
/// with the walk at a test state, e.g. an on-demand object of an older generator) by a walk over P's nonzeros
/// stored contiguously. No allocation per call.
class FoldedProduct {
public:
    /// hub_alone: P's row 0 is the hub's, which the kernel of a variant with a varying M keeps out of its row
    /// groups (generated_abi.h).
    FoldedProduct(const TermForces& terms, const FoldedForceKernel* kernel, const RowMajorMatrix& P,
                  bool hub_alone = false);
    void apply(const HubInput& u, const double* q, const double* qd, double* y)
    {
        if (kernel_ != nullptr) return kernel_->accelerations(groups_.data(), u, q, qd, y);
        terms_.terms(u, q, qd, m_.data());
        walk(m_.data(), y);
    }
    long nonzeros() const { return static_cast<long>(value_.size()); }
    bool by_kernel() const { return kernel_ != nullptr; }

private:
    void walk(const double* m, double* y) const;
    const TermForces& terms_;
    const FoldedForceKernel* kernel_;
    std::vector<double> groups_;                 // the kernel's argument: P by groups of W rows (generated_abi.h)
    std::vector<int> start_, column_;            // the walk: row i holds value_[start_[i] .. start_[i+1])
    std::vector<double> value_, m_;
};

/// Constant M, qdd = W m by FoldedProduct: the generated kernel with W's entries at fixed places where the model has
/// one (model.folded_kernel()), else the walk over W's nonzeros stored by rows, where W is mostly zeros (the prescribed
/// M's axial and transverse blocks keep W block-structured).
class Folded final : public Accelerations {
public:
    /// kernel: the model's folded kernel, or nullptr for the walk.
    Folded(const Model& model, const TermForces& terms, const FoldedForceKernel* kernel, const Eigen::MatrixXd& W);
    int accelerations(const HubInput& u, const double* q, const double* qd, double* qdd) override;
    std::string describe() const override;
    bool by_kernel() const { return product_.by_kernel(); }

private:
    FoldedProduct product_;
    Eigen::Index columns_;
    bool offered_;  // a kernel was given (by_kernel() false then: it disagreed with the walk)
};

/// Constant M, qdd = W m with W dense: one pass of multiply-adds.
class FoldedDense final : public Accelerations {
public:
    FoldedDense(const Model& model, const TermForces& terms, Eigen::MatrixXd W)
        : Accelerations(model), terms_(terms), W_(std::move(W)), m_(W_.cols())
    {
    }
    int accelerations(const HubInput& u, const double* q, const double* qd, double* qdd) override;
    std::string describe() const override;

private:
    const TermForces& terms_;
    Eigen::MatrixXd W_;
    Eigen::VectorXd m_;
};

/// Hub torque where M's varying entries all lie in the hub's row (m00(q), and with axial coordinates the couplings
/// b_v(q)); C, the rest of M, is constant. With b = b_c + b_v the couplings (b_c the constant ones),
/// W_C = C^-1 F_C and c_c = C^-1 b_c folded once, y = [F_0; W_C] m per call, then
///   c = c_c + C^-1 b_v(q),   theta_ddot = (y_0 - b^T y_C) / (m00(q) - b^T c),   qdd_C = y_C - c theta_ddot,
/// with C^-1 b_v from C^-1's columns at the varying couplings, stored by their nonzeros. Without varying couplings
/// the hub's row is folded too, g = F_0 - b_c^T W_C in place of F_0, and b^T c is a constant: theta_ddot =
/// y_0 / (m00(q) - b_c^T c_c). Besides saving the solves, the beam's ill-conditioned C (BIM) is applied through
/// fixed products of smooth monomials: its round-off is the same at every evaluation instead of noise that an error
/// control chases down to tiny steps. Throws std::invalid_argument when C is not positive definite or a varying
/// entry lies outside the hub's row.
class HubSchur final : public Accelerations {
public:
    HubSchur(const Model& model, const TermForces& terms, const HubInput& u0);
    int accelerations(const HubInput& u, const double* q, const double* qd, double* qdd) override;
    std::string describe() const override;
    /// Nonzeros of the folded [g; W_C] (or [F_0; W_C]): folding pays while they cost no more than the forces' terms
    /// plus a dense solve.
    long nonzeros() const { return product_->nonzeros(); }
    /// Nonzeros of C^-1 at the varying couplings, applied per call.
    long coupling_nonzeros() const { return static_cast<long>(z_.size()); }
    bool by_kernel() const { return product_->by_kernel(); }

private:
    std::unique_ptr<FoldedProduct> product_;
    std::vector<int> varying_;  // the coordinates j > 0 with m0j varying
    struct ColumnEntry {
        int row, column;  // row of C (0 .. n-2), and the coupling's column j of M
        double value;
    };
    std::vector<ColumnEntry> z_;                 // the nonzeros of C^-1's columns at the varying couplings
    std::vector<double> c_, y_;
    Eigen::VectorXd c_c_;                        // C^-1 b_c, b_c the constant couplings
    double s0_ = 0.0;                            // b_c^T c_c
    int columns_ = 0;                            // K
    RowMajorMatrix M_;                           // M at rest, its varying entries evaluated per call
};

/// M evaluated and factored by the mass solver its pattern allows (mass_solver.hpp), then qdd = M^-1 Q.
class MassSolved final : public Accelerations {
public:
    explicit MassSolved(const Model& model) : Accelerations(model), solver_(MassSolver::make(model)) {}
    int accelerations(const HubInput& u, const double* q, const double* qd, double* qdd) override;
    std::string describe() const override { return solver_->describe(); }

private:
    std::unique_ptr<MassSolver> solver_;
};

/// Quasi-static axial coordinates (docs/model.md section 9): y holds only theta (torque) and B with their rates; A
/// solves the axial rows of Lagrange's equations with A_dot = A_ddot = 0 (and the hub acceleration's axial term
/// dropped) at every evaluation, and the remaining rows are M_rr qdd_r = Q_r. Throws std::invalid_argument without
/// axial coordinates or without the model's exact derivatives (its Newton's Jacobian).
class QuasiStaticAxial final : public RightHandSide {
public:
    explicit QuasiStaticAxial(const Model& model);
    int derivative(const HubInput& u, const double* y, double* dydt) override;
    /// A by Newton on Q_A = 0 from the last solution, A_dot = 0.
    bool full_state(const HubInput& u, const double* y, double* q, double* qd) override;
    std::string describe() const override;

private:
    std::vector<int> kept_;  // the model's coordinates that are states
    std::vector<double> q_, qd_;
    Eigen::VectorXd A_, Q_;
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> dQdq_, dQdqd_, dQdu_;
    Eigen::LLT<Eigen::MatrixXd> reduced_llt_;
    bool reduced_factored_ = false;
};

/// The strategy for a model and its hub motion, chosen from the model's data: quasi-static axial coordinates if
/// asked; else, with a constant M and forces in term form, M^-1 folded into them (by the generated kernel where
/// the model has one, else dense or by rows as W's density decides) where W costs no more than the forces' terms
/// plus a dense solve; else, where M varies in the hub's row only, the Schur-folded hub row on the same condition;
/// else the mass solver.
std::unique_ptr<RightHandSide> make_right_hand_side(const Model& model, const Motion& motion, Axial axial);

}  // namespace hubbeam
