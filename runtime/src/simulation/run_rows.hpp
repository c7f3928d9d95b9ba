// What a run (run.hpp) and the error check's re-runs of it (error_check.cpp) share, so that both turn states
// into rows, meet the drive's breakpoints and stop at the model's limits alike. Defined in run_rows.cpp (model_limit
// in run_stops.cpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <hubbeam/config.hpp>
#include <hubbeam/simulate.hpp>
#include "dynamics/integrate.hpp"
#include "models/root_loads.hpp"

namespace hubbeam {

class SensitivitySystem;

// Times are compared relative to their size: an output time and a breakpoint closer than this are one
// instant, and t_end / dt_out within this of an integer counts as that integer.
inline constexpr double same_instant = 1e-12;

/// The equations a run of scene integrates: the state's, or with the sensitivities of scene.output.sensitivities.
std::unique_ptr<FirstOrderSystem> system_of(const Model& model, const Scene& scene);

/// The drive's breakpoints inside (0, t_last), in order.
std::vector<double> breaks_before(const Motion& motion, double t_last);

/// Why a row cannot stand, from the model's limits (empty if it can): the hub rate past the spin above which the
/// straight beam is unstable, a hub angle beyond max_hub_angle, or a tip deflection beyond the beam's length.
std::string model_limit(const Row& r, double critical, double L);

/// Rows from states: the hub's angle and rate (prescribed, or coordinates under torque), the tip, the energies, the
/// optional columns of a scene that has them (the torque, the reference, the auxiliary states), each blade's root
/// loads where the scene asks for them and a sensitivity system's derivative columns. The run's rows and the error
/// indicator's re-runs both come from here.
class RowMaker {
public:
    /// Rows of scene's run of model by system (its motion, controller and output.loads).
    RowMaker(const Model& model, const Scene& scene, FirstOrderSystem& system);
    /// The row of state y at t (its derivative columns valid until the next call); q() is then its full coordinates.
    Row operator()(double t, const double* y);
    const double* q() const { return q_.data(); }

private:
    const Model& model_;
    const Motion& motion_;
    FirstOrderSystem& system_;
    const Control* control_;
    SensitivitySystem* sensitivities_;  // null without sensitivities
    std::vector<double> q_, qd_, derived_, blades_;
    bool extended_;
    std::vector<BladeLoads> loads_;    // each blade's, where the scene asks for its root loads; else empty
    std::vector<double> qdd_, load_values_;
};

}  // namespace hubbeam
