// Figures with gnuplot: the look every figure of hubbeam shares (PNG and SVG at 1000 x 640, a boxed legend, a
// grid), running gnuplot on a script (for `hubbeam bench --plot` too), and `hubbeam plot`: the paper's figures
// from the program's CSV files (tip response, axial tip, Campbell diagram, bending moment along the beam).
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "text/option_lists.hpp"

namespace hubbeam {

/// Bad input to `plot`: an argument, or a file that is not what its kind reads ("FILE: expected ..., got ..."). An
/// OptionError, so that every command that draws (bench --plot, modes --plot) exits 2 for it.
struct PlotInputError : OptionError {
    using OptionError::OptionError;
};

/// text as a gnuplot string expression that reads back as it is: 'text' (no escapes, no substitutions), or with
/// quotes in it ('it'."'".'s'). Every string of every script passes through here, so here it is checked
/// (check_handed_text): text with a control or format character throws PlotInputError("NAME: expected text without
/// ..."), so that no path, title or label can end the script's line and start a command of its own.
std::string gnuplot_string(std::string_view text, const std::string& name = "a string for gnuplot");

/// Checks an output prefix (PREFIX.png, PREFIX.svg, PREFIX.gif, PREFIX.gp) before anything is computed: text a
/// script may hold (check_handed_text) with a file name after its last '/' (DIR/ would write the hidden DIR/.png,
/// DIR/. the file DIR/..png). Throws OutputRefused naming option.
void check_prefix(const std::string& option, const std::string& prefix);

/// The settings every figure starts with: comma-separated data (the CSV files), the legend boxed outside on the
/// right, where it covers no curve, and a grid.
std::string figure_style();

/// The loop that draws `figures` (gnuplot commands, each figure opened by figure_output) twice: as PNG for a
/// screen and as SVG for a document, both 1000 x 640 so that they look alike. Inside it, `ext` is 'png' or 'svg'.
std::string in_png_and_svg(const std::string& figures);

/// The command in in_png_and_svg's figures that sends the next figure to PREFIX.png or PREFIX.svg.
std::string figure_output(const std::string& prefix);

/// Runs gnuplot on the script at script_path; returns what went wrong (gnuplot's own messages), or empty.
std::string run_gnuplot(const std::string& script_path);

/// Draws figures with gnuplot so that each is replaced whole or not at all: for each PREFIX of prefixes, PREFIX.png
/// and PREFIX.svg are OutputFiles (checked, locked) whose temporary files gnuplot writes, from script_for(the
/// temporary prefixes); script (the same figures under their real names) goes to script_path, to redraw them. Only
/// when gnuplot exits 0 and every figure ends as a whole PNG or SVG are the files renamed into place. Returns what
/// went wrong (the old files then as they were), or empty; throws OutputRefused for a refused output.
std::string draw_figures(const std::vector<std::string>& prefixes, const std::string& script_path,
                         const std::string& script,
                         const std::function<std::string(const std::vector<std::string>&)>& script_for);

/// The `plot` arguments as typed (checked by plot_script, so that a bad one is one line naming it).
struct PlotArgs {
    std::string kind;                // one of plot_kinds()
    std::vector<std::string> files;  // CSV files in the kind's format
    std::string prefix;              // PREFIX.png, PREFIX.svg and the script PREFIX.gp
    std::string labels;              // comma-separated, one per file; empty: each file's stem
    std::string title;               // empty: the kind's
    std::string time;                // kind moment: draw the rows at the t closest to it; empty: each file's last t
    std::string harmonics;           // kind campbell: the excitation lines omega = n Omega drawn; empty: 1,2,3
    std::string kinds;               // kind campbell: the kinds of tracked mode drawn; empty: bending
    std::string modes;               // kind campbell: the lowest N lines of each variant; empty: all
    std::string max_hz;              // kind campbell: the top of the frequency axis (Hz); empty: the data's
    std::string column;              // kinds tip and moment: the column drawn; empty: tip_uy, bending_moment
};

/// The kinds of figure: tip, axial (run CSVs), campbell (modes CSVs), moment (field CSVs), animate (a field CSV).
const std::vector<std::string>& plot_kinds();

/// Checks what every kind takes before a file is read: a kind of plot_kinds(), at least one file, the prefix
/// (check_prefix), the files' names, --title and --labels as text a script may hold, and no option that args' kind
/// does not take (--time but for moment, --harmonics, --kinds, --modes, --max-hz but for campbell, --column but for tip
/// and moment, --labels for animate). Throws PlotInputError, or OutputRefused for the prefix.
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
