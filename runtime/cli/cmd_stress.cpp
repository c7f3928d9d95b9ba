// hubbeam stress: the stability stress suite (high spin, many DOFs, long runs, extreme beams).
#include <hubbeam/output_file.hpp>
#include <iostream>
#include <memory>
#include <vector>

#include "command.hpp"
#include "stress.hpp"

namespace hubbeam::cli {

namespace {

/// hubbeam stress: returns 0 when every case did what it must, 1 otherwise.
int stress(const StressOptions& options)
{
    try {
        check_outputs({}, {{options.output, "-o"}});  // checked now, not after the suite has run
    } catch (const OutputRefused& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }
    catch_stop_signals();
    const StopRequest stop = signal_stop();
    const std::vector<StressRow> rows = run_stress(options, std::cout, stop);
    int failed = 0;
    for (const StressRow& r : rows) failed += r.pass ? 0 : 1;
    std::cout << rows.size() << " cases, " << failed << " failed\n";
    if (stop_signal() != 0) return exit_signal_base + stop_signal();
    return failed == 0 ? exit_ok : exit_stopped;
}

}  // namespace

Command add_stress_command(CLI::App& app)
{
    auto options = std::make_shared<StressOptions>();
    Subcommand stress_cmd(app, "stress", "Stability stress suite: high spin, many DOFs, long runs, extreme beams");
    stress_cmd.add_flag("--long", options->long_runs, "1000 s runs and every method's largest DOF count");
    stress_cmd.add_flag("--quick", options->quick, "Spin rates up to 20 rad/s only (what the tests run)");
    stress_cmd.add_option("-o,--output", options->output, "Also write the table as CSV").type_name("FILE");
    stress_cmd.footer("Exit code 0 when every case did what it must, 1 otherwise.");
    return {stress_cmd.app(), [options] { return stress(*options); }};
}

}  // namespace hubbeam::cli
