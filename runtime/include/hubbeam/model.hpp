// Model: the one interface the integrator sees (mass matrix, generalized forces, energy, momentum of a
// variant). Implementations: generated kernels (generated_model.hpp) and the hand-assembled docs/model.md
// section 5 (assembled.hpp); make_model.hpp chooses between them.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

#include "interface.hpp"
#include "variant.hpp"

namespace hubbeam {

/// Kinetic energy split by degree in the rates qd (T = T2 + T1 + T0) and potential energy U.
struct Energy {
    double T2 = 0.0, T1 = 0.0, T0 = 0.0, U = 0.0;
    double kinetic() const { return T2 + T1 + T0; }
};

/// Tip displacements u_y(L), u_x1(L) and u_x(L) = u_x1(L) - 1/2 B^T H(L) B (docs/model.md section 5.4).
struct Tip {
    double uy = 0.0, ux1 = 0.0, ux = 0.0;
};

class Model {
public:
    virtual ~Model() = default;
    const VariantKey& key() const { return key_; }
    int nq() const { return key_.nq(); }
    /// "generated" or "assembled".
    virtual const char* source() const = 0;
    /// Where a generated model's kernels come from ("built in", "cached", "compiled now in 2.1 s"), or why
    /// an automatic choice fell back to the assembled path; empty if there is nothing to say.
    const std::string& origin() const { return origin_; }
    void set_origin(std::string origin) { origin_ = std::move(origin); }
    /// True when M does not depend on q (prescribed rotation, first and zero order): factor it once.
    virtual bool mass_is_constant() const = 0;
    /// M(q), nq x nq row-major.
    virtual void mass(const HubInput& u, const double* q, double* M) const = 0;
    /// M's structure, row-major, one character per entry: '0' zero, 'c' constant, 'v' depends on q. The
    /// integrator chooses its linear algebra from it; by default every entry is 'c' or every entry 'v'.
    virtual std::string mass_pattern() const { return std::string(nq() * nq(), mass_is_constant() ? 'c' : 'v'); }
    /// Writes the entries of M(q) that the pattern marks 'v', in both triangles, and leaves the others.
    virtual void mass_varying(const HubInput& u, const double* q, double* M) const { mass(u, q, M); }
    /// K > 0 when Q = F m with F (nq x K) fixed for the run and m K monomials of the state; 0 otherwise.
    virtual int force_terms() const { return 0; }
    /// m[K] of Q = F m (only if force_terms() > 0).
    virtual void forces_terms(const HubInput& u, const double* q, const double* qd, double* m) const;
    /// F[nq*K] of Q = F m, row-major (only if force_terms() > 0).
    virtual void forces_matrix(double* F) const;
    /// Whether forces_folded() computes.
    virtual bool has_forces_folded() const { return false; }
    /// qdd = W m for a row-major W (nq x K) by a kernel with W's entries at fixed places (only if
    /// has_forces_folded()).
    virtual void forces_folded(const double* W, const HubInput& u, const double* q, const double* qd,
                               double* qdd) const;
    /// Q(t, q, qd) such that M qdd = Q.
    virtual void forces(const HubInput& u, const double* q, const double* qd, double* Q) const = 0;
    virtual Energy energy(const HubInput& u, const double* q, const double* qd) const = 0;
    /// Angular momentum about the axis, dT/dtheta_dot.
    virtual double momentum(const HubInput& u, const double* q, const double* qd) const = 0;
    /// The tip's displacements at coordinates q.
    virtual Tip tip(const double* q) const = 0;

    /// True when the model supplies the exact derivatives below (generated kernels); otherwise the integrator
    /// falls back to a finite-difference Jacobian.
    virtual bool has_jacobian() const { return false; }
    /// The derivatives of Q, each row-major: dQdq[i*nq+k] = dQ_i/dq_k, dQdqd[i*nq+k] = dQ_i/dqd_k and
    /// dQdu[i*3+j] = dQ_i/du_j with u indexed by DriveValue (docs/model.md section 5.1). Only if has_jacobian().
    virtual void force_derivatives(const HubInput& u, const double* q, const double* qd, double* dQdq, double* dQdqd,
                                   double* dQdu) const;
    /// dMv[i*nq+k] = sum_j dM_ij/dq_k v_j, row-major; all zeros when mass_is_constant(). Only if has_jacobian().
    virtual void mass_q_product(const HubInput& u, const double* q, const double* v, double* dMv) const;

protected:
    explicit Model(const VariantKey& key) : key_(key) {}

private:
    VariantKey key_;
    std::string origin_;
};

inline void Model::forces_terms(const HubInput&, const double*, const double*, double*) const
{
    throw std::logic_error(std::string(source()) + " model has no term form of its forces");
}

inline void Model::forces_matrix(double*) const
{
    throw std::logic_error(std::string(source()) + " model has no term form of its forces");
}

inline void Model::forces_folded(const double*, const HubInput&, const double*, const double*, double*) const
{
    throw std::logic_error(std::string(source()) + " model has no folded forces kernel");
}

inline void Model::force_derivatives(const HubInput&, const double*, const double*, double*, double*, double*) const
{
    throw std::logic_error(std::string(source()) + " model has no Jacobian");
}

inline void Model::mass_q_product(const HubInput&, const double*, const double*, double*) const
{
    throw std::logic_error(std::string(source()) + " model has no Jacobian");
}

}  // namespace hubbeam
