// hubbeam plot campbell: the Campbell diagram of modes CSVs, a line per tracked mode of each variant, each its own
// colour and marker, with the excitation lines nP and the critical speeds where they cross the modes.
#include "plot_figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <utility>

#include "gnuplot.hpp"
#include "text/option_lists.hpp"
#include "text/printable.hpp"
#include "text/shortest.hpp"

namespace hubbeam::plotting {

/// The kinds of mode a modes CSV names (NaturalMode::kind). A table that marks a real decaying eigenvalue's rows as
/// kind overdamped labels a mode that begins so "overdamped N": --kinds overdamped draws such lines where they
/// oscillate (campbell_lines leaves out every row of frequency 0, whatever its kind).
const std::vector<std::string>& mode_kinds()
{
    static const std::vector<std::string> k = {"bending", "edge", "flap", "twist", "axial", "hub", "overdamped"};
    return k;
}

namespace {

/// A line of a Campbell diagram: one mode of one variant of one file, a tracked mode (by its label) or, in a file
/// without tracking, the modes of one kind and frequency rank; and its points (omega, Hz).
struct CampbellLine {
    std::size_t file;
    std::vector<std::string> variant;  // method, ny, nx, nz, nt, order, drive as the file writes them (nz, nt: empty
                                       // in a file without them, an older hubbeam's)
    std::string column, mode;          // the column that tells the line's rows ("label" or "mode") and its value
    std::string kind;                  // the kind its rows are selected by in a file without tracking; empty: any
    std::string name;                  // its legend entry: the label ("bending 2"), or "bending mode 2"
    std::vector<std::pair<double, double>> points;
};

/// The modes CSV columns that name a variant, and how the legend introduces each.
constexpr const char* variant_columns[] = {"method", "ny", "nx", "nz", "nt", "order", "drive"};
constexpr const char* variant_names[] = {"", " Ny = ", " Nx = ", " Nz = ", " Nt = ", " order ", " drive "};
constexpr std::size_t variant_size = std::size(variant_columns);

/// The Campbell diagram's lines, in the order of the files and of their first rows: each tracked mode whose label
/// names one of choice's kinds (its rows of every kind: through a veering its shape may turn axial), or in a file
/// without the label column (an older hubbeam's) the rows of one of those kinds of each frequency rank; then of
/// each variant the `modes` lowest (by their frequency at their lowest rate), and those with a point at or below
/// max_hz. A row of frequency 0 (an overdamped mode: it does not oscillate) is no point of any line, whether or not
/// the table lists it. Throws PlotInputError for a file without such rows.
std::vector<CampbellLine> campbell_lines(const std::vector<std::string>& files, const Kind& kind,
                                         const CampbellChoice& choice)
{
    std::vector<CampbellLine> lines;
    const auto chosen = [&](const std::string& k) {
        return std::find(choice.kinds.begin(), choice.kinds.end(), k) != choice.kinds.end();
    };
    for (std::size_t file = 0; file < files.size(); ++file) {
        const std::size_t before = lines.size();
        read_csv(files[file], kind, [&](const Record& r) {
            // An overdamped mode has no frequency to draw, and no critical speed: drawn at 0 Hz it would meet every
            // excitation line at rest and rank lowest for --modes (the same test as campbell_table's).
            if (!(r.number("hz") > 0.0)) return;
            const bool tracked = r.has("label");
            const std::string& label = tracked ? r["label"] : r["kind"];
            if (!chosen(tracked ? label.substr(0, label.find(' ')) : label)) return;
            CampbellLine l{file,
                           {r["method"], r["ny"], r["nx"], r.has("nz") ? r["nz"] : "", r.has("nt") ? r["nt"] : "",
                            r["order"], r["drive"]},
                           tracked ? "label" : "mode",
                           tracked ? label : r["mode"],
                           tracked ? "" : label,
                           tracked ? label : label + " mode " + r["mode"],
                           {}};
            auto same = std::find_if(lines.begin() + static_cast<std::ptrdiff_t>(before), lines.end(),
                                     [&](const CampbellLine& o) {
                                         return o.variant == l.variant && o.mode == l.mode && o.kind == l.kind;
                                     });
            if (same == lines.end()) same = lines.insert(lines.end(), l);
            same->points.emplace_back(r.number("omega"), r.number("hz"));
        });
        if (lines.size() == before)
            throw PlotInputError(printable(files[file], 400) + ": expected rows of kind " + joined(choice.kinds, "'") +
                                 " with a frequency above 0 (the modes the Campbell diagram draws, --kinds), got none");
    }
    for (CampbellLine& l : lines) std::stable_sort(l.points.begin(), l.points.end());
    // Of each file's variant, the lines ranked by their frequency at their lowest rate.
    std::vector<bool> keep(lines.size(), true);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        int lower = 0;
        for (std::size_t j = 0; j < lines.size(); ++j)
            if (j != i && lines[j].file == lines[i].file && lines[j].variant == lines[i].variant &&
                (lines[j].points.front().second < lines[i].points.front().second ||
                 (lines[j].points.front().second == lines[i].points.front().second && j < i)))
                ++lower;
        const bool in_range = std::any_of(lines[i].points.begin(), lines[i].points.end(),
                                          [&](const auto& p) { return p.second <= choice.max_hz; });
        keep[i] = (choice.modes == 0 || lower < choice.modes) && in_range;
    }
    std::vector<CampbellLine> kept;
    for (std::size_t i = 0; i < lines.size(); ++i)
        if (keep[i]) kept.push_back(std::move(lines[i]));
    return kept;
}

/// Where line l meets the excitation line f = n omega / 2 pi between two of its points: (omega, Hz) where the
/// straight segment between them crosses it, to the eye (hubbeam modes refines them on the eigenvalues themselves;
/// the two agree as the rates are refined).
std::vector<std::pair<double, double>> campbell_crossings(const CampbellLine& l, int n)
{
    std::vector<std::pair<double, double>> at;
    const auto gap = [n](const std::pair<double, double>& p) { return p.second - n * p.first / (2.0 * M_PI); };
    for (std::size_t i = 0; i + 1 < l.points.size(); ++i) {
        const double ga = gap(l.points[i]), gb = gap(l.points[i + 1]);
        if (ga == 0.0 || ga * gb >= 0.0) {
            if (ga == 0.0) at.push_back(l.points[i]);
            continue;
        }
        const double omega = l.points[i].first + (l.points[i + 1].first - l.points[i].first) * ga / (ga - gb);
        at.emplace_back(omega, n * omega / (2.0 * M_PI));
    }
    return at;
}

/// Which variant columns the legend names: method and Ny always, Nx, Nz, Nt, order and drive when they vary.
std::vector<bool> named_columns(const std::vector<CampbellLine>& lines)
{
    std::vector<bool> named = {true, true, false, false, false, false, false};
    for (const CampbellLine& l : lines)
        for (std::size_t c = 2; c < variant_size; ++c) named[c] = named[c] || l.variant[c] != lines.front().variant[c];
    return named;
}

/// The commands that select line l's rows of its file into the datablock `block`.
std::string campbell_table(const std::string& block, const CampbellLine& l, const std::string& file)
{
    std::string condition;
    for (std::size_t c = 0; c < variant_size; ++c)
        if (!l.variant[c].empty())  // a column the file has
            condition += "strcol('" + std::string(variant_columns[c]) + "') eq " + gnuplot_string(l.variant[c]) + " && ";
    condition += "strcol('" + l.column + "') eq " + gnuplot_string(l.mode);
    if (!l.kind.empty()) condition += " && strcol('kind') eq " + gnuplot_string(l.kind);
    condition += " && column('hz') > 0";  // not an overdamped row (campbell_lines)
    return "set table " + block + " separator comma\nplot " + gnuplot_string(file) +
           " using 'omega':'hz' with table if (" + condition + ")\n";
}

/// The first colours of a Campbell diagram's lines, none of them the black and grey of the excitation lines or the
/// red of the critical speeds.
constexpr const char* line_colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2",
                                        "#17becf", "#bcbd22", "#000080", "#808000", "#008080", "#ff00ff"};

