// What the files of hubbeam bench share (bench.cpp: the options, the grid and the run; bench_runs.cpp: running
// and timing; bench_error.cpp: the error measure and the Pareto front; bench_csv.cpp: the CSV and the summary's
// numbers; bench_figures.cpp: the figures; bench_table1.cpp: the paper's Table 1): private to them.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include "bench.hpp"

namespace hubbeam::bench_parts {

// The files of --plot PREFIX: the two figures (each .png and .svg), their script, the data the script reads.
inline constexpr const char* figure_suffixes[] = {"-work", "-dofs"};
inline constexpr const char* script_suffix = ".gp";
inline constexpr const char* data_suffixes[] = {"-front.dat", "-dofs.dat"};  // the Pareto front, the DOF convergence

// The tight reference: the most accurate explicit stepper, a step at every row, tolerances near round-off.
inline constexpr const char* reference_stepper = "rk8pd";
inline constexpr double reference_rtol = 1e-12, reference_atol = 1e-14;
// A probe integrates this fraction of the scene to estimate a run's time.
inline constexpr double probe_fraction = 1.0 / 30.0;
inline constexpr double refuse_seconds = 3600.0;

/// A run of scene collected into rows, its summary, and the wall time of Simulation::run.
struct Collected {
    std::vector<Row> rows;
    RunSummary summary;
};

Collected collect(const Scene& scene, const StopRequest& stop);

/// A point's repeated runs: the first run's rows and summary, and every run's wall time, sorted. Repeats stop at
/// the first run that does not complete.
struct Repeated {
    Collected first;
    std::vector<double> walls;
    double median() const
    {
        const std::size_t n = walls.size();
        return n % 2 == 1 ? walls[n / 2] : 0.5 * (walls[n / 2 - 1] + walls[n / 2]);
    }
};

Repeated repeat(const Scene& s, int repeats, const StopRequest& stop);

/// The largest |tip_uy| difference between two runs' rows, over the rows both have.
double max_difference(const std::vector<Row>& a, const std::vector<Row>& b);
/// A row's error against the converged solution: the larger of its two errors (their maximum is that error up to
/// the reference's own).
double overall_error(const BenchRow& r);
/// Prints the rows on the Pareto front, fastest first.
void print_front(const std::vector<BenchRow>& rows, double resolution, std::ostream& out);

/// base as variant key with the stepper, tolerances and stepping given.
Scene variant_scene(const Scene& base, const VariantKey& key, const std::string& stepper, double rtol, double atol,
                    Stepping stepping);
/// scene as variant k at the tight reference tolerance, with a step at every row.
Scene tight_scene(const Scene& scene, const VariantKey& k);

/// A CSV number; empty for a negative one (no data).
std::string number(double x);
/// A row of the bench CSV, its columns bench_header()'s.
std::string csv_row(const BenchRow& r);
/// A duration for the messages: ms, s or min.
std::string seconds_text(double s);
/// x to three significant digits, for the messages.
std::string three_digits(double x);

/// stepper_names() and the automatic choice: what a figure's series can be.
std::vector<std::string> steppers_and_auto();

/// The converged reference's run, why it stopped (empty: it did not), and its resolution in m (0: unknown).
struct References {
    Collected converged;
    std::string failure;
    double resolution = 0.0;
};

/// Runs the converged reference and the second one, and says on out what their difference, the first's
/// resolution, is (or why it is unknown). Throws BenchOptionError when either is not a valid variant.
References collect_references(const Scene& scene, const VariantKey& ref_key, const VariantKey& second_key,
                              std::ostream& out, const StopRequest& stop);
/// The grid's time in s, a lower bound (bench_runs.cpp says how it is found).
double estimate_seconds(const Scene& scene, const BenchOptions& o, const std::vector<VariantKey>& keys,
                        const StopRequest& stop);
/// Runs every grid point, each row written to the CSV o.output as it is measured and a line of progress per point
/// (`points` in all); stops between runs when asked, the CSV valid with the finished rows. Returns the rows.
std::vector<BenchRow> run_grid(const Scene& scene, const BenchOptions& o, const std::vector<VariantKey>& keys,
                               const References& refs, std::size_t points, std::ostream& progress,
                               const StopRequest& stop);

/// Writes and runs the gnuplot script of the figures of the bench CSV csv (of scene `scene`, its converged reference
/// good to `resolution` m); returns what went wrong, or empty.
std::string plot(const std::string& prefix, const std::string& csv, const std::string& scene, double resolution,
                 std::ostream& out);

}  // namespace hubbeam::bench_parts
