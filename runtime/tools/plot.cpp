// hubbeam plot: its arguments checked, each kind's figure (plot_figures.hpp) made into a gnuplot script with its
// title and panels, and the script drawn to PREFIX.png and PREFIX.svg (gnuplot.hpp).
#include "plot.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <hubbeam/option_lists.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/printable.hpp>
#include <string>
#include <string_view>

#include "plot_figures.hpp"

namespace hubbeam {

namespace plotting {

std::string right_edge(const Figure& f)
{
    const double chars = static_cast<double>(f.longest_label);
    const double edge = std::clamp(0.93 - 0.0085 * chars - 0.06, 0.55, 0.85);
    char buf[16];
    std::snprintf(buf, sizeof buf, "%.3f", edge);
    return buf;
}

}  // namespace plotting

using plotting::axial_figure;
using plotting::campbell_figure;
using plotting::CampbellChoice;
using plotting::default_per_rev;
using plotting::Figure;
using plotting::Kind;
using plotting::kinds;
using plotting::mode_kinds;
using plotting::moment_figure;
using plotting::Quantity;
using plotting::reading;
using plotting::right_edge;
using plotting::shortened;
using plotting::tip_figure;

namespace {

/// The most characters of the scene's name in a default title.
constexpr std::size_t title_cap = 80;

/// The scene the files are runs of, as their names say: the part of their stems that they share
/// ("spinup_omega4" of spinup_omega4-amm.csv and spinup_omega4-fem.csv, or of spinup_omega4-modes.csv), else the
/// stems, comma-separated.
std::string scene_of(const std::vector<std::string>& files)
{
    std::vector<std::string> stems;
    for (const std::string& f : files) {
        std::string stem = std::filesystem::path(f).stem().string();
        // the suffixes hubbeam gives the modes and field CSVs of a scene (SCENE-modes.csv, RUN-fields.csv)
        for (const std::string_view suffix : {"-modes", "-fields"})
            if (stem.size() > suffix.size() && stem.compare(stem.size() - suffix.size(), suffix.size(), suffix) == 0)
                stem.resize(stem.size() - suffix.size());
        stems.push_back(stem);
    }
    std::string common = stems.front();
    for (const std::string& s : stems) {
        std::size_t n = 0;
        while (n < common.size() && n < s.size() && common[n] == s[n]) ++n;
        common.resize(n);
    }
    while (!common.empty() && std::string_view("-_ .,").find(common.back()) != std::string_view::npos)
        common.pop_back();
    if (common.size() >= 3) return common;
    std::vector<std::string> unique;
    for (const std::string& s : stems)
        if (std::find(unique.begin(), unique.end(), s) == unique.end()) unique.push_back(s);
    return joined(unique);
}

/// Script lines as the body of in_png_and_svg's loop.
std::string indented(const std::string& lines)
{
    std::string out;
    std::size_t start = 0;
    while (start < lines.size()) {
        const std::size_t end = lines.find('\n', start);
        out += "  " + lines.substr(start, end == std::string::npos ? end : end - start + 1);
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return out;
}

}  // namespace

const std::vector<std::string>& plot_kinds()
{
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const Kind& k : kinds()) n.push_back(k.name);
        n.emplace_back("animate");  // draw_animation's, apart from the figures of the table
        return n;
    }();
    return names;
}

std::vector<std::string> plot_columns(const std::string& kind)
{
    std::vector<std::string> columns;
    for (const Kind& k : kinds())
        if (kind == k.name)
            for (const Quantity& q : k.quantities) columns.emplace_back(q.column);
    return columns;
}

void check_plot_args(const PlotArgs& args)
{
    if (std::find(plot_kinds().begin(), plot_kinds().end(), args.kind) == plot_kinds().end())
        bad_option<PlotInputError>("KIND", "one of " + joined(plot_kinds()), printable(args.kind, 40));
    if (args.files.empty()) bad_option<PlotInputError>("FILE", "at least one CSV file", "none");
    // Every text that goes into the script, checked here with its option's name; gnuplot_string checks it again
    // where it is quoted, so that none can be missed.
    check_prefix("-o", args.prefix);
    for (const std::string& f : args.files) check_handed_text<PlotInputError>("FILE", f, "a file name");
    check_handed_text<PlotInputError>("--title", args.title, "a title");
    check_handed_text<PlotInputError>("--labels", args.labels, "labels");
    const auto only = [&](const char* option, const std::string& value, const std::vector<std::string>& takers,
                          const std::string& what) {
        if (!value.empty() && std::find(takers.begin(), takers.end(), args.kind) == takers.end())
            bad_option<PlotInputError>(option, "no " + std::string(option + 2) + " for kind " + args.kind + " (only " +
                                                   what + ")",
                                       printable(value, 40));
    };
    only("--time", args.time, {"moment"}, "kind moment draws one time");
    for (const auto& [option, value] : {std::pair<const char*, const std::string&>{"--harmonics", args.harmonics},
                                        {"--kinds", args.kinds},
                                        {"--modes", args.modes},
                                        {"--max-frequency", args.max_hz},
                                        {"--spin-unit", args.spin_unit},
                                        {"--blades", args.blades},
                                        {"--operating-range", args.operating_range}})
        only(option, value, {"campbell"}, "kind campbell draws them");
    only("--column", args.column, {"tip", "moment"}, "kinds tip and moment draw a column of choice");
    only("--labels", args.labels, {"tip", "axial", "campbell", "moment"}, "kinds of a line per file take them");
}

