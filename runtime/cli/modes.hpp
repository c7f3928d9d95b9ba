// hubbeam modes and hubbeam linearize: natural frequencies against spin rate (a Campbell table) and the
// state-space model about one steady spin, as CSV files.
#pragma once

#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

#include <hubbeam/scene.hpp>
#include <hubbeam/modes_table.hpp>
#include <hubbeam/option_lists.hpp>

namespace hubbeam {

struct ModesOptionError : OptionError {
    using OptionError::OptionError;
};

/// Spin rates from a comma-separated list whose items are numbers >= 0 (rad/s) or ranges FIRST:LAST:STEP, each once,
/// in increasing order; throws ModesOptionError naming option for a bad item or more than 10000 rates.
std::vector<double> parse_spin_rates(const std::string& option, const std::string& text);

/// The `modes` options as typed.
struct ModesArgs {
    std::string omega;    // empty: 0 and the scene's steady rate (spin-up), or 0 (torque)
    std::string methods;  // empty: the scene's
    std::string ny;       // empty: the scene's
    std::string nz, nt;   // empty: the scene's
    std::string count = "4";  // modes printed per kind and spin rate
    std::string output;   // CSV; empty: none (the table is printed)
    std::string plot;     // PREFIX: the Campbell diagram PREFIX.{png,svg} (hubbeam plot campbell)
    std::string harmonics = default_harmonics;  // the lines omega = n Omega whose crossings are critical speeds
    std::string critical;             // CSV of the critical speeds; empty: none (they are printed)
    std::string elastodyn;            // ElastoDyn's BLADE MODE SHAPES section; empty: none
    bool quiet = false;   // the table to the CSV only, and one summary line printed
    std::string frame;    // "fixed" or "rotating"; empty: fixed where multi-blade coordinates apply
};

/// The table asked for (omegas, methods, ny, nz, nt, harmonics), and what of it is printed and written where.
struct ModesOptions : ModesRequest {
    int count = 4;
    std::string output, plot, critical, elastodyn;
    bool quiet = false;
};

/// Checks and converts the typed options against the scene; throws ModesOptionError.
ModesOptions parse_modes_options(const ModesArgs& args, const Scene& scene);

/// For each method, Ny and spin rate: the scene's variant linearized about the steady spin, the first `count` modes
/// of each kind (bending or edge and flap, twist, axial, hub, overdamped) printed to out (with options.quiet, only
/// how many modes there are), and every mode written to options.output if given (atomically), each with its
/// tracked label and MAC; then each variant's critical speeds (the crossings of its modes that oscillate with the
/// harmonics' excitation lines) printed, and written to
/// options.critical if given; with options.plot, the Campbell diagram; with options.elastodyn, the blade's mode shapes'
/// polynomials at the first spin rate in ElastoDyn's layout (elastodyn_section) and each fit's residual printed.
/// Throws std::runtime_error if a file or the figure cannot be written.
void run_modes(const Scene& scene, const ModesOptions& options, std::ostream& out);

/// --frame as typed for scene: empty is Frame::fixed (multi-blade coordinates where they apply, the blades' frames
/// elsewhere); "fixed" given for a scene where they do not apply is refused with multiblade_refusal's reason (or
/// [control]'s). Throws ModesOptionError.
Frame parse_frame(const std::string& text, const Scene& scene);

/// hubbeam linearize: A, B, C and D about the steady spin omega written to PREFIX-A.csv ... PREFIX-D.csv, each
/// with its row and column names; a summary to out. A rotor in multi-blade coordinates where they apply in frame.
void run_linearize(const Scene& scene, double omega, const std::string& prefix, std::ostream& out,
                   Frame frame = Frame::fixed);

}  // namespace hubbeam
