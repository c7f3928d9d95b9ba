// Model: the one interface the integrator sees (mass matrix, generalized forces, energy, momentum of a
// variant). Implementations: generated kernels (generated_model.hpp) and the hand-assembled docs/model.md
// section 5 (assembled.hpp); make_model.hpp chooses between them.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "coordinates.hpp"
#include "interface.hpp"
#include "variant.hpp"

namespace hubbeam {

/// Kinetic energy split by degree in the rates qd (T = T2 + T1 + T0) and potential energy U.
struct Energy {
    double T2 = 0.0, T1 = 0.0, T0 = 0.0, U = 0.0;
    double kinetic() const { return T2 + T1 + T0; }
};

/// Tip displacements u_y(L), u_x1(L) and u_x(L) = u_x1(L) - 1/2 B^T H(L) B (docs/model.md section 5.4); out of the
/// plane u_z(L), phi(L), and u_x shortened by both slopes (section 12); u_z and phi 0 in a planar variant.
struct Tip {
    double uy = 0.0, ux1 = 0.0, ux = 0.0, uz = 0.0, phi = 0.0;
};

/// A tip value by its column's name, in the one order every output lists them (a row's tip columns, a rotor's
/// blades 2 .. N, the sensitivities' outputs); fields is the coordinate count a variant needs for it (nz for u_z,
/// nt for phi), null where every variant has it.
struct TipValue {
    const char* name;
    double Tip::*member;
    int VariantKey::*fields;
};
inline constexpr TipValue tip_values[] = {{"tip_uy", &Tip::uy, nullptr},
                                          {"tip_ux1", &Tip::ux1, nullptr},
                                          {"tip_ux", &Tip::ux, nullptr},
                                          {"tip_uz", &Tip::uz, &VariantKey::nz},
                                          {"tip_phi", &Tip::phi, &VariantKey::nt}};
/// Whether key's variant has the tip value v (its field's coordinates).
inline bool has_tip_value(const VariantKey& key, const TipValue& v)
{
    return v.fields == nullptr || key.*v.fields > 0;
}

/// Q = F m: F (nq x K, free of the state) fixed for the run, m the K monomials of the state Q is a sum of. What
/// lets the integrator fold a constant M^-1 into F once (docs/architecture.md, "From scene to rows").
class TermForces {
public:
    virtual ~TermForces() = default;
    /// K, the number of monomials.
    virtual int term_count() const = 0;
    /// m[K] at the state.
    virtual void terms(const HubInput& u, const double* q, const double* qd, double* m) const = 0;
    /// F[nq*K], row-major.
    virtual void term_matrix(double* F) const = 0;
};

/// y = P m by a kernel with P's entries at fixed places: the runtime's folded P (nq x K; M^-1 F for a constant M)
/// laid out by groups of rows as generated_abi.h's forces_folded states.
class FoldedForceKernel {
public:
    virtual ~FoldedForceKernel() = default;
    virtual void accelerations(const double* W, const HubInput& u, const double* q, const double* qd,
                               double* qdd) const = 0;
};

/// The exact derivatives of M and Q that implicit steppers and linearization use.
class ExactJacobian {
public:
    virtual ~ExactJacobian() = default;
    /// Each row-major: dQdq[i*nq+k] = dQ_i/dq_k, dQdqd[i*nq+k] = dQ_i/dqd_k and dQdu[i*3+j] = dQ_i/du_j with u indexed
    /// by DriveValue (docs/model.md section 5.1).
    virtual void force_derivatives(const HubInput& u, const double* q, const double* qd, double* dQdq, double* dQdqd,
                                   double* dQdu) const = 0;
    /// dMv[i*nq+k] = sum_j dM_ij/dq_k v_j, row-major; all zeros when M is constant.
    virtual void mass_q_product(const HubInput& u, const double* q, const double* v, double* dMv) const = 0;
};

/// The derivatives of M, Q and the tip with respect to one physical parameter p_k (Param), the state and the drive
/// held fixed: what forward sensitivity equations add to the state's (docs/sensitivities.md).
class ParameterDerivatives {
public:
    virtual ~ParameterDerivatives() = default;
    /// dM/dp_k at q, nq x nq row-major, both triangles.
    virtual void mass_p(Param k, const HubInput& u, const double* q, double* dM) const = 0;
    /// dQ/dp_k at (u, q, qd).
    virtual void forces_p(Param k, const HubInput& u, const double* q, const double* qd, double* dQ) const = 0;
    /// mass_p and forces_p of count parameters ks at one state, what they share computed once: dM holds count nq x nq
    /// row-major matrices one after the other, dQ count vectors of nq.
    virtual void derivatives_p(const Param* ks, int count, int nq, const HubInput& u, const double* q,
                               const double* qd, double* dM, double* dQ) const = 0;
    /// d(tip)/dp_k at fixed q (a shape function's scale may hold L).
    virtual Tip tip_p(Param k, const double* q) const = 0;
    /// dF/dp_k of the term form Q = F m (nq x K row-major, free of the state, so once per run), for a model whose
    /// term_forces() is not null; false when this implementation has no such form.
    virtual bool term_matrix_p(Param k, double* dF) const
    {
        (void)k, (void)dF;
        return false;
    }
};

/// The one interface the integrator sees. What only some models can do (the term form of Q, a folded kernel, exact
/// Jacobians) is reached through an accessor that returns nullptr when the model cannot: a caller cannot call it
/// without asking first. Immutable once built (every evaluation is const and keeps no state between calls), so that
/// one model serves the runs of several threads at once; a run's work arrays belong to the run.
class Model {
public:
    virtual ~Model() = default;
    const VariantKey& key() const { return key_; }
    int nq() const { return nq_; }
    /// The fields of q, in order (coordinates.hpp): every offset into q is read from here.
    const CoordinateLayout& coordinates() const { return coordinates_; }
    /// The physical parameters the model's coefficients hold (Parameters::packed()), or empty for a model that does
    /// not say: what a caller that shares one model between scenes compares with each scene's.
    const std::vector<double>& parameters() const { return parameters_; }
    /// "generated" or "assembled".
    virtual const char* source() const = 0;
    /// Where a generated model's kernels come from ("built in", "cached", "compiled now in 2.1 s"), or why
    /// an automatic choice fell back to the assembled path; empty if there is nothing to say.
    const std::string& origin() const { return origin_; }
    void set_origin(std::string origin) { origin_ = std::move(origin); }
    /// True when M does not depend on q (prescribed rotation, first and zero order): factor it once.
    virtual bool mass_is_constant() const = 0;
    /// M(q), nq x nq row-major, symmetric to the bit (the solvers read either triangle).
    virtual void mass(const HubInput& u, const double* q, double* M) const = 0;
    /// M's structure, row-major, one character per entry: '0' zero, 'c' constant, 'v' depends on q. The
    /// integrator chooses its linear algebra from it; by default every entry is 'c' or every entry 'v'.
    virtual std::string mass_pattern() const { return std::string(nq() * nq(), mass_is_constant() ? 'c' : 'v'); }
    /// Writes the entries of M(q) that the pattern marks 'v', in both triangles, and leaves the others.
    virtual void mass_varying(const HubInput& u, const double* q, double* M) const { mass(u, q, M); }
    /// As mass_varying, for a caller that reads only the upper triangle: the lower one may be left as it was.
    virtual void mass_varying_upper(const HubInput& u, const double* q, double* M) const { mass_varying(u, q, M); }
    /// Q in the form F m (F fixed for the run, m monomials of the state), or nullptr when the model has no such
    /// form: the integrator then calls forces() and solves with M.
    virtual const TermForces* term_forces() const { return nullptr; }
    /// The kernel qdd = W m for a constant M, with W's entries at fixed places, or nullptr.
    virtual const FoldedForceKernel* folded_kernel() const { return nullptr; }
    /// Q(t, q, qd) such that M qdd = Q.
    virtual void forces(const HubInput& u, const double* q, const double* qd, double* Q) const = 0;
    virtual Energy energy(const HubInput& u, const double* q, const double* qd) const = 0;
    /// Angular momentum about the axis, dT/dtheta_dot.
    virtual double momentum(const HubInput& u, const double* q, const double* qd) const = 0;
    /// The tip's displacements at coordinates q.
    virtual Tip tip(const double* q) const = 0;

