// hubbeam plot: the paper's figures from the program's CSV files (tip response, axial tip, Campbell diagram, bending
// moment along the beam) and the beam's animation, drawn with gnuplot (gnuplot.hpp: the look and the run they share).
#pragma once

#include <string>
#include <vector>

#include "gnuplot.hpp"

namespace hubbeam {

/// The `plot` arguments as typed (checked by plot_script, so that a bad one is one line naming it).
struct PlotArgs {
    std::string kind;                // one of plot_kinds()
    std::vector<std::string> files;  // CSV files in the kind's format
    std::string prefix;              // PREFIX.png, PREFIX.svg and the script PREFIX.gp
    std::string labels;              // comma-separated, one per file; empty: each file's stem
    std::string title;               // empty: the kind's
    std::string time;                // kind moment: draw the rows at the t closest to it; empty: each file's last t
    std::string harmonics;           // kind campbell: the per-rev lines f = n Omega / 2 pi drawn; empty: 1 to 6 (or
                                     // to N of --blades N)
    std::string kinds;               // kind campbell: the kinds of tracked mode drawn; empty: bending
    std::string modes;               // kind campbell: the lowest N lines of each variant; empty: all
    std::string max_hz;              // kind campbell: the top of the frequency axis (Hz); empty: a little above the
                                     // highest per-rev line (plotting::campbell_cutoff)
    std::string spin_unit;           // kind campbell: the spin axis's unit, rpm or rad/s; empty: rad/s
    std::string blades;              // kind campbell: the rotor's blades N, whose per-rev multiples kN are drawn heavier
    std::string operating_range;     // kind campbell: LO:HI, the operating range shaded (in the spin unit)
    std::string column;              // kinds tip and moment: the column drawn; empty: tip_uy, bending_moment
};

/// The kinds of figure: tip, axial (run CSVs), campbell (modes CSVs), moment (field CSVs), animate (a field CSV).
const std::vector<std::string>& plot_kinds();

/// Checks what every kind takes before a file is read: a kind of plot_kinds(), at least one file, the prefix
/// (check_prefix), the files' names, --title and --labels as text a script may hold, and no option that args' kind
/// does not take (--time but for moment, --harmonics, --kinds, --modes, --max-frequency, --spin-unit, --blades,
/// --operating-range but for campbell, --column but for tip and moment, --labels for animate). Throws PlotInputError, or OutputRefused for the prefix.
void check_plot_args(const PlotArgs& args);

/// The columns kind draws, one at a time (--column), the default first: tip_uy, tip_uz, tip_phi for tip,
/// bending_moment, flap_moment, torque for moment; none for the others.
std::vector<std::string> plot_columns(const std::string& kind);

/// The gnuplot script of args' figure. Checks the arguments and reads every file through first: its header must
/// be exactly its kind's, and every row must hold numbers where the figure reads them. Throws PlotInputError.
std::string plot_script(const PlotArgs& args);

/// hubbeam plot: plot_script written to PREFIX.gp, then gnuplot draws PREFIX.png and PREFIX.svg (draw_figures). Bad
/// input throws PlotInputError, an output that is an input or not a regular file OutputRefused, with nothing
/// written; returns what went wrong with gnuplot or the disk (the old figures kept), or empty.
std::string draw_plot(const PlotArgs& args);

/// hubbeam plot animate: the gnuplot script that draws the beam of a fields CSV (args.files[0]) frame by frame into
/// the GIF gif, turned by the hub angle of a run CSV (args.files[1]) where given; in three dimensions where the
/// fields have u_z (a blade). Reads and checks the files; throws PlotInputError.
std::string animation_script(const PlotArgs& args, const std::string& gif);

/// hubbeam plot animate: animation_script to PREFIX.gp, then gnuplot draws PREFIX.gif, put in place only when whole.
/// Bad input throws PlotInputError, a refused output OutputRefused, nothing written; returns what went wrong with
/// gnuplot or the disk (the old animation kept), or empty.
std::string draw_animation(const PlotArgs& args);

}  // namespace hubbeam
