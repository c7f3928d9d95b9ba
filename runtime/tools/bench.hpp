// Work-precision benchmark (hubbeam bench): run time against error for a grid of discretizations, steppers and
// tolerances on one scene, each run timed in process and compared with two references that hubbeam computes:
// the same discretization at a tight tolerance (time-integration error) and a discretization converged in DOFs
// (discretization error).
#pragma once

#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/option_lists.hpp>

namespace hubbeam {

/// The `bench` options as typed (checked by parse_bench_options, so that a bad value is one line naming it).
struct BenchArgs {
    std::string methods = "amm,fem,bim,bsim";
    std::string ny = "4,8";
    std::string nx;  // empty: the scene's
    std::string steppers = "rk8pd,gauss4,msadams";
    std::string rtols = "1e-6,1e-8,1e-10";
    std::string repeats = "3";
    std::string ref_ny = "12";
    std::string ref_method = "amm";
    std::string output;  // CSV; empty: bench.csv
    std::string plot;    // PREFIX: PREFIX-work.{png,svg} and PREFIX-dofs.{png,svg} by gnuplot
    bool yes = false;    // run a grid estimated at over an hour
    bool table1 = false; // the paper's Table 1 instead of a grid
};

struct BenchOptionError : OptionError {
    using OptionError::OptionError;
};

struct BenchOptions {
    std::vector<Method> methods;
    std::vector<int> ny, nx;
    std::vector<std::string> steppers;
    std::vector<double> rtols;
    int repeats = 3;
    int ref_ny = 12;
    Method ref_method = Method::amm;
    std::string output, plot;
    bool yes = false;
    bool table1 = false;
};

/// Checks and converts the typed options against the scene (nx defaults to the scene's); throws BenchOptionError.
BenchOptions parse_bench_options(const BenchArgs& args, const Scene& scene);

/// Every file bench writes with these options (the CSV; with --plot the figures, their script and data), named as
/// its messages name them: what the command checks against its inputs before the grid runs.
std::vector<NamedPath> bench_outputs(const BenchOptions& options);

/// One grid point's result: a CSV row.
struct BenchRow {
    VariantKey key;
    std::string stepper;
    std::string chosen;  // the stepper that ran: stepper, or what "auto" chose
    double rtol = 0.0, atol = 0.0;
    double time_error = 0.0;  // max |tip_uy - same discretization at a tight tolerance|, m
    double disc_error = 0.0;  // max |tip_uy - converged reference|, m
    double jacobi_drift = -1.0;  // max |J - J(t_steady)| after the drive ends, J; -1: no steady part
    double wall_median = 0.0, wall_min = 0.0, wall_max = 0.0;  // s, in process, over the repeats
    int repeats = 0;
    long steps = 0, rhs_evals = 0, jacobian_evals = 0;
    std::string status = "ok";  // or why the run (or its reference) stopped early
};

/// A run on the work-precision plane: its wall time (s) and its error (m).
struct WorkPoint {
    double wall = 0.0, error = 0.0;
};

/// The indices of points on the Pareto front, fastest first: the fastest point, then each slower point whose error
/// is below the front's best so far by more than `resolution` (the converged reference's own: differences within
/// it are ties, so a slower run that is "better" by less than that is not on the front).
std::vector<std::size_t> pareto_front(const std::vector<WorkPoint>& points, double resolution);

/// The CSV header of BenchRow.
const char* bench_header();

/// Runs the grid: the references first, then an estimate of the grid's time (refused over an hour unless
/// options.yes, as BenchOptionError), then every point, each row written to the CSV as it is measured and
/// progress on `progress` (one line per point). Asked stop between runs; a stopped grid keeps its finished rows
/// in a valid CSV. Returns the rows.
std::vector<BenchRow> run_bench(const Scene& scene, const BenchOptions& options, std::ostream& out,
                                std::ostream& progress, const StopRequest& stop);

/// The paper's Table 1 redone on scene (its spin-up to 4 rad/s): for each method at Ny = 4 (the scene's Nx),
/// the relative run time with the scene's stepper and with msadams (median of options.repeats), the error against
/// the converged reference in percent of the largest deflection, and the steady amplitude and frequency, beside
/// the paper's values. Prints the table to out, and a line per finished case to progress (the table comes at the
/// end, after about a minute).
void run_table1(const Scene& scene, const BenchOptions& options, std::ostream& out, std::ostream& progress,
                const StopRequest& stop);

}  // namespace hubbeam