namespace {

/// Checks args (check_plot_args) for a kind of the table; returns the kind. Throws PlotInputError.
const Kind& checked_kind(const PlotArgs& args)
{
    check_plot_args(args);
    const auto kind = std::find_if(kinds().begin(), kinds().end(), [&](const Kind& k) { return args.kind == k.name; });
    if (kind == kinds().end())  // animate, which draw_animation draws
        bad_option<PlotInputError>("KIND", "one of " + joined(plot_kinds()) + " (animate draws PREFIX.gif alone)",
                                   printable(args.kind, 40));
    return *kind;
}

/// The column kind draws: --column, checked, or the kind's default. Throws PlotInputError.
const Quantity& chosen_quantity(const Kind& kind, const PlotArgs& args)
{
    if (args.column.empty()) return kind.quantities.front();
    for (const Quantity& q : kind.quantities)
        if (args.column == q.column) return q;
    bad_option<PlotInputError>("--column", "one of " + joined(plot_columns(kind.name)) + " for kind " + kind.name,
                               printable(args.column, 40));
}

/// The lines a Campbell diagram draws, from --kinds, --modes and --max-hz. Throws PlotInputError.
CampbellChoice campbell_choice(const PlotArgs& args)
{
    CampbellChoice c;
    if (!args.kinds.empty()) {
        c.kinds.clear();
        c.kinds_given = true;
        for (const std::string& k : split_list(args.kinds)) {
            if (std::find(mode_kinds().begin(), mode_kinds().end(), k) == mode_kinds().end() ||
                std::find(c.kinds.begin(), c.kinds.end(), k) != c.kinds.end())
                bad_option<PlotInputError>("--kinds", "a comma-separated list of " + joined(mode_kinds()) + ", each once",
                                           printable(args.kinds, 40));
            c.kinds.push_back(k);
        }
    }
    if (!args.modes.empty() && !parse_int(args.modes, 1, 1000, c.modes))
        bad_option<PlotInputError>("--modes", "an integer from 1 to 1000", printable(args.modes, 40));
    if (!args.max_hz.empty() && !parse_positive(args.max_hz, c.max_hz))
        bad_option<PlotInputError>("--max-frequency", "a frequency > 0 (Hz)", printable(args.max_hz, 40));
    if (!args.spin_unit.empty() && args.spin_unit != "rpm" && args.spin_unit != "rad/s")
        bad_option<PlotInputError>("--spin-unit", "rpm or rad/s", printable(args.spin_unit, 40));
    c.rpm = args.spin_unit == "rpm";
    if (!args.blades.empty() && !parse_int(args.blades, 1, 1000, c.blades))
        bad_option<PlotInputError>("--blades", "an integer from 1 to 1000", printable(args.blades, 40));
    if (!args.operating_range.empty()) {
        const std::size_t colon = args.operating_range.find(':');
        const std::string unit = c.rpm ? "rpm" : "rad/s";
        if (colon == std::string::npos ||
            !parse_non_negative(std::string_view(args.operating_range).substr(0, colon), c.range_lo) ||
            !parse_non_negative(std::string_view(args.operating_range).substr(colon + 1), c.range_hi) ||
            !(c.range_lo < c.range_hi))
            bad_option<PlotInputError>("--operating-range",
                                       "LO:HI, two spin rates >= 0 (" + unit + ", the --spin-unit) with LO < HI",
                                       printable(args.operating_range, 40));
        c.has_range = true;
    }
    return c;
}

/// The legend's label per file: --labels, checked, or the files' stems. Throws PlotInputError.
std::vector<std::string> file_labels(const PlotArgs& args)
{
    std::vector<std::string> labels;
    if (args.labels.empty()) {
        for (const std::string& f : args.files) labels.push_back(std::filesystem::path(f).stem().string());
        return labels;
    }
    labels = split_list(args.labels);
    if (labels.size() != args.files.size())
        bad_option<PlotInputError>("--labels",
                                   std::to_string(args.files.size()) + " comma-separated labels, one per file",
                                   std::to_string(labels.size()) + " (" + printable(args.labels, 120) + ")");
    for (const std::string& l : labels) {
        if (l.empty()) bad_option<PlotInputError>("--labels", "a non-empty label per file", "");
    }
    return labels;
}

/// The figure of kind, read from args' files.
Figure kind_figure(const Kind& kind, const PlotArgs& args, const std::vector<std::string>& labels)
{
    const std::string name = kind.name;
    if (name == "tip") {
        const Quantity& q = chosen_quantity(kind, args);
        return tip_figure(args.files, labels, reading(kind, q), q);
    }
    if (name == "axial") return axial_figure(args.files, labels, kind);
    if (name == "campbell") {
        const CampbellChoice choice = campbell_choice(args);
        // By default the per-rev lines 1P to 6P, or to NP for a rotor of more blades.
        std::string per_rev = args.harmonics;
        if (per_rev.empty())
            for (int k = 1; k <= std::max(default_per_rev, choice.blades); ++k) {
                if (k > 1) per_rev += ',';
                per_rev += std::to_string(k);
            }
        // the labels name the lines once there is more than one file, or when given
        return campbell_figure(args.files, labels, args.files.size() > 1 || !args.labels.empty(),
                               parse_harmonics<PlotInputError>("--harmonics", per_rev), choice, kind);
    }
    const Quantity& q = chosen_quantity(kind, args);
    return moment_figure(args.files, labels, args.time, reading(kind, q), q);
}

/// A plot command of the elements.
std::string plot_of(const std::vector<std::string>& elements)
{
    std::string plot = "  plot ";
    for (std::size_t i = 0; i < elements.size(); ++i) plot += (i ? ", \\\n       " : "") + elements[i];
    return plot + "\n";
}

/// The figure's commands inside in_png_and_svg's loop, drawn to prefix under title.
std::string figure_body(const Figure& figure, const std::string& prefix, const std::string& title)
{
    std::string body =
        figure_output(prefix) + "  set title " + gnuplot_string(title) + " noenhanced\n" + indented(figure.axes);
    if (figure.lower_elements.empty()) return body + plot_of(figure.elements);
    // Two panels with the same left and right edges (the legends in the margin on the right), so that their time
    // axes line up: the curves above, their differences against the first file's below.
    return body + "  set multiplot\n  set lmargin at screen 0.12\n  set rmargin at screen " + right_edge(figure) +
           "\n  set tmargin at screen 0.93\n  set bmargin at screen 0.42\n  set xlabel ''\n" +
           plot_of(figure.elements) + "  set title ''\n  set tmargin at screen 0.33\n  set bmargin at screen 0.09\n" +
           indented(figure.lower_axes) + plot_of(figure.lower_elements) +
           "  unset multiplot\n  unset lmargin\n  unset rmargin\n  unset tmargin\n  unset bmargin\n";
}

}  // namespace

