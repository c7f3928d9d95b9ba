// What hubbeam plot's kinds of figure share, between plot.cpp (the command) and the files that draw them: the kinds
// and the CSV formats they read (plot_csv.cpp), a figure's parts and the legend's look (plot_lines.cpp, with the
// figures of a line per file), and the Campbell diagram (plot_campbell.cpp). Not installed, not for other tools.
#pragma once

#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <hubbeam/csv_columns.hpp>

namespace hubbeam::plotting {

/// A CSV format that kinds read: what it is called in messages, and its header (the writer's one definition).
struct CsvFormat {
    const char* name;                // "a run CSV"
    const char* (*header)();         // the first line the writer puts
};

/// A column a kind can draw (--column): its axis label, the symbol and unit of the difference panel, and the
/// figure's default title (followed by what the files' names say the scene is).
struct Quantity {
    const char* column;
    const char* axis;    // "tip deflection u_y(L) (m)"
    const char* symbol;  // "u_y(L)"
    const char* unit;    // "m"
    const char* title;
};

/// A kind of figure: the format it reads, the columns it reads (by name) beside the one it draws, those of them that
/// must be numbers, those whose text goes into the script (checked row by row, so that a message can name the
/// line), its default title, and the columns it can draw, the default first (none: its columns are fixed).
struct Kind {
    const char* name;
    const CsvFormat* format;
    std::vector<std::string> columns;
    std::vector<std::string> numeric;
    std::vector<std::string> texts;
    const char* title;
    std::vector<Quantity> quantities;
};

/// The kinds of figure drawn from a table of them (all but animate): tip, axial, campbell, moment.
const std::vector<Kind>& kinds();

/// kind reading column q as well (a copy: the table stays as it is).
Kind reading(const Kind& kind, const Quantity& q);

/// Whether s is a number as a hubbeam CSV writes one (std::from_chars, the whole of s); v is its value.
bool is_number(const std::string& s, double& v);

/// One row of a CSV as read_csv passes it on: its fields, by the header's column names.
class Record {
public:
    Record(const CsvColumns& columns, const std::vector<std::string>& fields) : columns_(columns), fields_(fields) {}
    /// The field of column name (one of the kind's columns, which read_csv has checked are in the header).
    const std::string& operator[](std::string_view name) const { return fields_[columns_.at(name)]; }
    /// Whether the header has column name (beyond the kind's columns, which it has).
    bool has(std::string_view name) const { return columns_.has(name); }
    /// The same as a number (one of the kind's numeric columns, checked to hold one).
    double number(std::string_view name) const
    {
        double v = 0.0;
        is_number((*this)[name], v);
        return v;
    }

private:
    const CsvColumns& columns_;
    const std::vector<std::string>& fields_;
};

/// Reads path as kind's format: the header must hold every column the kind reads (in any order, among others),
/// every row must have the header's number of fields and numbers in the kind's numeric columns; each row goes to
/// `row`. Throws PlotInputError naming the file (and the column).
void read_csv(const std::string& path, const Kind& kind, const std::function<void(const Record&)>& row);

/// A figure of plot_script: what gnuplot computes before drawing, the axes, and the plot command's elements; and,
/// when its curves coincide to the eye, a panel below it of their differences against the first file's curve.
struct Figure {
    std::string data;  // datablocks of selected rows
    std::string axes;  // set xlabel, set ylabel
    std::vector<std::string> elements;
    std::string title_suffix;  // " at t = 2 s"
    std::string lower_axes;    // the difference panel's set xlabel, set ylabel; empty: no such panel
    std::vector<std::string> lower_elements;
    std::size_t longest_label = 0;  // characters of the longest legend entry
};

/// The most characters of a legend entry or a line's end label (title_of).
inline constexpr std::size_t legend_cap = 60;

/// Where the panels of a two-panel figure end on the right (screen fraction, as gnuplot reads it): room in the
/// margin for the longest legend entry or label.
std::string right_edge(const Figure& f);

/// text cut to at most cap characters (UTF-8 code points) by "..." in its middle, so that its start and its end
/// (a file's name, then the mode's label) both stay.
std::string shortened(const std::string& text, std::size_t cap);

/// A legend entry: its text shortened to legend_cap characters, as it is otherwise (noenhanced: no _ or ^ read as a
/// subscript or superscript). name is the option or file the text comes from, for gnuplot_string's message.
std::string title_of(const std::string& text, const std::string& name = "--labels");

/// The characters of a legend entry as title_of writes it.
std::size_t legend_size(const std::string& text);

/// Figures 3-4, 7-8 and 9-12 of the paper: tip_uy against t, a line per file; or a blade's tip_uz or tip_phi (q).
Figure tip_figure(const std::vector<std::string>& files, const std::vector<std::string>& labels, const Kind& kind,
                  const Quantity& q);

/// Figures 5-6: per file, the tip's displacement u_x with the foreshortening u_x2 = -1/2 int u_y'^2 (thick) and
/// its axial stretch u_x1 alone (thin, with points), both in the file's colour and dash pattern.
Figure axial_figure(const std::vector<std::string>& files, const std::vector<std::string>& labels, const Kind& kind);

/// The bending moment EI u_y'' (or a blade's flapwise moment or torque, q) against x at one time per file (the
/// last, or the closest to time).
Figure moment_figure(const std::vector<std::string>& files, const std::vector<std::string>& labels,
                     const std::string& time, const Kind& kind, const Quantity& q);

/// The kinds of mode a modes CSV names (NaturalMode::kind), which --kinds chooses from.
const std::vector<std::string>& mode_kinds();

/// The per-rev lines a Campbell diagram draws when --harmonics is not given: 1P to this (or to NP for N blades
/// beyond it).
inline constexpr int default_per_rev = 6;

/// Which lines a Campbell diagram draws and how (plot's --kinds, --modes, --max-frequency, --spin-unit, --blades,
/// --operating-range).
struct CampbellChoice {
    std::vector<std::string> kinds = {"bending", "edge", "flap"};  // a planar beam's, or a blade's out of the plane
    bool kinds_given = false;     // --kinds chose them: a line of another kind is not drawn even where it grows
    int modes = 0;                // the lowest this many lines of each variant; 0: all
    double max_hz = HUGE_VAL;     // the frequency axis ends here, and lines wholly above it are left out; HUGE_VAL:
                                  // campbell_cutoff's
    bool rpm = false;             // the spin axis in rpm, else rad/s
    int blades = 0;               // N > 1: the per-rev lines kN (the rotor's N-per-rev) drawn heavier
    bool has_range = false;       // the operating range [range_lo, range_hi] shaded, in the spin axis's unit
    double range_lo = 0.0, range_hi = 0.0;
};

/// The frequency (Hz) above which a Campbell diagram leaves its lines out when none is given: 1.1 n Omega_max / 2 pi,
/// a little above the highest per-rev line nP drawn at the highest rate, raised to 1.1 times the highest frequency
/// of the lowest line (lowest_top) so that at least one mode is drawn; HUGE_VAL (every line) without a per-rev line
/// (n = 0) or at rest alone (Omega_max = 0).
double campbell_cutoff(int highest_per_rev, double omega_max, double lowest_top);

/// A Campbell diagram: the chosen modes' frequencies (Hz) against the spin rate (choice.rpm: in rpm) above and their
/// damping ratios (%) below, a line per file, variant and tracked mode, named at its end; the per-rev lines of the
/// harmonics, the critical speeds, the unstable points and the operating range marked; the key names the variants by
/// their files' labels when label_lines.
Figure campbell_figure(const std::vector<std::string>& files, const std::vector<std::string>& labels, bool label_lines,
                       const std::vector<int>& harmonics, const CampbellChoice& choice, const Kind& kind);

}  // namespace hubbeam::plotting
