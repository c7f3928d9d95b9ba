// MassSolver: x = M(q)^-1 b with the linear algebra the mass matrix's pattern allows, chosen from the
// model's data (docs/model.md section 5): a constant M factored once (dense, or banded for FEM and BSIM),
// or, where only a few rows and columns depend on q (the hub's under torque), the constant block factored
// once and the rest eliminated through its Schur complement.
#pragma once

#include <memory>
#include <string>

#include <hubbeam/model.hpp>

namespace hubbeam {

class MassSolver {
public:
    /// The cheapest solver for model's mass pattern.
    static std::unique_ptr<MassSolver> make(const Model& model);
    virtual ~MassSolver() = default;

    /// Evaluates and factors M at (u, q) where it depends on them (a constant M is factored at the first
    /// call only). False when M is not positive definite.
    virtual bool prepare(const HubInput& u, const double* q) = 0;
    /// b := M^-1 b for the M of the last prepare(); b is n x columns, column-major.
    virtual void solve(double* b, int columns = 1) const = 0;
    /// prepare(u, q), then solve(b) for one column: where the preparation itself solves with a factor, the two
    /// solves run together (a banded solve is bound by the latency of its chain of multiply-adds, not their count).
    virtual bool prepare_and_solve(const HubInput& u, const double* q, double* b)
    {
        if (!prepare(u, q)) return false;
        solve(b);
        return true;
    }
    /// What was chosen, e.g. "banded Cholesky (bandwidth 3), factored once".
    virtual std::string describe() const = 0;
};

}  // namespace hubbeam
