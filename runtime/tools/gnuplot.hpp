// Figures with gnuplot: the look every figure of hubbeam shares (PNG and SVG at 1000 x 640, a boxed legend, a
// grid), the one way text reaches a script (gnuplot_string), and running gnuplot on a script so that each figure is
// replaced whole or not at all (for `hubbeam plot`, `bench --plot` and `modes --plot` alike).
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <hubbeam/option_lists.hpp>

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

}  // namespace hubbeam
