// A run's configuration as plain data: what parsing a scene (scene.hpp) produces and a simulation consumes, with
// the words of its small enums; nothing here reads a file or integrates.
#pragma once

#include <array>
#include <hubbeam/motion.hpp>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "interface.hpp"
#include "terms.hpp"
#include "variant.hpp"

namespace hubbeam {

/// How the axial coordinates A move: with their own inertia (the model as derived), or quasi-statically,
/// following the axial equations' equilibrium at every instant (docs/model.md section 9).
enum class Axial { dynamic, quasi_static };
/// Words "dynamic", "quasi-static" (scene key model.axial, option --axial).
std::string to_string(Axial);
bool parse(std::string_view, Axial&);
template <>
std::vector<std::string> words<Axial>();

/// Where steps end: free (the tolerance alone chooses them; rows between step ends are interpolated by
/// interpolate_state) or at rows (every output time ends a step, as GSL's driver does: exact, but the row
/// spacing caps the step).
enum class Stepping { free, rows };
/// Words "free", "rows" (scene key solver.stepping, option --stepping).
std::string to_string(Stepping);
bool parse(std::string_view, Stepping&);
template <>
std::vector<std::string> words<Stepping>();

/// The stepper word that asks for the stepper of the scene's stiffness (stiffness.hpp).
inline constexpr const char* automatic_stepper_word = "auto";

/// Which implementation serves a variant (make_model.hpp).
enum class ModelSource { automatic, generated, assembled };
/// Words "auto", "generated", "assembled" (scene key model.source, option --source).
std::string to_string(ModelSource);
bool parse(std::string_view, ModelSource&);
template <>
std::vector<std::string> words<ModelSource>();

/// Whether a run checks its own error by re-running windows at a tighter tolerance, or the whole run if it is looser
/// than the defaults (RunSummary::estimated_error): on by default; off saves its cost (about 13 % of the main job)
/// where the tolerance is known to be adequate; full re-runs the whole run alongside at any tolerance, so that an
/// error made between the windows is seen too (the whole process of a cases/ scene then takes 1.4 to 3.2 times).
enum class ErrorCheck { on, off, full };
std::string to_string(ErrorCheck);
bool parse(std::string_view, ErrorCheck&);
template <>
std::vector<std::string> words<ErrorCheck>();

/// Whether the step-size control weighs a run's sensitivities beside its state (docs/sensitivities.md): on by default;
/// off lets the state alone choose the steps, as CVODES's errconS = false, at an accuracy of the sensitivities that
/// the error check measures.
enum class SensitivityErrorControl { on, off };
std::string to_string(SensitivityErrorControl);
bool parse(std::string_view, SensitivityErrorControl&);
template <>
std::vector<std::string> words<SensitivityErrorControl>();

struct SolverOptions {
    std::string stepper = automatic_stepper_word;  // a name from stepper_names() (integrate.hpp), or automatic
    double rtol = 1e-8;
    double atol = 1e-10;
    double h0 = 1e-4;  // first trial step (s)
    Stepping stepping = Stepping::free;
    long max_steps = 10'000'000;  // a run that needs more steps stops with the reason its steps are short
    ErrorCheck error_check = ErrorCheck::on;
    SensitivityErrorControl sensitivity_error_control = SensitivityErrorControl::on;
};

/// The most rows a run may write (t_end / dt_out): 10^8 rows is about 20 GB of CSV.
inline constexpr long max_output_rows = 100'000'000;

/// The control gains a sensitivity can be taken by (beside the physical parameters, Param): [control]'s keys.
inline constexpr std::array<const char*, 4> gain_names = {"kp", "kd", "ki", "k_tip"};

/// Which loads a run's rows carry beside the tip's (scene key output.loads): none, or each blade's root loads by force
/// summation (docs/model.md section 13.3: root_edge_moment, ...).
enum class OutputLoads { none, root };
std::string to_string(OutputLoads);
bool parse(std::string_view, OutputLoads&);
template <>
std::vector<std::string> words<OutputLoads>();

struct OutputOptions {
    double t_end = 30.0;   // s
    double dt_out = 0.01;  // s; rows fall on exact multiples of dt_out
    std::string file;      // CSV path; empty: derived from the scene name by the command line (a file or an
                           // override cannot set it empty, nor put a NUL in it)
    /// Parameters whose derivatives the run integrates and writes (docs/sensitivities.md): symbols of Param
    /// (interface.hpp) and the control gains kp, kd, ki, k_tip; empty: none.
    std::vector<std::string> sensitivities;
    OutputLoads loads = OutputLoads::none;
};

/// The most blades a rotor may have ([rotor] blades): rotors in the field have 1 to 8; the bound keeps a mistyped
/// count from building a model of a million blades.
inline constexpr int max_blades = 64;

/// A rotor of identical blades on one hub (docs/model.md section 13): blade b (1-based) at azimuth
/// theta + 2 pi (b - 1)/blades, with its own pitch increment and tip mass. One blade: the scene's beam alone.
struct Rotor {
    int blades = 1;
    std::vector<double> pitch_offsets;  // rad, one per blade, added to the pitch; empty: none
    std::vector<double> tip_masses;     // kg, one per blade, in place of tip.mass; empty: tip.mass on every blade