std::string plot_script(const PlotArgs& args)
{
    const Kind& kind = checked_kind(args);
    const std::vector<std::string> labels = file_labels(args);
    const Figure figure = kind_figure(kind, args, labels);
    const std::string title =
        args.title.empty() ? (kind.quantities.empty() ? kind.title : chosen_quantity(kind, args).title) +
                                 (", " + shortened(scene_of(args.files), title_cap)) + figure.title_suffix
                           : args.title;
    // The comment's names escaped as a message's are (printable): a comment line must stay one line too.
    std::string script = "# gnuplot script written by hubbeam plot " + std::string(kind.name) + " (redraw: gnuplot " +
                         printable(args.prefix, 4096) + ".gp), from";
    for (const std::string& f : args.files) script += " " + printable(f, 4096);
    return script + "\n" + figure_style() + figure.data + in_png_and_svg(figure_body(figure, args.prefix, title));
}

std::string draw_plot(const PlotArgs& args)
{
    const std::string script = plot_script(args);  // checks args first (check_plot_args)
    std::vector<NamedPath> inputs;
    for (const std::string& f : args.files) inputs.push_back({f, "the input " + printable(f, 400)});
    check_outputs(inputs, {{args.prefix + ".gp", "-o"}, {args.prefix + ".png", "-o"}, {args.prefix + ".svg", "-o"}});
    return draw_figures({args.prefix}, args.prefix + ".gp", script, [&](const std::vector<std::string>& temp) {
        PlotArgs drawn = args;
        drawn.prefix = temp.front();
        return plot_script(drawn);
    });
}

}  // namespace hubbeam
