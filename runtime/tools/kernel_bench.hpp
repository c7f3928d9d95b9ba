// Kernel benchmark (hubbeam kernels): nanoseconds per right-hand side and per Jacobian of FirstOrderSystem for
// a grid of variants, generated kernels against the hand-assembled path, timed in process.
#pragma once

#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

#include <hubbeam/option_lists.hpp>

#include "variant.hpp"

namespace hubbeam {

/// The `kernels` options as typed on the command line (CLI11 fills them; parse_kernel_options checks them), so
/// that every bad value is reported the same way: the option, what it must hold, and what it got.
struct KernelArgs {
    std::string ny = "4,8,16,32";
    std::string methods = "amm,fem,bim,bsim";
    std::string drives = "prescribed,torque";
    std::string orders = "first";
    std::string nx = "0,ny";
    bool nx_equal_ny = false;  // --nx-equal-ny: nx = ny only
    bool nx0 = false;          // --nx0: nx = 0 only
    std::string samples = "7";
    std::string output;  // CSV path; empty: no CSV
};

/// Bad `kernels` option value: what() is "--ny: expected ..., got 0", one line for the user.
struct KernelOptionError : OptionError {
    using OptionError::OptionError;
};

/// An entry of the Nx list that stands for "the same as this row's Ny".
inline constexpr int nx_equal_ny = -1;

/// The checked benchmark grid and its settings.
struct KernelBenchOptions {
    std::vector<Method> methods;
    std::vector<Drive> drives;
    std::vector<Order> orders;
    std::vector<int> ny;
    std::vector<int> nx;  // counts, or nx_equal_ny
    int samples = 7;
    std::string output;
};

/// Checks and converts the typed options; throws KernelOptionError naming the first bad option.
KernelBenchOptions parse_kernel_options(const KernelArgs& args);

/// One timing: median and spread of the per-call time over the samples, in ns.
struct CallTiming {
    double median = 0.0, min = 0.0, max = 0.0;
    long repetitions = 0;  // calls per sample
    int samples = 0;
    bool capped = false;  // a single call was so slow that fewer samples of one call each were taken
};

/// One measured row: a variant served by one model source.
struct KernelBenchRow {
    VariantKey key;
    std::string source;  // "generated" or "assembled"
    CallTiming rhs, jacobian;
    bool exact_jacobian = false;  // false: the finite-difference fallback
    std::string failure;          // non-empty: the model fails at the benchmark state, nothing was timed
};

/// Runs the grid, printing an aligned table to out as rows are measured (skipped variants and capped timings
/// and models that fail at the benchmark state noted below it) and writing the CSV (timed rows) if options.output
/// is set. Throws KernelOptionError if the CSV cannot be created (before anything is timed).
std::vector<KernelBenchRow> run_kernel_bench(const KernelBenchOptions& options, std::ostream& out);

}  // namespace hubbeam