    /// The exact derivatives of M and Q (the generated kernels, or the assembled blocks' derivatives), or nullptr for
    /// a model without them (a test's stand-in): the implicit steppers then difference Q; linearization and
    /// quasi-static axial coordinates refuse it.
    virtual const ExactJacobian* jacobian() const { return nullptr; }
    /// The exact derivatives of M, Q and the tip with respect to the physical parameters (generated kernels), or
    /// nullptr: a caller then differences models built at perturbed parameters.
    virtual const ParameterDerivatives* parameter_derivatives() const { return nullptr; }

    /// dQ/dtheta of a prescribed variant with gravity, where the angle u.theta is an input (the time derivative of
    /// the implicit steppers' Jacobian gains dQ/dtheta theta_dot); zeros for every other variant.
    virtual void forces_theta(const HubInput& u, const double* q, const double* qd, double* dQdtheta) const
    {
        (void)u, (void)q, (void)qd;
        std::fill_n(dQdtheta, nq(), 0.0);
    }

protected:
    explicit Model(const VariantKey& key) : key_(key), coordinates_(coordinate_layout(key)), nq_(coordinates_.size()) {}
    /// A model whose q is laid out otherwise than its variant's (a rotor's blades, each of the variant).
    Model(const VariantKey& key, CoordinateLayout layout, const Parameters& p)
        : key_(key), coordinates_(std::move(layout)), nq_(coordinates_.size()), parameters_(p.packed())
    {
    }
    Model(const VariantKey& key, const Parameters& p)
        : key_(key), coordinates_(coordinate_layout(key)), nq_(coordinates_.size()), parameters_(p.packed())
    {
    }

private:
    VariantKey key_;
    CoordinateLayout coordinates_;
    int nq_;
    std::vector<double> parameters_;
    std::string origin_;
};

}  // namespace hubbeam
