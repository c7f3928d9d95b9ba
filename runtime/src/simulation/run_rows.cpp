// States to rows (RowMaker, shared with the error check's re-runs) and a run's rows to its sink (Simulation::Run).
#include "simulation/run_rows.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <hubbeam/make_model.hpp>
#include <hubbeam/simulate.hpp>
#include "dynamics/integrate.hpp"
#include "simulation/column_check.hpp"
#include "simulation/run.hpp"
#include "simulation/sensitivity.hpp"

namespace hubbeam {

static_assert(root_load_members.size() == root_load_width, "a root load's member for each of its columns");

/// The drive's breakpoints inside (0, t_last), in order.
std::vector<double> breaks_before(const Motion& motion, double t_last)
{
    std::vector<double> breaks;
    for (double b : motion.breakpoints())
        if (b > 0.0 && b < t_last) breaks.push_back(b);
    std::sort(breaks.begin(), breaks.end());
    return breaks;
}

/// The equations a run of scene integrates: the state's, or with the sensitivities of scene.output.sensitivities.
std::unique_ptr<FirstOrderSystem> system_of(const Model& model, const Scene& scene)
{
    if (!scene.output.sensitivities.empty()) return std::make_unique<SensitivitySystem>(model, scene);
    return std::make_unique<FirstOrderSystem>(model, scene.motion, scene.axial, scene.controller(), &scene.parameters);
}

RowMaker::RowMaker(const Model& model, const Scene& scene, FirstOrderSystem& system)
    : model_(model),
      motion_(scene.motion),
      system_(system),
      control_(scene.controller()),
      sensitivities_(dynamic_cast<SensitivitySystem*>(&system)),
      q_(static_cast<std::size_t>(model.nq())),
      qd_(q_),
      derived_(sensitivities_ != nullptr
                   ? static_cast<std::size_t>(sensitivities_->count()) * sensitivity_outputs_of(model.key()).size()
                   : 0),
      extended_(control_ != nullptr || system.auxiliary().count() > 0)
{
    if (scene.output.loads == OutputLoads::root) {
        // One blade's variant serves every blade, each at its own parameters (pitch increment, tip mass).
        const VariantKey key = scene.key();
        for (int b = 0; b < scene.rotor.blades; ++b) loads_.emplace_back(key, scene.rotor.blade(scene.parameters, b));
        qdd_.resize(q_.size());
    }
}

Row RowMaker::operator()(double t, const double* y)
{
    system_.full_state(t, y, q_.data(), qd_.data());
    const double* q = q_.data();
    const double* qd = qd_.data();
    const bool torque = model_.key().drive == Drive::torque;
    const HubInput u = system_.input_at(t, y);  // under a control, the torque alone
    RowExtras extras;
    if (extended_) {
        if (torque) extras.tau = u.tau;
        if (control_ != nullptr) extras.theta_ref = motion_.at(t).theta;
        const auto at = [y](int i) { return i >= 0 ? y[i] : 0.0; };
        extras.controller_integral = at(system_.integral_index());
        extras.dissipated = at(system_.dissipated_index());
        extras.work = at(system_.work_index());
    }
    if (const CoordinateField* x = model_.coordinates().find(FieldKind::hub_x)) {
        const int ix = x->first, iy = model_.coordinates().first(FieldKind::hub_y);
        const std::vector<double>& p = model_.parameters();
        extras.hub_x = q[ix];
        extras.hub_y = q[iy];
        extras.hub_fx = -(p[index(Param::k_x)] * q[ix] + p[index(Param::c_x)] * qd[ix]);
        extras.hub_fy = -(p[index(Param::k_y)] * q[iy] + p[index(Param::c_y)] * qd[iy]);
    }
    const Tip tip = model_.tip(q);
    extras.tip_uz = tip.uz;
    extras.tip_phi = tip.phi;
    const Energy e = model_.energy(u, q, qd);
    const double theta = torque ? q[0] : u.theta, theta_dot = torque ? qd[0] : u.theta_dot;
    Row r{t,
          theta,
          theta_dot,
          tip.uy,
          tip.ux1,
          tip.ux,
          e.kinetic(),
          e.U,
          model_.momentum(u, q, qd),
          e.T2 - e.T0 + e.U,
          extras};
    if (sensitivities_ != nullptr) {
        sensitivities_->outputs(t, y, derived_.data());
        r.derived = derived_.data();
    }
    if (const int blades = blade_count(model_); blades > 1) {
        // Blades 2 .. N's tip columns, in tip_values' order (row_column_names').
        blades_.clear();
        for (int b = 1; b < blades; ++b) {
            const Tip tb = blade_tip(model_, q, b);
            for (const TipValue& v : tip_values)
                if (has_tip_value(model_.key(), v)) blades_.push_back(tb.*v.member);
        }
        r.blades = blades_.data();
    }
    if (!loads_.empty()) {
        // The accelerations the run's own equations give at this state: what the blade's inertial forces are made of.
        system_.full_acceleration(t, y, qdd_.data());
        load_values_.clear();
        for (const RootLoads& l : blade_root_loads(model_, loads_, u, q, qd, qdd_.data()))
            for (double RootLoads::*member : root_load_members) load_values_.push_back(l.*member);
        r.loads = load_values_.data();
    }
    return r;
}

/// The row at ti to the sink (the observer first), then the monitors; or why the run must stop.
std::string Simulation::Run::emit(double ti, const double* state, const RowSink& sink)
{
    const Row r = make_row_(ti, state);
    values_.clear();
    append_row_values(r, check_.columns().set, values_);
    for (std::size_t c = 0; c < values_.size(); ++c)
        if (!std::isfinite(values_[c])) {  // not a row to write: the run ends with the rows before it
            model_failure_ = "unstable: the solution became non-finite" + at_time(ti) + " (" +
                             check_.columns().names[c] + " is " + std::to_string(values_[c]) + ")";
            non_finite_ = true;
            t_ = ti;
            return model_failure_;
        }
    if (sim_.observer_) sim_.observer_(ti, make_row_.q());
    summary_.max_abs_tip_uy = std::max(summary_.max_abs_tip_uy, std::abs(r.tip_uy));
    sink(r);
    last_row_ = ti;
    if (!(std::abs(r.theta_dot) > critical_)) monitor(r);
    model_failure_ = model_limit(r, critical_, scene_.parameters.L);
    if (!model_failure_.empty()) t_ = ti;  // the run ends with this row, whatever the step reached
    return model_failure_;
}

}  // namespace hubbeam
