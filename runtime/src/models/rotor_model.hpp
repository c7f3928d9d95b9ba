// A rotor (docs/model.md section 13): N identical blades on one hub, each run by one model of the blade's variant at
// its own parameters and azimuth, joined through the hub angle. The blades' code is the variant's, once for all N.
#pragma once

#include <memory>
#include <vector>

#include <hubbeam/model.hpp>

namespace hubbeam {

/// q = (theta under a torque, a moving hub's x_h, y_h, blade 1's fields, ..., blade N's): coordinate_layout(key, N).
/// Blade b's model sees its own q with the hub angle theta + psi_b; its forces and mass scatter into the rotor's.
/// Blades couple through the hub's coordinates alone, so M is block-arrowhead: each blade's block on the diagonal,
/// the hub's rows and columns dense.
class RotorModel final : public Model {
public:
    /// blades[b]: blade b's model (its parameters: Rotor::blade), all of one variant; azimuths[b]: psi_b - theta.
    RotorModel(std::vector<std::unique_ptr<Model>> blades, std::vector<double> azimuths, const Parameters& p);

    int blades() const { return static_cast<int>(blades_.size()); }
    const Model& blade(int b) const { return *blades_[static_cast<std::size_t>(b)]; }
    /// Blade b's tip at the rotor's q.
    Tip blade_tip(const double* q, int b) const;

    const char* source() const override { return blades_.front()->source(); }
    bool mass_is_constant() const override { return blades_.front()->mass_is_constant(); }
    std::string mass_pattern() const override { return pattern_; }
    void mass(const HubInput& u, const double* q, double* M) const override;
    /// Each blade's varying entries (its own kernel's), summed where blades share them (the hub's): the solvers call
    /// this at every right-hand side, where the whole matrix would cost a scatter of nq^2 entries.
    void mass_varying(const HubInput& u, const double* q, double* M) const override;
    void forces(const HubInput& u, const double* q, const double* qd, double* Q) const override;
    Energy energy(const HubInput& u, const double* q, const double* qd) const override;
    double momentum(const HubInput& u, const double* q, const double* qd) const override;
    Tip tip(const double* q) const override { return blade_tip(q, 0); }
    const ExactJacobian* jacobian() const override { return jacobian_.get(); }
    void forces_theta(const HubInput& u, const double* q, const double* qd, double* dQdtheta) const override;

    /// Blade b's view of the rotor's state: its drive (the torque on blade 0 alone, the angle turned by psi_b), its
    /// coordinates (theta + psi_b under a torque) and rates. angle: whether q holds positions (turned) or a direction.
    HubInput blade_input(const HubInput& u, int b) const;
    void gather(const double* q, int b, double* local, bool angle) const;
    /// Adds blade b's local vector into the rotor's.
    void scatter_add(const double* local, int b, double* global) const;
    /// Adds blade b's local nl x nl matrix (row-major) into the rotor's nq x nq one.
    void scatter_add_matrix(const double* local, int b, double* global) const;
    /// The rotor's index of blade b's local coordinate i.
    int global_index(int b, int i) const { return i < hub_ ? i : i + b * (local_ - hub_); }

private:
    class Jacobian;
    /// out = the blades' vectors (forces, dQ/dtheta) summed into the rotor's, each at its blade's state.
    void summed(const HubInput& u, const double* q, const double* qd, double* out,
                void (Model::*vector)(const HubInput&, const double*, const double*, double*) const) const;
    std::vector<std::unique_ptr<Model>> blades_;
    std::vector<double> azimuths_;
    int hub_;       // the hub's coordinates, first in every blade's q and in the rotor's: theta (under a torque), x_h, y_h
    bool torque_;   // theta is q[0]
    int local_;  // a blade's nq
    std::string pattern_;
    /// The rotor's varying entries of M (row-major indices), and for each blade the pairs (its local entry, the
    /// rotor's entry) of its own varying ones.
    std::vector<int> varying_;
    std::vector<std::vector<std::pair<int, int>>> blade_varying_;
    std::unique_ptr<ExactJacobian> jacobian_;
};

}  // namespace hubbeam
