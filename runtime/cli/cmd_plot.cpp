// hubbeam plot: figures from run, modes and field CSVs with gnuplot.
#include <hubbeam/output_file.hpp>
#include <iostream>
#include <memory>

#include "command.hpp"
#include "plot.hpp"

namespace hubbeam::cli {

namespace {

/// Declares the `plot` arguments; all are taken as text and checked by plot_script, so that a bad one is one line
/// naming it.
void add_plot_options(Subcommand& sub, PlotArgs& a)
{
    sub.add_option("KIND", a.kind,
                   "tip, axial (run CSVs), campbell (modes CSVs), moment (field CSVs) or animate (a field CSV, and "
                   "the run's CSV for the hub angle: PREFIX.gif)")
        .required();
    sub.add_option("FILE", a.files, "CSV files in the kind's format (docs/cli.md)").required();
    sub.add_option("-o,--output", a.prefix, "Writes PREFIX.png, PREFIX.svg and the gnuplot script PREFIX.gp")
        .type_name("PREFIX")
        .required();
    sub.add_option("--labels", a.labels, "Legend labels, comma-separated, one per file (default: the files' stems)")
        .type_name("LIST");
    sub.add_option("--title", a.title, "Title (default: the kind's, then the scene's name)").type_name("TEXT");
    sub.add_option("--time", a.time, "moment: the rows at the t closest to T (default: each file's last t)")
        .type_name("T");
    sub.add_option("--harmonics", a.harmonics,
                   "campbell: the per-rev lines f = n Omega / 2 pi drawn, with their crossings (default 1 to 6, or to "
                   "N with --blades N)")
        .type_name("LIST");
    sub.add_option("--kinds", a.kinds,
                   "campbell: the kinds of mode drawn, of bending, edge, flap, twist, axial, hub, overdamped (default "
                   "bending, edge, flap)")
        .type_name("LIST");
    sub.add_option("--modes", a.modes, "campbell: only the N lowest modes of each variant (default: all)")
        .type_name("N");
    sub.add_option("--max-frequency,--max-hz", a.max_hz,
                   "campbell: the frequency axis from 0 to HZ, without the modes wholly above it (default: 1.1 times "
                   "the highest per-rev line at the highest rate)")
        .type_name("HZ");
    sub.add_option("--spin-unit", a.spin_unit, "campbell: the spin axis in rpm or rad/s (default rad/s)")
        .type_name("UNIT");
    sub.add_option("--blades", a.blades, "campbell: the rotor's N blades: the per-rev lines NP, 2NP, ... drawn heavier")
        .type_name("N");
    sub.add_option("--operating-range", a.operating_range,
                   "campbell: the operating range LO:HI shaded, in the spin unit")
        .type_name("LO:HI");
    sub.add_option("--column", a.column,
                   "tip: tip_uy (default), a blade's tip_uz or tip_phi; moment: bending_moment (default), a blade's "
                   "flap_moment or torque")
        .type_name("NAME");
}

/// hubbeam plot: returns the exit code.
int plot(const PlotArgs& args)
{
    const bool animate = args.kind == "animate";
    try {
        if (const std::string problem = animate ? draw_animation(args) : draw_plot(args); !problem.empty()) {
            std::cerr << "hubbeam: " << problem << "\n";
            return exit_stopped;
        }
    } catch (const PlotInputError& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    } catch (const OutputRefused& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }
    std::cout << (animate ? "animation: " + args.prefix + ".gif\n" : "figure: " + args.prefix + ".{png,svg}\n");
    return exit_ok;
}

}  // namespace

Command add_plot_command(CLI::App& app)
{
    auto args = std::make_shared<PlotArgs>();
    Subcommand plot_cmd(
        app, "plot",
        "Figures from CSV files with gnuplot: tip deflection, axial tip, Campbell diagram, bending moment, the "
        "deformed beam animated");
    plot_cmd.footer(
        "docs/cli.md. gnuplot draws into temporary files that replace the figures only when complete. "
        "Exit codes: 0 figure written, 1 gnuplot or the disk failed (old figures kept), 2 bad input (one "
        "line on stderr, nothing written).");
    add_plot_options(plot_cmd, *args);

    return {plot_cmd.app(), [args] { return plot(*args); }};
}

}  // namespace hubbeam::cli
