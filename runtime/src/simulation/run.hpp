// One run of Simulation::run (Simulation::Run): its state, shared by the files of its jobs: the setup (run.cpp),
// the stepping (run_stepping.cpp), the rows (run_rows.cpp), why it stops (run_stops.cpp) and the invariant monitor
// and summary (run_monitor.cpp).
#pragma once

#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <hubbeam/simulate.hpp>
#include "dynamics/integrate.hpp"
#include "dynamics/stepper.hpp"
#include "simulation/error_check.hpp"
#include "simulation/output_times.hpp"
#include "simulation/run_rows.hpp"

namespace hubbeam {

/// " at t = T s": where a message's event happened.
std::string at_time(double t);

/// The state at t = 0 of the model's coordinates q (nq, initial_coordinates: where initial.state starts): the kept
/// coordinates, the free hub's angle first; the rates 0 (a prescribed hub's rate is the drive's).
std::vector<double> initial_state(const FirstOrderSystem& system, const Model& model, Axial axial,
                                  const std::vector<double>& q);

/// One run of Simulation::run: the integration's state, with one member function per job (setup, the two stepping
/// loops, rows to the sink, the diagnosis of a stop, the checks and the summary).
class Simulation::Run {
public:
    explicit Run(const Simulation& simulation);
    RunSummary operator()(const RowSink& sink, const StopRequest& stop);

private:
    /// What free stepping carries from step to step: the step's start, the derivatives at its ends, the step limit.
    struct FreeStep {
        explicit FreeStep(std::size_t size) : y0(size), f0(size), f1(size), yi(size), y_mid(size), f_mid(size) {}
        std::vector<double> y0, f0, f1, yi, y_mid, f_mid;
        bool have_f0 = false, have_f1 = false;
        double t0 = 0.0;
        // Longest step whose interpolated rows stay within the tolerance (interpolation_error), learnt from the
        // steps that held rows: the quintic's error grows as h^6.
        double h_max = std::numeric_limits<double>::infinity();
    };

    std::string free_steps(const RowSink& sink, const StopRequest& stop);
    bool limit_interpolation(FreeStep& s);
    bool saturation_switch(FreeStep& s);
    void interpolate(const FreeStep& s, double t, double* y) const;
    std::string rows_in_step(FreeStep& s, long& i, const RowSink& sink, const StopRequest& stop);
    std::string row_steps(const RowSink& sink, const StopRequest& stop);
    const char* stop_requested(const StopRequest& stop);
    void restart();

    std::string emit(double ti, const double* state, const RowSink& sink);
    void start_summary();
    void monitor(const Row& r);

    std::string why_failed(StepStatus status);
    std::string failure_hint() const;
    std::string singular_cause() const;
    std::string over_budget() const;

    RunSummary finish(std::string failure);
    std::string untrustworthy();
    std::string tolerance_as_cause(const std::string& failure);

    const Simulation& sim_;
    const Scene& scene_;
    const Model& model_;
    const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    // The state's equations, or with the sensitivities beside them (system_of).
    const std::unique_ptr<FirstOrderSystem> owned_system_;
    FirstOrderSystem& system_;
    std::vector<double> y_;
    std::unique_ptr<Stepper> stepper_;
    RowMaker make_row_;
    const OutputTimes times_;
    std::vector<double> breaks_;  // the drive's, then the saturation switches found on the way
    std::size_t next_break_ = 0;
    const double critical_;  // critical_spin: passing it stops the run at once, not after metres of deflection
    const long budget_;      // solver.max_steps
    double t_ = 0.0, last_row_ = 0.0;
    RunSummary summary_;
    double jacobi0_ = 0.0;
    double u_min_ = INFINITY, u_max_ = -INFINITY;  // U's range since t_steady (the drift's reference under gravity)
    double potential0_ = 0.0;                      // U at t = 0: a start at an equilibrium holds it
    std::string model_failure_;                    // set when a row broke a model limit
    RunErrorCheck check_;                          // the error indicator; its columns are the ones a row writes
    std::vector<double> values_;                   // the last row's values (append_row_values)
    bool non_finite_ = false;                      // the run stopped at a row with a non-finite value, not written
};

}  // namespace hubbeam
