// Modal damping of a blade's own modes at rest (modal_damping.hpp): the matrix from the blade's eigenproblem at rest
// and the model that adds it to a blade's forces and exact Jacobian.
#include "models/modal_damping.hpp"

#include <Eigen/Eigenvalues>
#include <complex>
#include <stdexcept>

#include <hubbeam/make_model.hpp>

#include "models/mode_kinds.hpp"
#include "models/model_operations.hpp"
#include "models/rotor_model.hpp"
#include "terms.hpp"

namespace hubbeam {

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// The indices into q of the blade's elastic fields (those with a basis: not the hub's angle or translation).
std::vector<int> elastic_coordinates(const Model& blade)
{
    std::vector<int> E;
    for (const CoordinateField& f : blade.coordinates().fields)
        if (f.basis)
            for (int i = f.first; i < f.end(); ++i) E.push_back(i);
    return E;
}

/// "expected at most N ratios (the blade's ... modes at rest), got G", against file and key.
[[noreturn]] void too_many(const std::string& file, const char* key, std::size_t modes, std::size_t given,
                           const char* kind)
{
    throw std::invalid_argument(file + ": " + key + ": expected at most " + std::to_string(modes) + " ratio" +
                                (modes == 1 ? "" : "s") + " (the blade's " + kind + " modes at rest" +
                                (modes == 0 ? ": it has none" : "") + "), got " + std::to_string(given));
}

/// The model with -C qd added to the forces of another: C constant, over the coordinates it damps.
class ModallyDamped final : public Model, ExactJacobian {
public:
    ModallyDamped(std::unique_ptr<Model> inner, Eigen::MatrixXd C, const Parameters& p)
        : Model(inner->key(), inner->coordinates(), p), inner_(std::move(inner)), C_(std::move(C))
    {
        set_origin(inner_->origin());
        for (int i = 0; i < nq(); ++i)
            if (C_.row(i).cwiseAbs().maxCoeff() > 0.0) damped_.push_back(i);
        Cd_ = C_(damped_, damped_);
    }

    const Eigen::MatrixXd& damping() const { return C_; }

    const char* source() const override { return inner_->source(); }
    bool mass_is_constant() const override { return inner_->mass_is_constant(); }
    void mass(const HubInput& u, const double* q, double* M) const override { inner_->mass(u, q, M); }
    std::string mass_pattern() const override { return inner_->mass_pattern(); }
    void mass_varying(const HubInput& u, const double* q, double* M) const override { inner_->mass_varying(u, q, M); }
    void mass_varying_upper(const HubInput& u, const double* q, double* M) const override
    {
        inner_->mass_varying_upper(u, q, M);
    }
    void forces(const HubInput& u, const double* q, const double* qd, double* Q) const override
    {
        inner_->forces(u, q, qd, Q);
        const auto d = static_cast<Eigen::Index>(damped_.size());
        for (Eigen::Index i = 0; i < d; ++i) {
            double c = 0.0;
            for (Eigen::Index j = 0; j < d; ++j) c += Cd_(i, j) * qd[damped_[static_cast<std::size_t>(j)]];
            Q[damped_[static_cast<std::size_t>(i)]] -= c;
        }
    }
    Energy energy(const HubInput& u, const double* q, const double* qd) const override
    {
        return inner_->energy(u, q, qd);
    }
    double momentum(const HubInput& u, const double* q, const double* qd) const override
    {
        return inner_->momentum(u, q, qd);
    }
    Tip tip(const double* q) const override { return inner_->tip(q); }
    void forces_theta(const HubInput& u, const double* q, const double* qd, double* dQdtheta) const override
    {
        inner_->forces_theta(u, q, qd, dQdtheta);
    }
    const ExactJacobian* jacobian() const override { return inner_->jacobian() != nullptr ? this : nullptr; }

    void force_derivatives(const HubInput& u, const double* q, const double* qd, double* dQdq, double* dQdqd,
                           double* dQdu) const override
    {
        inner_->jacobian()->force_derivatives(u, q, qd, dQdq, dQdqd, dQdu);
        const std::size_t d = damped_.size(), n = static_cast<std::size_t>(nq());
        for (std::size_t i = 0; i < d; ++i)
            for (std::size_t j = 0; j < d; ++j)
                dQdqd[static_cast<std::size_t>(damped_[i]) * n + static_cast<std::size_t>(damped_[j])] -=
                    Cd_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
    }
    void mass_q_product(const HubInput& u, const double* q, const double* v, double* dMv) const override
    {
        inner_->jacobian()->mass_q_product(u, q, v, dMv);
    }

private:
    std::unique_ptr<Model> inner_;
    Eigen::MatrixXd C_;
    std::vector<int> damped_;  // the coordinates C damps (its nonzero rows)
    Eigen::MatrixXd Cd_;       // C over them
};

}  // namespace