    /// Blade b's azimuth offset from theta, 2 pi b / blades (b 0-based).
    double azimuth(int b) const;
    /// Blade b's parameters (b 0-based): the scene's, with its pitch increment and tip mass, and the hub's inertia on
    /// blade 0 alone (each blade's model carries the hub terms it is given; the rotor sums them once).
    Parameters blade(const Parameters& p, int b) const;
};
/// The damping of a blade's own modes at rest (docs/model.md section 11.5; ElastoDyn's BldFlDmp, BldEdDmp): fractions of
/// critical of its first flapwise-dominated modes and of its first edgewise-dominated ones (a planar blade's in-plane
/// bending modes), in order of frequency; the other modes undamped. Empty: none.
struct ModalDamping {
    std::vector<double> flap, edge;
    /// Whether any ratio is given (what the count of the blade's modes is checked against).
    bool given() const { return !flap.empty() || !edge.empty(); }
    /// Whether any ratio damps: ratios of 0 leave the scene as it is without them.
    bool damps() const
    {
        for (const std::vector<double>* v : {&flap, &edge})
            for (double z : *v)
                if (z != 0.0) return true;
        return false;
    }
};

/// Where a run starts (scene key initial.state, docs/scene.md): at rest (the beam straight and unloaded), at the
/// static equilibrium of its elastic coordinates under the constant loads at the drive's initial angle and rate, or
/// at the steady spin of that rate (refused where the scene has none: gravity in the plane of a spinning hub).
enum class InitialState { rest, static_equilibrium, steady };
/// Words "rest", "static", "steady" (scene key initial.state, option --initial).
std::string to_string(InitialState);
bool parse(std::string_view, InitialState&);
template <>
std::vector<std::string> words<InitialState>();

/// Factors on a blade file's columns (scene table [blade_scale], docs/scene.md): BModes' property multipliers, as a
/// main input file gives them; io/scene_io.hpp's blade_scale_fields names each and its column. 1 each leaves the
/// file as it is.
struct BladeScale {
    double mass = 1.0, inertia_flap = 1.0, inertia_edge = 1.0, stiffness_flap = 1.0, stiffness_edge = 1.0,
           stiffness_torsion = 1.0, stiffness_axial = 1.0, cg_offset = 1.0, tc_offset = 1.0;
};

struct Scene {
    std::string path;  // the file it came from, for messages
    /// The other files it was read from, each with its key: {"beam.profile", FILE}, {"beam.blade_file", FILE},
    /// {"motion.file", FILE}, as scene.hpp's scene_files lists them from the key table's file keys. A command's outputs
    /// are checked against these and path (output_file.hpp's scene_inputs).
    std::vector<std::pair<std::string, std::string>> tables;
    /// beam.blade_stations: the stations a blade file was resampled at, 0 for its own (docs/scene.md).
    int blade_stations = 0;
    BladeScale blade_scale;  // [blade_scale]: factors on beam.blade_file's columns
    Parameters parameters;
    Motion motion;
    std::optional<Control> control;  // [control]: motion is then the reference of a torque-driven hub
    VariantKey variant;              // drive follows motion, or control
    ModelSource source = ModelSource::automatic;
    Axial axial = Axial::dynamic;  // quasi-static: A follows the axial equilibrium (integrate.hpp)
    SolverOptions solver;
    OutputOptions output;
    Rotor rotor;
    ModalDamping modal_damping;  // [damping] flap_ratios, edge_ratios: each blade's
    InitialState initial = InitialState::rest;  // initial.state
    /// The hub's rate at t = 0 (rad/s): a prescribed rotation's; a torque-driven hub starts at rest.
    double initial_theta_dot() const { return drive() == Drive::torque ? 0.0 : motion.at(0.0).theta_dot; }

    /// Whether its model dissipates: its variant's damping or support (dissipates, terms.hpp) or modal damping.
    bool damped() const { return dissipates(key()) || modal_damping.damps(); }
    /// The control, or nullptr: what the integrator and the linearization take.
    const Control* controller() const { return control ? &*control : nullptr; }
    /// The hub's drive: torque under a control (its motion is a reference), else the one the motion implies.
    Drive drive() const { return control ? Drive::torque : motion.drive(); }
    /// The variant this scene runs: its discretization with the drive its motion and control imply and the extra
    /// terms its parameters use (either may have been changed in code since loading). A term whose values are all
    /// zero is left out: the paper's scenes run the paper's variants.
    /// Whether output.sensitivities asks for any of names: a term (or the controller's integral) it asks for is
    /// kept even where its value is zero.
    bool wants(std::initializer_list<const char*> names) const
    {
        for (const std::string& s : output.sensitivities)
            for (const char* n : names)
                if (s == n) return true;
        return false;
    }
    VariantKey key() const
    {
        VariantKey k = variant;
        k.drive = drive();
        // A sensitivity to a term's value needs the term, even at zero (where it reproduces the scene).
        // A rotor's blades run one variant: a term is carried when any blade's values use it. Each blade's values
        // packed once (Rotor::blade copies the parameters, a profile's table with them).
        std::vector<std::vector<double>> blades;
        for (int b = 0; b < rotor.blades; ++b)
            blades.push_back((rotor.blades > 1 ? rotor.blade(parameters, b) : parameters).packed());
        for (const TermInfo& t : terms()) {
            if (!t.selected_by_values) continue;
            bool used = false;
            for (const std::vector<double>& p : blades)
                for (Param q : t.params) used = used || p[index(q)] != 0.0 || wants({param_names[index(q)]});
            t.set(k.extras, used);
        }
        return k;
    }
};

}  // namespace hubbeam
