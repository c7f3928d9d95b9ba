// hubbeam plot's figures of a line per file (tip, axial, moment), the legend's look every kind shares, and the
// panel of differences drawn below curves that coincide to the eye.
#include "plot_figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <hubbeam/option_lists.hpp>
#include <hubbeam/printable.hpp>
#include <hubbeam/shortest.hpp>
#include <iterator>
#include <utility>

#include "gnuplot.hpp"

namespace hubbeam::plotting {


std::string shortened(const std::string& text, std::size_t cap)
{
    std::vector<std::size_t> starts;  // where each character begins
    for (std::size_t i = 0; i < text.size(); ++i)
        if ((static_cast<unsigned char>(text[i]) & 0xc0) != 0x80) starts.push_back(i);
    if (starts.size() <= cap) return text;
    const std::size_t head = (cap - 3) / 2, tail = cap - 3 - head;
    return text.substr(0, starts[head]) + "..." + text.substr(starts[starts.size() - tail]);
}

/// A legend entry: its text shortened to legend_cap characters, as it is otherwise (noenhanced: no _ or ^ read as a
/// subscript or superscript). name is the option or file the text comes from, for gnuplot_string's message.
std::string title_of(const std::string& text, const std::string& name)
{
    return "title " + gnuplot_string(shortened(text, legend_cap), name) + " noenhanced";
}

/// The characters of a legend entry as title_of writes it.
std::size_t legend_size(const std::string& text)
{
    return std::min(text.size(), legend_cap);
}

namespace {

/// The line style of the i-th file's curve in figures of a line per file: its own colour, its own dash pattern,
/// and a width that shrinks from the first file's on, so that curves drawn on top of each other still show the
/// ones below them (in the gaps of their dashes and at their edges).
std::string line_style(std::size_t i)
{
    static const char* const dashes[] = {"1", "2", "3", "4", "5", "(20,6,3,6,3,6)", "(4,8)", "(30,10)"};
    const double width = std::max(1.2, 3.0 - 0.5 * static_cast<double>(i));
    char w[16];
    std::snprintf(w, sizeof w, "%.1f", width);
    return std::string(" lw ") + w + " dt " + dashes[i % std::size(dashes)] + " lc " + std::to_string(i + 1) + " ";
}

/// A curve read from a file: (t, value) in the file's order.
using Series = std::vector<std::pair<double, double>>;

/// Reads column `value` against t from every file (each checked as kind's format).
std::vector<Series> read_series(const std::vector<std::string>& files, const Kind& kind, const char* value)
{
    std::vector<Series> all;
    for (const std::string& file : files) {
        Series s;
        read_csv(file, kind, [&](const Record& r) { s.emplace_back(r.number("t"), r.number(value)); });
        all.push_back(std::move(s));
    }
    return all;
}

/// b minus a at b's times inside a's span (a, its times ascending, interpolated linearly between its rows).
Series difference(const Series& a, const Series& b)
{
    Series d;
    for (const auto& [t, y] : b) {
        if (a.empty() || !(t >= a.front().first && t <= a.back().first)) continue;
        const auto after = std::upper_bound(a.begin(), a.end(), t, [](double x, const auto& p) { return x < p.first; });
        const auto& [t0, y0] = *(after - 1);
        double ya = y0;
        if (after != a.end() && after->first > t0) ya += (after->second - y0) * (t - t0) / (after->first - t0);
        d.emplace_back(t, y - ya);
    }
    return d;
}

/// Curves closer than this fraction of the figure's value range (a few pixels of a 640-pixel figure) are drawn on
/// top of each other: the differences then get a panel of their own.
constexpr double coincide_fraction = 0.02;

/// Adds the panel of the differences of series[1..] against series[0], if any of them stays within
/// coincide_fraction of the figure's range (otherwise the curves are told apart where they are drawn).
void add_difference_panel(Figure& f, const std::vector<Series>& series, const std::vector<std::string>& labels,
                          const std::string& quantity, const std::string& unit)
{
    if (series.size() < 2) return;
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (const Series& s : series)
        for (const auto& [t, y] : s) lo = std::min(lo, y), hi = std::max(hi, y);
    std::vector<Series> differences;
    bool coincide = false;
    for (std::size_t i = 1; i < series.size(); ++i) {
        differences.push_back(difference(series[0], series[i]));
        double largest = 0.0;
        for (const auto& [t, d] : differences.back()) largest = std::max(largest, std::abs(d));
        coincide = coincide || largest <= coincide_fraction * (hi - lo);
    }
    if (!coincide) return;
    f.lower_axes = "set xlabel 'time t (s)'\nset ylabel " +
                   gnuplot_string(quantity + " - " + labels[0] + " (" + unit + ")", "--labels") + " noenhanced\n";
    f.data += "# the differences against " + printable(labels[0], 80) + "'s curve, for the panel below\n";
    for (std::size_t i = 1; i < series.size(); ++i) {
        const std::string block = "$difference" + std::to_string(i + 1);
        f.data += block + " << EOD\n";
        for (const auto& [t, d] : differences[i - 1]) f.data += shortest(t) + "," + shortest(d) + "\n";
        f.data += "EOD\n";
        f.lower_elements.push_back(block + " using 1:2 with lines" + line_style(i) +
                                   title_of(labels[i] + " - " + labels[0]));
        f.longest_label = std::max(f.longest_label, legend_size(labels[i] + " - " + labels[0]));
    }
}

}  // namespace

Figure tip_figure(const std::vector<std::string>& files, const std::vector<std::string>& labels, const Kind& kind,
                  const Quantity& q)
{
    Figure f;
    f.axes = "set xlabel 'time t (s)'\nset ylabel " + gnuplot_string(q.axis) + "\n";
    for (std::size_t i = 0; i < files.size(); ++i)
    {
        f.elements.push_back(gnuplot_string(files[i], "FILE") + " using 't':'" + q.column + "' with lines" +
                             line_style(i) + title_of(labels[i]));
        f.longest_label = std::max(f.longest_label, legend_size(labels[i]));
    }
    add_difference_panel(f, read_series(files, kind, q.column), labels, q.symbol, q.unit);
    return f;
}

Figure axial_figure(const std::vector<std::string>& files, const std::vector<std::string>& labels, const Kind& kind)
{
    Figure f;
    f.axes = "set xlabel 'time t (s)'\nset ylabel 'longitudinal tip deformation (m)'\n";
    for (std::size_t i = 0; i < files.size(); ++i) {
        const std::string colour = " dt " + std::to_string(i % 5 + 1) + " lc " + std::to_string(i + 1) + " ";
        f.elements.push_back(gnuplot_string(files[i], "FILE") + " using 't':'tip_ux' with lines" + line_style(i) +
                             title_of(labels[i] + ": u_x (foreshortened)"));
        f.elements.push_back(gnuplot_string(files[i], "FILE") +
                             " using 't':'tip_ux1' with linespoints lw 1 pi 250 pt " +
                             std::to_string(2 * i + 4) + " ps 1" + colour + title_of(labels[i] + ": u_x1 (stretch)"));
        f.longest_label = std::max(f.longest_label, legend_size(labels[i] + ": u_x (foreshortened)") + 1);
    }
    add_difference_panel(f, read_series(files, kind, "tip_ux"), labels, "u_x(L)", "m");
    return f;
}

/// The bending moment EI u_y'' (or a blade's flapwise moment or torque, q) against x at one time per file, lines
/// with small points: FEM's moment jumps at the element nodes (u_y'' of cubic elements is not continuous there), the
/// other methods' is continuous. The rows of that time go to a datablock first, so that their order in the file does
/// not matter.
Figure moment_figure(const std::vector<std::string>& files, const std::vector<std::string>& labels,
                     const std::string& time, const Kind& kind, const Quantity& q)
{
    double wanted = 0.0;
    if (!time.empty() && (!is_number(time, wanted) || !std::isfinite(wanted)))
        bad_option<PlotInputError>("--time", "a time in seconds", printable(time, 40));
    std::vector<std::string> chosen;  // per file, its t as the file writes it
    std::size_t blades = 0;           // files of a blade (fields out of the plane: flap_moment among them)
    for (const std::string& file : files) {
        std::string best;
        double best_t = 0.0;
        bool blade = false;
        read_csv(file, kind, [&](const Record& r) {
            blade = r.has("flap_moment");
            const double t = r.number("t");
            // without --time the last t, with it the closest (the earlier of two as close)
            if (best.empty() || (time.empty() ? t >= best_t : std::abs(t - wanted) < std::abs(best_t - wanted))) {
                best = r["t"];
                best_t = t;
            }
        });
        chosen.push_back(best);
        blades += blade ? 1 : 0;
    }
    // A blade's bending_moment is the edgewise moment about its turned chord, not EI u_y'' (docs/cli.md, the fields
    // CSV): the axis says what is drawn.
    std::string axis = q.axis;
    if (std::string_view(q.column) == "bending_moment" && blades > 0)
        axis = blades == files.size() ? "edgewise bending moment EI_{edge} kappa_c (N m)"
                                      : "bending moment: EI d^2u_y/dx^2 in the plane, a blade's edgewise (N m)";
    const bool one_time =
        std::all_of(chosen.begin(), chosen.end(), [&](const std::string& t) { return t == chosen[0]; });
    Figure f;
    if (one_time) f.title_suffix = " at t = " + chosen[0] + " s";
    f.axes = "set xlabel 'position along the beam x (m)'\nset ylabel " + gnuplot_string(axis) + "\n";
    f.data = "# one datablock per file: its rows at the time drawn\n";
    for (std::size_t i = 0; i < files.size(); ++i) {
        const std::string block = "$moment" + std::to_string(i + 1);
        f.data += "set table " + block + " separator comma\nplot " + gnuplot_string(files[i], "FILE") +
                  " using 'x':'" + q.column + "' with table if (strcol('t') eq " + gnuplot_string(chosen[i]) + ")\n";
        f.elements.push_back(block + " using 1:2 with linespoints" + line_style(i) + "pt 7 ps 0.5 " +
                             title_of(one_time ? labels[i] : labels[i] + ", t = " + chosen[i] + " s"));
    }
    f.data += "unset table\n";
    return f;
}

}  // namespace hubbeam::plotting