/// The colour of a Campbell diagram's line `line`, its own however many lines there are (a blade's table has
/// dozens of modes): line_colours first, then hues a golden angle apart, kept from the reds (within 40 degrees of
/// hue 0) and from grey, at three saturations and brightnesses in turn; a colour taken already moves on by a degree.
std::vector<std::string> line_colours_for(std::size_t lines)
{
    std::vector<std::string> colours;
    for (std::size_t i = 0; i < lines; ++i) {
        if (i < std::size(line_colours)) {
            colours.emplace_back(line_colours[i]);
            continue;
        }
        const std::size_t k = i - std::size(line_colours);
        const double shade = 0.2 * static_cast<double>(k % 3), saturation = 0.9 - shade, value = 0.85 - shade;
        double hue = 40.0 + std::fmod(static_cast<double>(k) * 137.50776, 280.0);
        for (std::string colour;; hue = 40.0 + std::fmod(hue - 40.0 + 1.0, 280.0)) {
            // HSV to RGB (hue in degrees)
            const double c = value * saturation, h = hue / 60.0, x = c * (1.0 - std::abs(std::fmod(h, 2.0) - 1.0));
            const int sector = static_cast<int>(h) % 6;
            const double r = sector == 0 || sector == 5 ? c : sector == 1 || sector == 4 ? x : 0.0;
            const double g = sector == 1 || sector == 2 ? c : sector == 0 || sector == 3 ? x : 0.0;
            const double b = sector == 3 || sector == 4 ? c : sector == 2 || sector == 5 ? x : 0.0;
            const auto byte = [&](double v) { return static_cast<unsigned>(std::lround(255.0 * (v + value - c))); };
            char hex[8];
            std::snprintf(hex, sizeof hex, "#%02x%02x%02x", byte(r), byte(g), byte(b));
            colour = hex;
            if (std::find(colours.begin(), colours.end(), colour) == colours.end()) {
                colours.push_back(colour);
                break;
            }
        }
    }
    return colours;
}

