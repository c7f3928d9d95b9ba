// Simulation: one scene integrated from rest, rows handed to a sink at exact multiples of dt_out. The
// library entry point under the command line.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "scene.hpp"

namespace hubbeam {

/// One output row. Columns: t, theta, theta_dot, tip_uy, tip_ux1, tip_ux, then kinetic, potential,
/// momentum (dT/dtheta_dot) and the Jacobi integral T2 - T0 + U (T split by degree in the coordinates' rates),
/// which is constant whenever the drive is steady: at constant prescribed spin, and, where theta is a
/// coordinate, with zero torque (then it is the total energy T + U).
struct Row {
    double t, theta, theta_dot, tip_uy, tip_ux1, tip_ux, kinetic, potential, momentum, jacobi;
};
/// CSV header matching Row.
inline const char* row_header()
{
    return "t,theta,theta_dot,tip_uy,tip_ux1,tip_ux,kinetic,potential,momentum,jacobi";
}

/// A run whose Jacobi integral drifts by more than this fraction of the vibration energy once the drive is steady
/// is reported as untrustworthy (exit 1): correct runs drift by 1e-8 of it, runs at absurd tolerances by 100 %.
inline constexpr double invariant_tolerance = 1e-2;

struct RunSummary {
    std::string variant;  // VariantKey::name()
    std::string source;   // "generated" or "assembled", then where from ("generated, cached")
    std::string algebra;  // how accelerations are computed (FirstOrderSystem::linear_algebra())
    std::string stepper;      // the step type that ran
    std::string stepper_why;  // why, when it was chosen automatically (stiffness.hpp); else empty
    bool completed = false;
    std::string failure;  // why the run stopped early (empty if completed)
    double t_reached = 0.0;
    double max_abs_tip_uy = 0.0;
    // The invariant monitor (after t_steady, the drive's last breakpoint): the Jacobi integral's largest change
    // and the largest strain energy U; vibration_energy < 0 when no row came after t_steady.
    double t_steady = 0.0;
    double jacobi_drift = 0.0;
    double vibration_energy = -1.0;
    long steps = 0;
    long rhs_evals = 0;
    long jacobian_evals = 0;
    double wall_seconds = 0.0;
};

using RowSink = std::function<void(const Row&)>;
/// Asked between output rows whether the run should stop (a signal, a failed output): the reason, which becomes
/// RunSummary::failure, or nullptr to go on. Called from the integrating thread, so it needs no locking.
using StopRequest = std::function<const char*()>;

class Model;

/// One run of a scene, in two steps so that everything that can refuse the scene (no model serves its
/// variant) does so before the caller creates any output.
class Simulation {
public:
    /// Chooses the model (make_model, which tells note about an on-demand compilation or a fallback); throws
    /// std::invalid_argument if none can serve the scene's variant, CompileError if compiling it failed.
    explicit Simulation(const Scene& scene, const std::function<void(const std::string&)>& note = {});
    ~Simulation();
    Simulation(const Simulation&) = delete;
    Simulation& operator=(const Simulation&) = delete;

    const Model& model() const { return *model_; }
    /// For a long run's progress line: "--stepper X is faster here (why)" when the scene names a stepper other
    /// than the one its stiffness calls for; empty otherwise.
    std::string faster_stepper_hint() const;

    /// Integrates from rest; every row reaches sink before the next step is taken, so a failed run keeps all
    /// rows up to the failure. Before each step to the next row it asks stop (if given), so an interrupted
    /// run ends on a whole row. Does not throw for numerical failure: see RunSummary::completed.
    RunSummary run(const RowSink& sink, const StopRequest& stop = {});

    /// Also called for every row, before sink, with the model's coordinates q (nq of them) at the row's time:
    /// for outputs that need the whole state, such as the fields along the beam.
    using StateObserver = std::function<void(double t, const double* q)>;
    void observe_states(StateObserver observer) { observer_ = std::move(observer); }

private:
    const Scene& scene_;
    std::unique_ptr<Model> model_;
    StateObserver observer_;
    std::string stepper_, stepper_why_;  // the scene's, or the automatic choice and why
};

/// Simulation(scene).run(sink).
RunSummary simulate(const Scene& scene, const RowSink& sink);

}  // namespace hubbeam
