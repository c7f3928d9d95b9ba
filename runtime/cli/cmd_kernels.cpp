// hubbeam kernels: nanoseconds per right-hand side and Jacobian, generated kernels against the assembled path.
#include <hubbeam/output_file.hpp>
#include <iostream>
#include <memory>

#include "command.hpp"
#include "kernel_bench.hpp"

namespace hubbeam::cli {

namespace {

/// Declares the `kernels` options; all are taken as text and checked by parse_kernel_options, so that every bad
/// value is reported as "--option: expected ..., got ...".
void add_kernel_options(Subcommand& sub, KernelArgs& a)
{
    sub.add_option("--ny", a.ny, "Ny values, comma-separated (default " + a.ny + ")").type_name("LIST");
    sub.add_option("--methods", a.methods, "Methods, comma-separated (default " + a.methods + ")").type_name("LIST");
    sub.add_option("--drives", a.drives, "Drives, comma-separated (default " + a.drives + ")").type_name("LIST");
    sub.add_option("--orders", a.orders, "Model orders, comma-separated (default " + a.orders + ")").type_name("LIST");
    Option nx = sub.add_option("--nx", a.nx, "Nx values, comma-separated; 'ny' is Nx = Ny (default " + a.nx + ")")
                    .type_name("LIST");
    Option equal = sub.add_flag("--nx-equal-ny", a.nx_equal_ny, "Only Nx = Ny (same as --nx ny)");
    Option zero = sub.add_flag("--nx0", a.nx0, "Only Nx = 0 (same as --nx 0)");
    nx.excludes(equal).excludes(zero);
    equal.excludes(zero);
    sub.add_option("--samples", a.samples, "Timed samples per measurement, median reported (default 7)").type_name("N");
    sub.add_option("-o,--output", a.output, "Also write the results as CSV to FILE").type_name("FILE");
}

/// hubbeam kernels: returns the exit code.
int kernels(const KernelArgs& args)
{
    try {
        const KernelBenchOptions options = parse_kernel_options(args);
        check_outputs({}, {{options.output, "-o"}});
        run_kernel_bench(options, std::cout);
    } catch (const OptionError& e) {  // KernelOptionError, OutputRefused
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }
    return exit_ok;
}

}  // namespace

Command add_kernels_command(CLI::App& app)
{
    auto args = std::make_shared<KernelArgs>();
    Subcommand kernels_cmd(
        app, "kernels", "Time the right-hand side and Jacobian per call, generated kernels against the assembled path");
    kernels_cmd.footer("Prints a table (ns per call); exit code 2 for a bad option value.");
    add_kernel_options(kernels_cmd, *args);
    return {kernels_cmd.app(), [args] { return kernels(*args); }};
}

}  // namespace hubbeam::cli
