// Forward sensitivities: the state's equations with, beside them, the derivative of the state by each of a few
// parameters, s_j' = J(t, y) s_j + df/dp_j, integrated as one system by whichever stepper the run uses
// (docs/sensitivities.md).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <hubbeam/config.hpp>
#include "dynamics/integrate.hpp"

namespace hubbeam {

/// y = (state, s_1, ..., s_k) with s_j = d(state)/dp_j, starting at 0 (a run starts from rest, whatever the
/// parameters). J is the state's Jacobian (exact where the model has derivative kernels); df/dp_j comes from
/// ParameterDerivatives (generated, or differences of models built at moved parameters) or, for a control gain, from
/// the control law through dQ/dtau. Implicit steppers get J on each diagonal block: the sensitivities' own equations
/// are linear, and their coupling to the state is left to the iteration.
class SensitivitySystem final : public FirstOrderSystem {
public:
    /// The scene's run of model with the sensitivities of scene.output.sensitivities. Throws std::invalid_argument
    /// for what the equations cannot follow (a torque law given as code).
    SensitivitySystem(const Model& model, const Scene& scene);
    ~SensitivitySystem() override;

    int size() const override { return (1 + count()) * state_size(); }
    int auxiliary_count() const override { return FirstOrderSystem::auxiliary_count() + count() * state_size(); }
    int blocks() const override { return 1 + count(); }
    int controlled_size() const override { return controlled_ ? size() : state_size(); }
    int rhs(double t, const double* y, double* dydt) override;
    int jacobian(double t, const double* y, double* dfdy, double* dfdt) override;
    /// With derivative kernels: the forcings' solves with M alone, no linearization of the forces.
    int blocks_forcing(double t, const double* y, double* dydt) override;

    int count() const { return static_cast<int>(parameters_.size()); }
    /// The size of parameter j (|p_j|, or 1 where it is 0): a derivative by it times this is a change of the output.
    double scale(int j) const;
    /// d(output)/dp for each parameter, each of sensitivity_outputs within it (simulate.hpp's column order), at the
    /// state y at t; q is y's coordinates.
    void outputs(double t, const double* y, double* out);

private:
    /// Parameter j's forcing before M^-1, r = dQ/dp_j - dM/dp_j qdd (unscaled), at the state y with accelerations
    /// qdd under the input u; false for a gain while the torque saturates (it has none). work_rate: the derivative of
    /// the hub's work's rate by a gain, scaled.
    bool forcing(int j, const double* y, const double* qdd, const HubInput& u, const HubInput& reference, double* r,
                 double& work_rate) const;
    /// The state's rates into dydt, and each parameter's forcing before M^-1 into the Work's R (scaled, and zero
    /// where it has none, with derivative kernels; unscaled otherwise), with the hub's work's rates. GSL status.
    int state_and_forcings(double t, const double* y, double* dydt);
    /// The forcings' terms outside M^-1 (the hub's work by a gain, the dissipated energy by C's parameters) added to
    /// each block's rates in dydt; GSL_EBADFUNC where any rate of dydt is not finite.
    int finish_rates(const double* y, double* dydt) const;
    /// J sigma_j by central differences of the state's right-hand side along sigma_j, into out.
    int product_by_differences(double t, const double* y, int j, double* out);
    struct Parameter;
    const Model& model_;
    const Scene& scene_;
    bool controlled_;  // solver.sensitivity_error_control: whether the steps weigh the sensitivities' error
    std::vector<std::unique_ptr<Parameter>> parameters_;
    struct Work;
    std::unique_ptr<Work> work_;
};

}  // namespace hubbeam