/// The look of a Campbell line: its own colour (line_colours_for), an open marker of its own per variant (by the
/// variant's index), larger and the line wider the earlier the variant, so that variants whose frequencies coincide
/// show as nested outlines; a dash type per file.
std::string campbell_style(const std::string& colour, std::size_t variant_index, std::size_t file)
{
    static const int open_points[] = {6, 4, 8, 12, 10, 14, 1, 2};
    char size[40];
    std::snprintf(size, sizeof size, "lw %.1f", std::max(1.0, 2.5 - 0.4 * static_cast<double>(variant_index)));
    char points[40];
    std::snprintf(points, sizeof points, " pt %d ps %.2f ", open_points[variant_index % std::size(open_points)],
                  std::max(0.6, 1.6 - 0.25 * static_cast<double>(variant_index)));
    return std::string(size) + " lc rgb '" + colour + "' dt " +
           std::to_string(file % 5 + 1) + points;
}

/// The look of the excitation line nP: 1P black and widest, the others in greys, each its own dash pattern (long
/// dashes, short dashes, dots, dash-dot, ...) so that 1P, 2P and 3P are told apart in the figure as in the legend.
std::string harmonic_style(int n)
{
    static const char* const dashes[] = {"(18,6)", "(12,8)", "(2,5)", "(18,5,2,5)", "(18,5,2,5,2,5)", "(7,5,2,5)"};
    static const char* const greys[] = {"black", "#404040", "#808080"};  // (gnuplot's gray25 draws lighter)
    const std::size_t k = static_cast<std::size_t>(n - 1);
    return std::string("lw ") + (n == 1 ? "2" : "1.5") + " dt " + dashes[k % std::size(dashes)] + " lc rgb '" +
           (k == 0 ? greys[0] : greys[1 + (k + 1) % 2]) + "'";
}

/// Adds the chosen modes' lines to f, each its own colour and legend entry (its label, led by its file's label when
/// label_lines and by its variant when there are several; one variant's name goes to the title instead).
void add_mode_lines(Figure& f, const std::vector<CampbellLine>& lines, const std::vector<std::string>& files,
                    const std::vector<std::string>& labels, bool label_lines)
{
    const std::vector<bool> named = named_columns(lines);
    f.data = "# one datablock per line: the rows of one tracked mode of one variant\n";
    std::vector<std::pair<std::size_t, std::vector<std::string>>> variants;  // (file, variant): a marker each
    for (const CampbellLine& l : lines)
        if (std::find(variants.begin(), variants.end(), std::pair{l.file, l.variant}) == variants.end())
            variants.emplace_back(l.file, l.variant);
    // One variant: its name goes to the title, and the legend holds the modes' labels alone.
    if (variants.size() == 1) {
        std::string name;
        for (std::size_t c = 0; c < variant_size; ++c)
            if (named[c]) name += (c ? "," : "") + std::string(variant_names[c]) + lines.front().variant[c];
        f.title_suffix = " (" + name + ")";
    }
    const std::vector<std::string> colours = line_colours_for(lines.size());
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const CampbellLine& l = lines[i];
        const std::string block = "$mode" + std::to_string(i + 1);
        f.data += campbell_table(block, l, files[l.file]);
        const auto v = std::find(variants.begin(), variants.end(), std::pair{l.file, l.variant});
        std::string legend = label_lines ? labels[l.file] + ": " : "";
        if (variants.size() > 1) {
            for (std::size_t c = 0; c < variant_size; ++c)
                if (named[c]) legend += variant_names[c] + l.variant[c];
            legend += ", ";
        }
        legend += l.name;
        f.longest_label = std::max(f.longest_label, legend_size(legend));
        // smooth unique: the points by increasing rate, whatever the rows' order in the file
        f.elements.push_back(block + " using 1:2 smooth unique with linespoints " +
                             campbell_style(colours[i], static_cast<std::size_t>(v - variants.begin()), l.file) +
                             title_of(legend, "a modes CSV's label"));
    }
    f.data += "unset table\n";
}

