// Figures with gnuplot: the look every figure of hubbeam shares (PNG and SVG at 1000 x 640, a boxed legend, a
// grid) and running gnuplot on a script, for `hubbeam bench --plot` and `hubbeam plot`.
#pragma once

#include <string>
#include <string_view>

namespace hubbeam {

/// text as a gnuplot single-quoted string, 'it''s': gnuplot reads it back as it is (no escapes, quotes doubled).
std::string gnuplot_string(std::string_view text);

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

}  // namespace hubbeam