Eigen::MatrixXd modal_damping_matrix(const Model& blade, const ModalDamping& ratios, const std::string& file)
{
    const HubInput rest;
    const std::vector<double> zero(static_cast<std::size_t>(blade.nq()), 0.0);
    const std::vector<int> E = elastic_coordinates(blade);
    const Eigen::MatrixXd M = mass_at(blade, rest, zero);
    const Eigen::MatrixXd K = -force_q_jacobian(blade, rest, zero, zero);
    const Eigen::MatrixXd Me = M(E, E), Ke = 0.5 * (K(E, E) + K(E, E).transpose());
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Ke, Me);  // Phi^T Me Phi = 1, ascending
    if (eig.info() != Eigen::Success) throw std::runtime_error("the blade's modes at rest did not converge");
    Eigen::MatrixXd Phi = eig.eigenvectors();
    const Eigen::VectorXd omega2 = eig.eigenvalues();
    separate_repeated(blade, M, E, omega2, Phi);  // a uniform blade's flap and edge modes of one frequency
    std::size_t flap = 0, edge = 0;
    Eigen::MatrixXd Ce = Eigen::MatrixXd::Zero(Me.rows(), Me.cols());
    for (Eigen::Index k = 0; k < Phi.cols(); ++k) {
        const Eigen::VectorXcd rates = Phi.col(k).cast<std::complex<double>>();
        const FieldKind kind = dominant_field(blade, M, E, rates);
        if (kind != FieldKind::flap && kind != FieldKind::inplane) continue;  // axial and twist modes: undamped
        const std::vector<double>& named = kind == FieldKind::flap ? ratios.flap : ratios.edge;
        std::size_t& count = kind == FieldKind::flap ? flap : edge;
        if (count++ >= named.size()) continue;
        const Eigen::VectorXd m = Me * Phi.col(k);
        Ce += 2.0 * named[count - 1] * std::sqrt(omega2[k]) * m * m.transpose();
    }
    if (ratios.flap.size() > flap) too_many(file, "damping.flap_ratios", flap, ratios.flap.size(), "flapwise");
    if (ratios.edge.size() > edge)
        too_many(file, "damping.edge_ratios", edge, ratios.edge.size(),
                 blade.key().out_of_plane() ? "edgewise" : "in-plane bending");
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(blade.nq(), blade.nq());
    C(E, E) = 0.5 * (Ce + Ce.transpose());
    return C;
}

std::unique_ptr<Model> with_modal_damping(std::unique_ptr<Model> blade, const Scene& scene, const Parameters& p)
{
    if (!scene.modal_damping.given()) return blade;
    // The blade's own modes: without its weight, which at rest and theta = 0 stiffens only a coned blade under
    // gravity along the axis, but is no part of the blade's structure.
    std::unique_ptr<Model> bare;
    if (p.g != 0.0 || p.g_axis != 0.0) {
        Parameters weightless = p;
        weightless.g = weightless.g_axis = 0.0;
        bare = make_model(blade->key(), weightless, scene.source);
    }
    Eigen::MatrixXd C = modal_damping_matrix(bare ? *bare : *blade, scene.modal_damping, scene.path);
    if (!scene.modal_damping.damps()) return blade;
    return std::make_unique<ModallyDamped>(std::move(blade), std::move(C), p);
}

Eigen::MatrixXd added_damping(const Model& model)
{
    if (const auto* d = dynamic_cast<const ModallyDamped*>(&model)) return d->damping();
    const auto* rotor = dynamic_cast<const RotorModel*>(&model);
    if (rotor == nullptr) return {};
    RowMatrix C = RowMatrix::Zero(model.nq(), model.nq());
    bool any = false;
    for (int b = 0; b < rotor->blades(); ++b) {
        const RowMatrix local = added_damping(rotor->blade(b));
        if (local.size() == 0) continue;
        rotor->scatter_add_matrix(local.data(), b, C.data());
        any = true;
    }
    return any ? Eigen::MatrixXd(C) : Eigen::MatrixXd();
}

bool dissipates(const Model& model)
{
    return dissipates(model.key()) || added_damping(model).size() > 0;
}

}  // namespace hubbeam
