// Simulation: a scene's model and the stepper chosen for it (the automatic choice, with its pilot run), and its runs,
// each a Simulation::Run (run.hpp).
#include <hubbeam/simulate.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include <hubbeam/make_model.hpp>
#include "dynamics/integrate.hpp"
#include "dynamics/stepper.hpp"
#include "dynamics/stiffness.hpp"
#include "simulation/initial_state.hpp"
#include "simulation/run.hpp"
#include "simulation/run_rows.hpp"

namespace hubbeam {

namespace {

/// gauss4 from the run's initial coordinates q0 over plan's window at the scene's tolerances, the drive's breakpoints
/// stepped to as a run does; past plan's budget it stops once gauss4 has lost (pilot_lost with the costs of the pilot
/// so far). Deterministic, as the choice must be.
Pilot pilot_run(const Scene& scene, const Model& model, const std::vector<double>& q0, PilotPlan plan,
                const std::function<StepperCosts(const Pilot&)>& costs)
{
    FirstOrderSystem system(model, scene.motion, scene.axial, scene.controller(), &scene.parameters);
    std::vector<double> y = initial_state(system, model, scene.axial, q0);
    const std::unique_ptr<Stepper> stepper =
        make_stepper(system, gauss_stepper, 0.0, y.data(), scene.solver.h0, scene.solver.atol, scene.solver.rtol);
    Pilot pilot{.t = 0.0, .steps = 0, .rtol = scene.solver.rtol};
    std::vector<double> ends;  // of its steps, for the count of its first half
    const auto observe = [&] {
        pilot.steps = stepper->steps();
        pilot.steps_to_half = std::upper_bound(ends.begin(), ends.end(), 0.5 * pilot.t) - ends.begin();
        if (const auto band = stepper->banded_newton_flops()) {
            pilot.band_factor_flops = band->first;
            pilot.band_solve_flops = band->second;
        }
    };
    std::vector<double> stops = breaks_before(scene.motion, plan.t);
    stops.push_back(plan.t);
    bool lost = false;
    for (const double stop : stops) {
        while (pilot.t < stop && !lost) {
            if (stepper->step(pilot.t, stop, y.data(), INFINITY) != StepStatus::success) {
                pilot.failed = true;
                return pilot;
            }
            ends.push_back(pilot.t);
            if (stepper->steps() > plan.budget) {
                observe();
                lost = pilot_lost(pilot, costs(pilot), scene.output.t_end);
            }
        }
        if (lost) break;
        stepper->restart(pilot.t, y.data());
    }
    observe();
    return pilot;
}

/// The auxiliary states a run of scene carries (FirstOrderSystem::Auxiliary).
int auxiliary_count(const Scene& scene)
{
    return Auxiliary::of(scene.key(), scene.damped(), scene.controller(), &scene.parameters, scene.wants({"ki"}))
        .count();
}

}  // namespace

Simulation::Simulation(const Scene& scene, const std::function<void(const std::string&)>& note)
    : scene_(scene), model_(make_scene_model(scene, note))
{
    find_initial_state();
    choose_stepper();
}

Simulation::Simulation(const Scene& scene, std::shared_ptr<const Model> model) : scene_(scene), model_(std::move(model))
{
    const std::string variant = scene.key().name();
    if (model_ == nullptr) throw std::invalid_argument("a simulation of variant " + variant + " was given no model");
    if (!(model_->key() == scene.key()))
        throw std::invalid_argument("a model of variant " + model_->key().name() + " cannot run a scene of variant " +
                                    variant);
    // A model holds its parameters in its coefficients: one built at others would run another beam.
    if (!model_->parameters().empty() && model_->parameters() != scene.parameters.packed())
        throw std::invalid_argument("the model of variant " + variant +
                                    " was built at other physical parameters than the scene's");
    find_initial_state();
    choose_stepper();
}

void Simulation::find_initial_state()
{
    try {
        InitialCoordinates start = initial_coordinates(*model_, scene_);
        initial_q_ = std::move(start.q);
        initial_how_ = std::move(start.description);
    } catch (const std::runtime_error& e) {  // no equilibrium (a beam that buckles under its weight): the scene's fault
        throw std::invalid_argument("initial.state \"" + to_string(scene_.initial) + "\": " + e.what());
    }
}

void Simulation::choose_stepper()
{
    check_error_ = scene_.solver.error_check != ErrorCheck::off;
    whole_run_ = scene_.solver.error_check == ErrorCheck::full;
    stepper_ = scene_.solver.stepper;
    if (stepper_ == automatic_stepper_word) {
        const StepperChoice choice = automatic(scene_.solver.rtol);
        stepper_ = choice.stepper;
        stepper_why_ = choice.why;
    }
}

Simulation::~Simulation() = default;

StepperChoice Simulation::automatic(double rtol) const
{
    const double t_end = scene_.output.t_end;
    const int auxiliary = auxiliary_count(scene_);
    if (!rates_) rates_ = std::make_unique<RatesAtRest>(rates_at_rest(*model_, scene_.axial));
    if (!pilot_decided_ && needs_pilot(*model_, scene_.solver.rtol)) {
        const StepperCosts rule =
            predicted_costs(*model_, scene_.axial, scene_.solver.rtol, t_end, auxiliary, nullptr, rates_.get());
        const auto costs = [&](const Pilot& p) {
            return predicted_costs(*model_, scene_.axial, scene_.solver.rtol, t_end, auxiliary, &p, rates_.get());
        };
        pilot_ = std::make_unique<Pilot>(pilot_run(scene_, *model_, initial_q_, pilot_plan(rule, t_end), costs));
    }
    pilot_decided_ = true;  // needs_pilot's eigenvalues once, not at every check's re-run
    return automatic_stepper(*model_, scene_.axial, rtol, t_end, auxiliary,
                             rtol >= gauss4_tightest_rtol ? pilot_.get() : nullptr, rates_.get());
}

std::string Simulation::faster_stepper_hint() const
{
    if (!stepper_why_.empty()) return {};  // chosen automatically already
    const StepperChoice choice = automatic(scene_.solver.rtol);
    if (choice.stepper == stepper_) return {};
    return "--stepper " + choice.stepper + " suits this scene (" + choice.why.substr(choice.why.find(' ') + 1) + ")";
}

RunSummary Simulation::run(const RowSink& sink, const StopRequest& stop)
{
    return Run(*this)(sink, stop);
}

RunSummary simulate(const Scene& scene, const RowSink& sink)
{
    return Simulation(scene).run(sink);
}

}  // namespace hubbeam