/// Adds the excitation lines nP of the harmonics (f = n omega / 2 pi), each named at its end inside the figure, and
/// their crossings with the lines (the critical speeds) at or below choice's frequency limit.
void add_harmonics(Figure& f, const std::vector<CampbellLine>& lines, const std::vector<int>& harmonics,
                   const CampbellChoice& choice)
{
    // Where the excitation lines leave the figure: the highest rate, and the top of the frequency axis (--max-hz,
    // else at least the highest point drawn; gnuplot's autoscale only rounds it up to a tic).
    double omega_top = 0.0, hz_top = 0.0;
    for (const CampbellLine& l : lines)
        for (const auto& [omega, hz] : l.points) omega_top = std::max(omega_top, omega), hz_top = std::max(hz_top, hz);
    for (const int n : harmonics) hz_top = std::max(hz_top, n * omega_top / (2.0 * M_PI));
    if (choice.max_hz < HUGE_VAL) hz_top = choice.max_hz;
    std::string crossings;
    for (const int n : harmonics) {
        const std::string times = n == 1 ? "" : std::to_string(n) + "*";
        f.elements.push_back(times + "x/(2*pi) with lines " + harmonic_style(n) + " title '" + std::to_string(n) +
                             "P: " + (n == 1 ? "spin frequency omega" : times + "omega") + "/2pi'");
        // Its name at its end inside the figure, so that each line is told without the legend.
        if (omega_top > 0.0) {
            const double hz_end = n * omega_top / (2.0 * M_PI);
            const bool leaves_at_top = hz_end > hz_top;
            const double x = leaves_at_top ? hz_top * 2.0 * M_PI / n : omega_top, y = leaves_at_top ? hz_top : hz_end;
            f.axes += "set label '" + std::to_string(n) + "P' at " + shortest(x) + "," + shortest(y) +
                      (leaves_at_top ? " right offset -0.6,-0.9" : " right offset -0.6,0.9") + " front\n";
        }
        for (const CampbellLine& l : lines)
            for (const auto& [omega, hz] : campbell_crossings(l, n))
                if (hz <= choice.max_hz) crossings += shortest(omega) + ',' + shortest(hz) + '\n';
    }
    if (!crossings.empty()) {
        f.data += "$critical << EOD\n" + crossings + "EOD\n";
        f.elements.push_back("$critical using 1:2 with points pt 7 ps 1.2 lc rgb 'red' title 'critical speeds'");
    }
}

}  // namespace

/// A Campbell diagram: the chosen modes' frequencies (Hz) against the spin rate, a line per file, variant (method,
/// Ny, Nx, order, drive) and tracked mode, each its own colour and legend entry (its label, led by its variant when
/// there are several), with the excitation lines nP (f = n omega / 2 pi) of the harmonics and their crossings with
/// the modes (the critical speeds) marked; with a frequency limit, the axis ends there. A mode's rows are
/// interleaved with the other modes' in the file, and gnuplot breaks a line at every row a condition leaves out: so
/// each line's rows are first selected into a datablock of their own (`with table if`, gnuplot 5.4).
Figure campbell_figure(const std::vector<std::string>& files, const std::vector<std::string>& labels, bool label_lines,
                       const std::vector<int>& harmonics, const CampbellChoice& choice, const Kind& kind)
{
    const std::vector<CampbellLine> lines = campbell_lines(files, kind, choice);
    Figure f;
    f.axes = "set xlabel 'hub spin rate omega (rad/s)'\nset ylabel 'natural frequency f (Hz)'\n";
    if (choice.max_hz < HUGE_VAL) f.axes += "set yrange [0:" + shortest(choice.max_hz) + "]\n";
    add_mode_lines(f, lines, files, labels, label_lines);
    add_harmonics(f, lines, harmonics, choice);
    return f;
}

}  // namespace hubbeam::plotting
