// Simulation: one scene integrated from its initial state (initial.state: rest, unless it says otherwise), rows
// handed to a sink at exact multiples of dt_out. The library entry point under the command line.
#pragma once

#include <cstddef>
#include <functional>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <hubbeam/config.hpp>
#include <hubbeam/model.hpp>

namespace hubbeam {

/// The values of a row's optional columns (optional_columns): those a scene does not have stay 0 and are not written.
struct RowExtras {
    double tip_uz = 0.0, tip_phi = 0.0;
    double tau = 0.0, theta_ref = 0.0, controller_integral = 0.0, dissipated = 0.0, work = 0.0;
    double hub_x = 0.0, hub_y = 0.0, hub_fx = 0.0, hub_fy = 0.0;
};

/// One output row: the columns of row_columns, in that order, then the optional ones its scene has.
struct Row {
    double t, theta, theta_dot, tip_uy, tip_ux1, tip_ux, kinetic, potential, momentum, jacobi;
    RowExtras extras{};
    /// A sensitivity run's derivative columns (ColumnSet::derived names them), valid while the sink runs; else null.
    const double* derived = nullptr;
    /// A rotor's blades 2 .. N: each blade's tip columns (ColumnSet::blade_columns), valid while the sink runs; else
    /// null.
    const double* blades = nullptr;
    /// Each blade's root loads (ColumnSet::loads: root_load_columns, blade by blade), valid while the sink runs; else
    /// null.
    const double* loads = nullptr;
};

/// One column of the output: its name in the CSV header and the Python module, its unit, what it holds.
struct RowColumn {
    const char* name;
    const char* unit;
    double Row::*member;
    const char* meaning;
};

/// The output row's columns, the one definition that the CSV header and lines, the Python module and the docs read.
/// The Jacobi integral T2 - T0 + U (T split by degree in the coordinates' rates) is constant whenever the drive is
/// steady: at constant prescribed spin, and, where theta is a coordinate, with zero torque (then it is T + U).
inline constexpr RowColumn row_columns[] = {
    {"t", "s", &Row::t, "time"},
    {"theta", "rad", &Row::theta, "hub angle"},
    {"theta_dot", "rad/s", &Row::theta_dot, "hub rate"},
    {"tip_uy", "m", &Row::tip_uy, "tip transverse deflection u_y(L)"},
    {"tip_ux1", "m", &Row::tip_ux1, "tip axial stretch u_x1(L)"},
    {"tip_ux", "m", &Row::tip_ux, "tip axial displacement u_x(L): u_x1(L) - 1/2 B^T H(L) B, order zero u_x1(L)"},
    {"kinetic", "J", &Row::kinetic, "kinetic energy T"},
    {"potential", "J", &Row::potential, "strain energy U"},
    {"momentum", "N m s", &Row::momentum, "angular momentum about the axis dT/dtheta_dot"},
    {"jacobi", "J", &Row::jacobi, "Jacobi integral T2 - T0 + U"},
};
inline constexpr std::size_t row_width = std::size(row_columns);

/// A column that only some scenes' rows have (a scene without a controller, damping or a torque law writes the
/// table of row_columns alone, as ever).
struct OptionalColumn {
    const char* name;
    const char* unit;
    double RowExtras::*member;
    const char* meaning;
    const char* when;  // which scenes have it
};
inline constexpr OptionalColumn optional_columns[] = {
    {"tip_uz", "m", &RowExtras::tip_uz, "tip flapwise deflection u_z(L)", "nz > 0"},
    {"tip_phi", "rad", &RowExtras::tip_phi, "tip twist phi(L)", "nt > 0"},
    {"tau", "N m", &RowExtras::tau, "hub torque applied (after saturation)",
     "a torque-driven hub under a controller or a torque law, or with damping"},
    {"theta_ref", "rad", &RowExtras::theta_ref, "the controller's reference angle", "[control]"},
    {"controller_integral", "rad s", &RowExtras::controller_integral, "int (theta - theta_ref) dt",
     "[control] with ki > 0"},
    {"dissipated", "J", &RowExtras::dissipated, "energy dissipated by damping, int 2 D dt", "damping"},
    {"work", "J", &RowExtras::work, "work of the hub torque, int tau theta_dot dt", "as tau"},
    {"hub_x", "m", &RowExtras::hub_x, "the hub centre's displacement x_h along the inertial x", "[support]"},
    {"hub_y", "m", &RowExtras::hub_y, "the hub centre's displacement y_h along the inertial y", "[support]"},
    {"hub_fx", "N", &RowExtras::hub_fx, "the support's force on the hub along x, -(k_x x_h + c_x x_h_dot)", "[support]"},
    {"hub_fy", "N", &RowExtras::hub_fy, "the support's force on the hub along y, -(k_y y_h + c_y y_h_dot)", "[support]"},
};
inline constexpr std::size_t optional_width = std::size(optional_columns);
// Every member of Row has its column (a member added to Row and not here fails to compile).
static_assert(sizeof(Row) == (row_width + optional_width) * sizeof(double) + 3 * sizeof(const double*));
static_assert(sizeof(RowExtras) == optional_width * sizeof(double));

/// A blade's root loads (scene key output.loads = "root"; docs/model.md section 13.2): the load the blade exerts on
/// the hub at x = 0 by force summation, in the blade's root frame; a rotor's carry the blade's number ("_2").
struct LoadColumn {
    const char* name;
    const char* unit;
    const char* meaning;
};
inline constexpr LoadColumn root_load_columns[] = {
    {"root_edge_moment", "N m", "edgewise bending moment, about the flap axis e3 (EI u_y''(0) at rest)"},
    {"root_flap_moment", "N m", "flapwise bending moment, about -e2 (EI_flap u_z''(0) at rest)"},
    {"root_shear_edge", "N", "shear force along e2, in the plane of rotation towards the direction of travel"},
    {"root_shear_flap", "N", "shear force along e3, the spin axis turned by the precone"},
    {"root_axial_force", "N", "axial force along e1, positive in tension"},
};
inline constexpr std::size_t root_load_width = std::size(root_load_columns);

/// Which optional columns a run's rows carry: bit i for optional_columns[i].
struct ColumnSet {
    unsigned bits = 0;
    /// The derivative columns after the optional ones, "d_OUTPUT/d_PARAM" (sensitivity_columns), read from Row::derived.
    std::vector<std::string> derived = {};
    /// A rotor's blades (docs/model.md section 13): with more than one, the tip columns carry the blade's number
    /// ("tip_uy_1"), and blades 2 .. N's follow the optional ones, read from Row::blades.
    int blades = 1;
    /// Each blade's root loads (root_load_columns, blade by blade) after the blades' tip columns, read from Row::loads.
    bool loads = false;
    bool has(std::size_t i) const { return (bits >> i & 1u) != 0; }
    /// The tip columns of one blade: those of tip_values (model.hpp) the rows have.
    std::size_t blade_columns() const;
    /// The root loads' columns: root_load_width for each blade, or none.
    std::size_t load_columns() const { return loads ? root_load_width * static_cast<std::size_t>(blades) : 0; }
    std::size_t count() const
    {
        std::size_t n = 0;
        for (std::size_t i = 0; i < optional_width; ++i) n += has(i) ? 1 : 0;
        return n + static_cast<std::size_t>(blades - 1) * blade_columns() + load_columns() + derived.size();
    }
};
/// Calls value(x) for each value of row a CSV line or the Python module's array holds, in column order: row_columns',
/// then the optional columns of set.
template <class Value>
void for_each_value(const Row& row, const ColumnSet& set, Value value)
{
    for (const RowColumn& c : row_columns) value(row.*c.member);
    for (std::size_t i = 0; set.bits != 0 && i < optional_width; ++i)
        if (set.has(i)) value(row.extras.*optional_columns[i].member);
    const std::size_t blade_values = static_cast<std::size_t>(set.blades - 1) * set.blade_columns();
    for (std::size_t i = 0; i < blade_values; ++i) value(row.blades[i]);
    for (std::size_t i = 0; i < set.load_columns(); ++i) value(row.loads[i]);
    for (std::size_t i = 0; i < set.derived.size(); ++i) value(row.derived[i]);
}
/// The outputs a sensitivity run differentiates, in column order: the hub's, then the tip's (tip_values, where the
/// variant has them): what a reader of the rows plots (the energies follow from these).
inline constexpr const char* sensitivity_outputs[] = {"theta", "theta_dot"};
/// The outputs a sensitivity run of key's variant differentiates: sensitivity_outputs, then each of tip_values the
/// variant has (tip_uz where nz > 0, tip_phi where nt > 0).
std::vector<std::string> sensitivity_outputs_of(const VariantKey& key);
/// The most derivative columns a row can carry: every output by every parameter and gain.
inline constexpr std::size_t max_derived_columns =
    (param_count + gain_names.size()) * (std::size(sensitivity_outputs) + std::size(tip_values));
/// "d_OUTPUT/d_PARAM" for each parameter (in the order given), each output of key's variant within it.
std::vector<std::string> sensitivity_columns(const std::vector<std::string>& parameters, const VariantKey& key);
/// The optional columns of a scene's rows (none for the paper's scenes).
ColumnSet optional_columns_of(const Scene& scene);
/// The column names of rows with the optional columns of set: row_columns', then theirs (for_each_value's order).
std::vector<std::string> row_column_names(const ColumnSet& set);
/// The CSV header of rows with the optional columns of set: row_column_names joined by commas.
std::string row_header(const ColumnSet& set);
static_assert([] {
    for (std::size_t i = 0; i < row_width; ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (row_columns[i].member == row_columns[j].member) return false;
    return true;
}(), "two columns read the same member of Row");

/// The CSV header: row_columns' names joined by commas.
const char* row_header();

/// A run whose Jacobi integral drifts by more than this fraction of the vibration energy once the drive is steady
/// is reported as untrustworthy (exit 1): correct runs drift by 1e-8 of it, runs at absurd tolerances by 100 %.
inline constexpr double invariant_tolerance = 1e-2;

/// A run whose estimated error (RunSummary::estimated_error) exceeds this fraction of a column's largest value is
/// reported as untrustworthy (exit 1): the cases/ scenes at their tolerances estimate 1.2e-3 or less (the axial
/// stretch of cases/torque_tau1.toml, 2e-8 m against atol 1e-10), the rest 1e-5 or less.
inline constexpr double error_tolerance = 1e-2;

struct RunSummary {
    std::string variant;  // VariantKey::name()
    std::string source;   // "generated" or "assembled", then where from ("generated, cached")
    std::string algebra;  // how accelerations are computed (FirstOrderSystem::linear_algebra())
    std::string stepper;      // the step type that ran
    std::string stepper_why;  // why, when it was chosen automatically (stiffness.hpp); else empty
    std::string newton;       // how gauss4 solved its Newton systems (dense, or a bordered band); empty for the others
    std::string initial;      // how the start of initial.state was found (initial_state.hpp); empty at rest
    bool completed = false;
    std::string failure;  // why the run stopped early (empty if completed)
    double t_reached = 0.0;
    double max_abs_tip_uy = 0.0;
    // The invariant monitor (after t_steady, the drive's last breakpoint): the Jacobi integral's largest change
    // and the largest strain energy U; vibration_energy < 0 when no row came after t_steady.
    // With damping or a controlled hub the balance E + dissipated - work (E the Jacobi integral, T + U under torque)
    // is what stays constant (energy_balance); under a prescribed rotation with gravity nothing does and the monitor
    // is off (monitor_off says why), as it is for a run that ends before its drive does.
    double t_steady = 0.0;
    double jacobi_drift = 0.0;
    double vibration_energy = -1.0;
    bool energy_balance = false;
    std::string monitor_off;
    // What vibration_energy is, as the summary and the untrustworthy message name it ("the vibration energy": the
    // largest U since t_steady; under gravity, whose potential can keep U <= 0, U's range since).
    std::string invariant_reference;
    // The error indicator: the rows of a window at the start and one at the end re-run from the run's own state
    // there at check_rtol, check_atol (ten times tighter), compared in every column the run writes.
    // estimated_error is the largest difference relative to that column's largest value in the run, the end
    // window's scaled by the square root of the run's length over the window's (the windows' errors adding up
    // as independent ones); < 0 when not checked.
    // Under error_check full the whole run is re-run alongside and compared at every row instead, unscaled.
    double estimated_error = -1.0;
    std::string error_column;  // where it is largest
    std::string error_from = "windows";  // what was re-run: "windows", "the whole run", or "the run to t = 7 s"
    double check_rtol = 0.0, check_atol = 0.0;
    long steps = 0;
    long rejected_steps = 0;  // steps the error test failed and the stepper took again shorter (not in steps)
    long rhs_evals = 0;
    long jacobian_evals = 0;
    double wall_seconds = 0.0;        // the integration's, without the error check
    double check_wall_seconds = 0.0;  // the error check's
};

using RowSink = std::function<void(const Row&)>;
/// Asked between output rows whether the run should stop (a signal, a failed output): the reason, which becomes
/// RunSummary::failure, or nullptr to go on. Called from the integrating thread, so it needs no locking.
using StopRequest = std::function<const char*()>;

class Model;
struct Pilot;
struct RatesAtRest;
struct StepperChoice;

/// One run of a scene, in two steps so that everything that can refuse the scene (no model serves its
/// variant) does so before the caller creates any output.
class Simulation {
public:
    /// Keeps its own copy of scene, which the caller may then change or let go. Chooses the model (make_model, which
    /// tells note about an on-demand compilation or a fallback); throws
    /// std::invalid_argument if none can serve the scene's variant or the scene has no initial state of its
    /// initial.state (no steady spin, no equilibrium), CompileError if compiling it failed.
    explicit Simulation(const Scene& scene, const std::function<void(const std::string&)>& note = {});
    /// Runs scene on model, which other runs, on other threads too, may share: a run only reads its model and owns
    /// its work arrays. Throws std::invalid_argument if model is null, serves a variant other than the scene's, was
    /// built at other parameters, or the scene has no initial state of its initial.state.
    Simulation(const Scene& scene, std::shared_ptr<const Model> model);
    ~Simulation();
    Simulation(const Simulation&) = delete;
    Simulation& operator=(const Simulation&) = delete;

    const Model& model() const { return *model_; }
    /// For a long run's progress line: "--stepper X is faster here (why)" when the scene names a stepper other
    /// than the one its stiffness calls for; empty otherwise.
    std::string faster_stepper_hint() const;

    /// Integrates from the scene's initial state (initial.state); every row reaches sink before the next step is
    /// taken, so a failed run keeps all rows up to the failure. Before each step to the next row it asks stop (if
    /// given), so an interrupted run ends on a whole row. Does not throw for numerical failure: see
    /// RunSummary::completed. Then the run's rows are checked (the invariant monitor; the error indicator, see
    /// check_error), which can make a run that reached t_end untrustworthy, and a failure that a tighter tolerance
    /// avoids is said to be the tolerance's.
    RunSummary run(const RowSink& sink, const StopRequest& stop = {});

    /// Also called for every row, before sink, with the model's coordinates q (nq of them) at the row's time:
    /// for outputs that need the whole state, such as the fields along the beam.
    using StateObserver = std::function<void(double t, const double* q)>;
    void observe_states(StateObserver observer) { observer_ = std::move(observer); }

    /// Whether run() checks its error by re-running windows at a tighter tolerance (RunSummary::estimated_error;
    /// on by default): off for a caller that measures the error itself against a reference.
    void check_error(bool on) { check_error_ = on; }

private:
    class Run;  // one call of run(): simulation/run.hpp
    /// The scene's stepper, or the automatic choice and why; whether the error is checked.
    void choose_stepper();
    /// initial_q_ and initial_how_ of the scene's initial.state, once for the pilot and every run.
    void find_initial_state();
    /// The automatic choice at rtol, with the pilot run (made once, at the first call that needs one).
    StepperChoice automatic(double rtol) const;
    const Scene scene_;  // its own copy: a caller's scene may be a temporary, or change after
    std::shared_ptr<const Model> model_;
    StateObserver observer_;
    std::vector<double> initial_q_;  // the model's coordinates at t = 0 (initial.state)
    std::string initial_how_;        // how they were found (RunSummary::initial); empty at rest
    std::string stepper_, stepper_why_;  // the scene's, or the automatic choice and why
    // Worked out at the first question that needs them (the automatic stepper's, faster_stepper_hint's) and kept: a
    // memo, which is why const questions may fill it. A Simulation is one run's, never shared between threads.
    mutable std::unique_ptr<RatesAtRest> rates_;  // the model's rates at rest, once (stiffness.hpp)
    mutable std::unique_ptr<Pilot> pilot_;  // gauss4's measured start under a hub torque (stiffness.hpp)
    mutable bool pilot_decided_ = false;    // whether the scene needs one was asked
    bool check_error_ = true;
    bool whole_run_ = false;  // error_check full: the whole run re-run alongside, not windows
};

/// Simulation(scene).run(sink).
RunSummary simulate(const Scene& scene, const RowSink& sink);

}  // namespace hubbeam
