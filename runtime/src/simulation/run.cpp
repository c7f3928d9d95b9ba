// A run's setup (Simulation::Run): the system, the stepper and the row maker of the scene, and the summary's
// description of the run; then the stepping its scene asks for.
#include "simulation/run.hpp"

#include <vector>

#include <hubbeam/simulate.hpp>
#include "dynamics/stiffness.hpp"
#include "models/model_operations.hpp"
#include "simulation/run_rows.hpp"

namespace hubbeam {

std::vector<double> initial_state(const FirstOrderSystem& system, const Model& model, Axial axial,
                                  const std::vector<double>& q)
{
    std::vector<double> y(static_cast<std::size_t>(system.size()), 0.0);
    // The positions are the kept coordinates in q's order (quasi-static A follows from them, as in every step).
    const std::vector<int> kept = kept_coordinates(model.coordinates(), axial);
    for (std::size_t i = 0; i < kept.size(); ++i) y[i] = q[static_cast<std::size_t>(kept[i])];
    return y;
}

Simulation::Run::Run(const Simulation& simulation)
    : sim_(simulation),
      scene_(simulation.scene_),
      model_(*simulation.model_),
      owned_system_(system_of(model_, scene_)),
      system_(*owned_system_),
      y_(initial_state(system_, model_, scene_.axial, simulation.initial_q_)),
      stepper_(make_stepper(system_, sim_.stepper_, 0.0, y_.data(), scene_.solver.h0, scene_.solver.atol,
                            scene_.solver.rtol)),
      make_row_(model_, scene_, system_),
      times_(scene_.output),
      breaks_(breaks_before(scene_.motion, times_(times_.last()))),
      critical_(critical_spin(model_)),
      budget_(scene_.solver.max_steps),
      check_(scene_, model_, system_, y_, times_(times_.last()),
             !sim_.check_error_ ? ErrorCheck::off
             : sim_.whole_run_  ? ErrorCheck::full
                                : ErrorCheck::on,
             [&sim = sim_](double rtol) { return sim.automatic(rtol).stepper; })
{
    start_summary();
}

RunSummary Simulation::Run::operator()(const RowSink& sink, const StopRequest& stop)
{
    if (std::string failure = emit(0.0, y_.data(), sink); !failure.empty()) return finish(failure);
    return finish(scene_.solver.stepping == Stepping::free ? free_steps(sink, stop) : row_steps(sink, stop));
}

}  // namespace hubbeam
