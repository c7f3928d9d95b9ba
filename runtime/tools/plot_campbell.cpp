// hubbeam plot campbell: the Campbell diagram of modes CSVs as rotor engineers draw it, a line per tracked mode of
// each variant in its family's shade and its whirl's dashes, named at its end, with the per-rev lines kP, the critical
// speeds where they cross the modes, the damping ratios and instabilities in a panel below, the operating range.
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

/// The kinds of mode a modes CSV names (NaturalMode::kind). A table that marks a real decaying eigenvalue's rows as
/// kind overdamped labels a mode that begins so "overdamped N": --kinds overdamped draws such lines where they
/// oscillate (campbell_lines leaves out every row of frequency 0, whatever its kind).
const std::vector<std::string>& mode_kinds()
{
    static const std::vector<std::string> k = {"bending", "edge", "flap", "twist", "axial", "hub", "overdamped"};
    return k;
}

namespace {

/// The rpm of 1 rad/s: the spin axis's factor in rpm.
constexpr double rpm_per_rad_s = 60.0 / (2.0 * M_PI);

/// The words a mode's kind or label may begin with to name its whirl (a rotor of several blades: backward,
/// forward, collective, differential; "BW2", "FW2", ... of a higher cyclic pair are BW and FW); a mode of one blade
/// names none.
constexpr const char* whirl_words[] = {"BW", "FW", "collective", "differential"};

/// A mode's kind or label read word by word: its whirl (one of whirl_words, or empty), its family (the kind:
/// "flap", "edge", ...) and its number (the label's last word; 0 where there is none).
struct ModeName {
    std::string whirl, family;
    int number = 0;
};

ModeName mode_name(const std::string& text)
{
    std::vector<std::string> words;
    for (std::size_t at = 0; at < text.size();) {
        const std::size_t space = text.find(' ', at);
        const std::size_t end = space == std::string::npos ? text.size() : space;
        if (end > at) words.push_back(text.substr(at, end - at));
        at = end + 1;
    }
    ModeName n;
    std::size_t first = 0;
    const auto higher_pair = [](const std::string& w) {
        return w.size() > 2 && (w.rfind("BW", 0) == 0 || w.rfind("FW", 0) == 0) &&
               w.find_first_not_of("0123456789", 2) == std::string::npos;
    };
    if (!words.empty() &&
        std::find(std::begin(whirl_words), std::end(whirl_words), words.front()) != std::end(whirl_words))
        n.whirl = words[first++];
    else if (!words.empty() && higher_pair(words.front()))
        n.whirl = words[first++].substr(0, 2);
    if (first < words.size()) n.family = words[first];
    if (words.size() > first + 1) parse_int(words.back(), 0, 1000000, n.number);
    return n;
}

/// A point of a Campbell line: the spin rate (rad/s), the frequency (Hz), and the damping ratio and growth rate
/// (the eigenvalue's real part, 1/s) that say whether the mode is stable there.
struct CampbellPoint {
    double omega, hz, zeta, growth;
    bool operator<(const CampbellPoint& o) const { return omega < o.omega; }
    /// Unstable: the eigenvalue in the right half-plane (a negative damping ratio, a positive real part).
    bool unstable() const { return zeta < 0.0 || growth > 0.0; }
};

/// A line of a Campbell diagram: one mode of one variant of one file, a tracked mode (by its label) or, in a file
/// without tracking, the modes of one kind and frequency rank; and its points by increasing rate.
struct CampbellLine {
    std::size_t file;
    std::vector<std::string> variant;  // method, ny, nx, nz, nt, order, drive as the file writes them (nz, nt: empty
                                       // in a file without them, an older hubbeam's)
    std::string column, mode;          // the column that tells the line's rows ("label" or "mode") and its value
    std::string kind;                  // the kind its rows are selected by in a file without tracking; empty: any
    std::string name;                  // its end label: the label ("bending 2"), or "bending mode 2"
    ModeName family;                   // its whirl, family and number: its colour and dash pattern
    std::vector<CampbellPoint> points;
    bool chosen = true;                // of a kind asked for (else drawn only where it is unstable)
    /// Whether some point of the line is unstable.
    bool grows() const { return std::any_of(points.begin(), points.end(), [](const CampbellPoint& p) { return p.unstable(); }); }
};

/// The modes CSV columns that name a variant, and how the key introduces each.
constexpr const char* variant_columns[] = {"method", "ny", "nx", "nz", "nt", "order", "drive"};
constexpr const char* variant_names[] = {"", " Ny = ", " Nx = ", " Nz = ", " Nt = ", " order ", " drive "};
constexpr std::size_t variant_size = std::size(variant_columns);

/// The Campbell diagram's lines, in the order of the files and of their first rows: each tracked mode whose label
/// names one of choice's kinds (after its whirl, if any: "BW edge 1" is an edge mode; its rows of every kind:
/// through a veering its shape may turn axial), or in a file without the label column (an older hubbeam's) the rows
/// of one of those kinds of each frequency rank; then of each variant the `modes` lowest (by their frequency at
/// their lowest rate). A line that is unstable at some rate is drawn whatever its rank, and whatever its kind unless
/// --kinds leaves it out (a rotor's hub whirl in a ground-resonance band): the default kinds hide no instability. A row of frequency 0 (an overdamped mode: it does not oscillate) is no point of any line,
/// whether or not the table lists it; the rates of those that grow (a divergence: a real root in the right
/// half-plane) go to `divergent`. Throws PlotInputError for a file without such rows.
std::vector<CampbellLine> campbell_lines(const std::vector<std::string>& files, const Kind& kind,
                                         const CampbellChoice& choice, std::vector<double>& divergent)
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
            if (!(r.number("hz") > 0.0)) {
                // A real root that grows (a divergence) is an instability all the same, whatever its kind.
                if (r.number("growth") > 0.0) divergent.push_back(r.number("omega"));
                return;
            }
            const bool tracked = r.has("label");
            const std::string& label = tracked ? r["label"] : r["kind"];
            ModeName family = mode_name(label);
            if (!tracked) family.number = static_cast<int>(r.number("mode"));
            CampbellLine l{file,
                           {r["method"], r["ny"], r["nx"], r.has("nz") ? r["nz"] : "", r.has("nt") ? r["nt"] : "",
                            r["order"], r["drive"]},
                           tracked ? "label" : "mode",
                           tracked ? label : r["mode"],
                           tracked ? "" : label,
                           tracked ? label : label + " mode " + r["mode"],
                           family,
                           {},
                           chosen(family.family)};
            auto same = std::find_if(
                lines.begin() + static_cast<std::ptrdiff_t>(before), lines.end(),
                [&](const CampbellLine& o) { return o.variant == l.variant && o.mode == l.mode && o.kind == l.kind; });
            if (same == lines.end()) same = lines.insert(lines.end(), l);
            same->points.push_back({r.number("omega"), r.number("hz"), r.number("damping_ratio"), r.number("growth")});
        });
        if (std::none_of(lines.begin() + static_cast<std::ptrdiff_t>(before), lines.end(),
                         [](const CampbellLine& l) { return l.chosen; }))
            throw PlotInputError(printable(files[file], 400) + ": expected rows of kind " + joined(choice.kinds, "'") +
                                 " with a frequency above 0 (the modes the Campbell diagram draws, --kinds), got none");
    }
    for (CampbellLine& l : lines) std::stable_sort(l.points.begin(), l.points.end());
    // Of each file's variant, the chosen lines ranked by their frequency at their lowest rate; the unstable ones all.
    std::vector<bool> keep(lines.size(), true);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        int lower = 0;
        for (std::size_t j = 0; j < lines.size(); ++j)
            if (j != i && lines[j].chosen && lines[j].file == lines[i].file && lines[j].variant == lines[i].variant &&
                (lines[j].points.front().hz < lines[i].points.front().hz ||
                 (lines[j].points.front().hz == lines[i].points.front().hz && j < i)))
                ++lower;
        const bool asked = lines[i].chosen || !choice.kinds_given;
        keep[i] = asked && (lines[i].grows() || (lines[i].chosen && (choice.modes == 0 || lower < choice.modes)));
    }
    std::vector<CampbellLine> kept;
    for (std::size_t i = 0; i < lines.size(); ++i)
        if (keep[i]) kept.push_back(std::move(lines[i]));
    return kept;
}

/// The lines with a point at or below max_hz: those wholly above it are left out.
std::vector<CampbellLine> lines_below(std::vector<CampbellLine> lines, double max_hz)
{
    std::erase_if(lines, [&](const CampbellLine& l) {
        return std::none_of(l.points.begin(), l.points.end(), [&](const CampbellPoint& p) { return p.hz <= max_hz; });
    });
    return lines;
}

/// Where line l meets the excitation line f = n omega / 2 pi between two of its points: (omega, Hz) where the
/// straight segment between them crosses it, to the eye (hubbeam modes refines them on the eigenvalues themselves;
/// the two agree as the rates are refined).
std::vector<std::pair<double, double>> campbell_crossings(const CampbellLine& l, int n)
{
    std::vector<std::pair<double, double>> at;
    const auto gap = [n](const CampbellPoint& p) { return p.hz - n * p.omega / (2.0 * M_PI); };
    for (std::size_t i = 0; i + 1 < l.points.size(); ++i) {
        const double ga = gap(l.points[i]), gb = gap(l.points[i + 1]);
        if (ga == 0.0 || ga * gb >= 0.0) {
            if (ga == 0.0) at.emplace_back(l.points[i].omega, l.points[i].hz);
            continue;
        }
        const double omega = l.points[i].omega + (l.points[i + 1].omega - l.points[i].omega) * ga / (ga - gb);
        at.emplace_back(omega, n * omega / (2.0 * M_PI));
    }
    return at;
}

/// Which variant columns the key names: method and Ny always, Nx, Nz, Nt, order and drive when they vary.
std::vector<bool> named_columns(const std::vector<CampbellLine>& lines)
{
    std::vector<bool> named = {true, true, false, false, false, false, false};
    for (const CampbellLine& l : lines)
        for (std::size_t c = 2; c < variant_size; ++c) named[c] = named[c] || l.variant[c] != lines.front().variant[c];
    return named;
}

/// The spin axis's unit: how a rate in rad/s reads on it, its expression in a gnuplot `using`, its label, and
/// the per-rev line kP as a function of the axis's x (f = k Omega / 2 pi in Hz).
struct SpinAxis {
    bool rpm;
    double of(double rad_s) const { return rpm ? rad_s * rpm_per_rad_s : rad_s; }
    std::string column() const { return rpm ? "(column('omega')*60/(2*pi))" : "'omega'"; }
    std::string unit() const { return rpm ? "rpm" : "rad/s"; }
    std::string per_rev(int k) const { return (k == 1 ? "" : std::to_string(k) + "*") + (rpm ? "x/60" : "x/(2*pi)"); }
};

/// The commands that select line l's rows of its file into the datablocks `block` (spin, Hz) and `zeta_block`
/// (spin, damping ratio in %).
std::string campbell_table(const std::string& block, const std::string& zeta_block, const CampbellLine& l,
                           const std::string& file, const SpinAxis& spin)
{
    std::string condition;
    for (std::size_t c = 0; c < variant_size; ++c)
        if (!l.variant[c].empty())  // a column the file has
            condition +=
                "strcol('" + std::string(variant_columns[c]) + "') eq " + gnuplot_string(l.variant[c]) + " && ";
    condition += "strcol('" + l.column + "') eq " + gnuplot_string(l.mode);
    if (!l.kind.empty()) condition += " && strcol('kind') eq " + gnuplot_string(l.kind);
    condition += " && column('hz') > 0";  // not an overdamped row (campbell_lines)
    const std::string from = "plot " + gnuplot_string(file) + " using " + spin.column() + ":";
    return "set table " + block + " separator comma\n" + from + "'hz' with table if (" + condition + ")\n" +
           "set table " + zeta_block + " separator comma\n" + from + "(100*column('damping_ratio')) with table if (" +
           condition + ")\n";
}

/// The shades of each mode family, darkest first (ColorBrewer's sequential scales, their light end left out so
/// that every shade reads on white): flap blue, edge and a planar beam's (in-plane) bending green, twist purple,
/// axial orange, the hub's pink, any other (overdamped) brown; none the greys of the per-rev lines nor the red of
/// the critical speeds and the instabilities.
struct Family {
    const char* name;
    const char* shades[5];
};
constexpr Family families[] = {
    {"flap", {"#08306b", "#08519c", "#2171b5", "#4292c6", "#6baed6"}},
    {"edge", {"#00441b", "#006d2c", "#238b45", "#41ab5d", "#74c476"}},
    {"bending", {"#00441b", "#006d2c", "#238b45", "#41ab5d", "#74c476"}},
    {"twist", {"#3f007d", "#54278f", "#6a51a3", "#807dba", "#9e9ac8"}},
    {"axial", {"#7f2704", "#a63603", "#d94801", "#f16913", "#fd8d3c"}},
    {"hub", {"#49006a", "#7a0177", "#ae017e", "#dd3497", "#f768a1"}},
    {"", {"#543005", "#8c510a", "#bf812d", "#a6761d", "#dfc27d"}},
};

/// The colour of mode `number` of a family: the family's hue, darker the lower the mode (shades cycle past 5).
std::string family_colour(const std::string& family, int number)
{
    const Family* f =
        std::find_if(std::begin(families), std::end(families) - 1, [&](const Family& g) { return family == g.name; });
    return f->shades[static_cast<std::size_t>(std::max(number, 1) - 1) % std::size(f->shades)];
}

/// The dash pattern of a whirl: backward whirl dashed, forward whirl dotted, collective (and a mode of one blade,
/// which names none) solid.
std::string whirl_dashes(const std::string& whirl)
{
    if (whirl == "BW") return "dt (12,6)";
    if (whirl == "FW") return "dt (2,4)";
    return "dt solid";
}

/// A variant's open marker.
int open_point(std::size_t variant_index)
{
    static const int open_points[] = {6, 4, 8, 12, 10, 14, 1, 2};
    return open_points[variant_index % std::size(open_points)];
}

/// The look of a Campbell line: its family's colour, its whirl's dashes; of one variant small dots at its rates; of
/// several an open marker of its own per variant (by the variant's index), larger and the line wider the earlier the
/// variant, so that variants whose frequencies coincide show as nested outlines.
std::string campbell_style(const std::string& colour, const std::string& whirl, std::size_t variant_index,
                           bool one_variant)
{
    char look[96];
    if (one_variant) {
        std::snprintf(look, sizeof look, "lw 2 lc rgb '%s' %s pt 7 ps 0.5", colour.c_str(),
                      whirl_dashes(whirl).c_str());
        return look;
    }
    std::snprintf(look, sizeof look, "lw %.1f lc rgb '%s' %s pt %d ps %.2f",
                  std::max(1.0, 2.5 - 0.4 * static_cast<double>(variant_index)), colour.c_str(),
                  whirl_dashes(whirl).c_str(), open_point(variant_index),
                  std::max(0.6, 1.6 - 0.25 * static_cast<double>(variant_index)));
    return look;
}

/// The look of the per-rev line kP: thin light grey, solid, so that the modes' dashes (their whirl) stay apart from
/// it; the rotor's N-per-rev multiples (k a multiple of N blades) heavier and darker, as the rotor passes their
/// excitation on to the hub.
std::string per_rev_style(int k, int blades)
{
    const bool multiple = blades > 1 && k % blades == 0;
    return multiple ? "lw 2.5 dt solid lc rgb '#303030'" : "lw 1 dt solid lc rgb '#909090'";
}

/// Labels at the right edge of the frequency panel: text at height y (Hz), moved apart so that no two overlap (at
/// least gap Hz apart, inside [0, top] when they fit), in the order of their heights.
struct EndLabel {
    std::string text, colour;
    double y;
};
void spread(std::vector<EndLabel>& labels, double gap, double top)
{
    std::stable_sort(labels.begin(), labels.end(), [](const EndLabel& a, const EndLabel& b) { return a.y < b.y; });
    for (EndLabel& l : labels) l.y = std::clamp(l.y, 0.0, top);
    for (std::size_t i = 1; i < labels.size(); ++i) labels[i].y = std::max(labels[i].y, labels[i - 1].y + gap);
    if (!labels.empty() && labels.back().y > top) {
        labels.back().y = top;
        for (std::size_t i = labels.size() - 1; i-- > 0;) labels[i].y = std::min(labels[i].y, labels[i + 1].y - gap);
    }
}

/// A datablock of points "x,y" a line each.
std::string datablock(const std::string& name, const std::vector<std::pair<double, double>>& points)
{
    std::string block = name + " << EOD\n";
    for (const auto& [x, y] : points) block += shortest(x) + ',' + shortest(y) + '\n';
    return block + "EOD\n";
}

/// The Campbell figure under construction: its lines, what they share, and the key's entries (in the lower panel's
/// right margin, where no label can be cut off).
struct Campbell {
    const std::vector<CampbellLine>& lines;
    const CampbellChoice& choice;
    SpinAxis spin;
    double top;  // the frequency axis's top (Hz)
    Figure& f;
    std::vector<std::string> key;   // the key's entries (plot elements drawing nothing but their sample)
    std::vector<double> divergent;  // the rates (rad/s) of a divergence: a real root that grows, at 0 Hz

    /// Adds an entry to the key: the sample `look` draws (of NaN: nothing in the panel), named text.
    void add_key(const std::string& look, const std::string& text)
    {
        key.push_back("NaN with " + look + " " + title_of(text, "a modes CSV's variant"));
        f.longest_label = std::max(f.longest_label, legend_size(text));
    }
};

/// Adds the chosen modes' lines to both panels, each in its family's shade and its whirl's dashes, a marker at
/// every rate up to 12 and at about 12 of them beyond, named at its end (once per name: a mode of several variants or
/// files ends in one label, the variants told by their markers in the key, led by their file's label when
/// label_lines; one variant's name goes to the title instead). A mode unstable anywhere says so in its label.
void add_mode_lines(Campbell& c, const std::vector<std::string>& files, const std::vector<std::string>& labels,
                    bool label_lines)
{
    const std::vector<CampbellLine>& lines = c.lines;
    const std::vector<bool> named = named_columns(lines);
    // Fixed ranges while the rows are selected: an autoscaled one warns of a column of one value (an undamped
    // table's damping ratios, a table at one rate), and `with table` keeps every row whatever the ranges.
    c.f.data =
        "# two datablocks per line: the rows of one tracked mode of one variant, Hz ($modeN) and damping ratio "
        "in % ($zetaN)\nset xrange [-1:1]\nset yrange [-1:1]\n";
    std::vector<std::pair<std::size_t, std::vector<std::string>>> variants;  // (file, variant): a marker each
    for (const CampbellLine& l : lines)
        if (std::find(variants.begin(), variants.end(), std::pair{l.file, l.variant}) == variants.end())
            variants.emplace_back(l.file, l.variant);
    // A variant's name: "amm Ny = 4" in the key, "amm, Ny = 4" in the title.
    const auto variant_name = [&](const CampbellLine& l, const char* comma) {
        std::string name;
        for (std::size_t c = 0; c < variant_size; ++c)
            if (named[c]) name += (c ? comma : "") + std::string(variant_names[c]) + l.variant[c];
        return name;
    };
    // One variant: its name goes to the title.
    if (variants.size() == 1) c.f.title_suffix = " (" + variant_name(lines.front(), ",") + ")";
    std::vector<EndLabel> ends;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const CampbellLine& l = lines[i];
        const std::string block = "$mode" + std::to_string(i + 1), zeta = "$zeta" + std::to_string(i + 1);
        c.f.data += campbell_table(block, zeta, l, files[l.file], c.spin);
        const std::size_t v = static_cast<std::size_t>(
            std::find(variants.begin(), variants.end(), std::pair{l.file, l.variant}) - variants.begin());
        const std::string colour = family_colour(l.family.family, l.family.number);
        // smooth unique: the points by increasing rate, whatever the rows' order in the file
        const std::string look = " using 1:2 smooth unique with linespoints " +
                                 campbell_style(colour, l.family.whirl, v, variants.size() == 1) + " pi " +
                                 std::to_string((l.points.size() + 11) / 12) + " notitle";
        c.f.elements.push_back(block + look);
        c.f.lower_elements.push_back(zeta + look);
        const bool unstable = std::any_of(l.points.begin(), l.points.end(), [](const auto& p) { return p.unstable(); });
        const std::string text = l.name + (unstable ? " (unstable)" : "");
        if (std::none_of(ends.begin(), ends.end(), [&](const EndLabel& e) { return e.text == text; }))
            ends.push_back({text, colour, l.points.back().hz});
    }
    c.f.data += "unset table\n";
    // The labels at the right edge, a line of text apart (the panel is about 330 pixels high, a label 15).
    spread(ends, 0.045 * c.top, c.top);
    for (const EndLabel& e : ends) {
        c.f.axes += "set label " + gnuplot_string(shortened(e.text, legend_cap), "a modes CSV's label") +
                    " at graph 1, first " + shortest(e.y) + " left offset 1.5,0 tc rgb '" + e.colour +
                    "' front noenhanced\n";
        c.f.longest_label = std::max(c.f.longest_label, legend_size(e.text));
    }
    // Several variants: each its marker in the key.
    if (variants.size() > 1)
        for (std::size_t v = 0; v < variants.size(); ++v) {
            const auto& line = *std::find_if(lines.begin(), lines.end(), [&](const CampbellLine& l) {
                return std::pair{l.file, l.variant} == variants[v];
            });
            char marker[48];
            std::snprintf(marker, sizeof marker, "points pt %d ps %.2f lc rgb '#404040'", open_point(v),
                          std::max(0.6, 1.6 - 0.25 * static_cast<double>(v)));
            c.add_key(marker, (label_lines ? labels[line.file] + ": " : "") + variant_name(line, ""));
        }
    for (const auto& [whirl, name] : {std::pair{"BW", "backward whirl (BW)"}, {"FW", "forward whirl (FW)"}})
        if (std::any_of(lines.begin(), lines.end(), [&](const CampbellLine& l) { return l.family.whirl == whirl; }))
            c.add_key("lines lw 1.5 lc rgb '#404040' " + whirl_dashes(whirl), name);
}

/// Marks every point where a mode is unstable (a negative damping ratio, a positive real part) in both panels, and
/// every divergence at 0 Hz in the upper one (its damping ratio, -1, would squash the lower), with a red cross of its
/// own in the key.
void add_instabilities(Campbell& c)
{
    std::vector<std::pair<double, double>> hz, zeta;
    for (const CampbellLine& l : c.lines)
        for (const CampbellPoint& p : l.points)
            if (p.unstable()) {
                hz.emplace_back(c.spin.of(p.omega), p.hz);
                zeta.emplace_back(c.spin.of(p.omega), 100.0 * p.zeta);
            }
    for (const double omega : c.divergent) hz.emplace_back(c.spin.of(omega), 0.0);
    if (hz.empty()) return;
    const std::string look = " using 1:2 with points pt 2 ps 2 lw 2.5 lc rgb '#b2182b' notitle";
    c.f.data += datablock("$unstable", hz);
    c.f.elements.push_back("$unstable" + look);
    if (!zeta.empty()) {
        c.f.data += datablock("$unstable_zeta", zeta);
        c.f.lower_elements.push_back("$unstable_zeta" + look);
    }
    c.add_key("points pt 2 ps 2 lw 2.5 lc rgb '#b2182b'", "unstable");
}

/// Adds the per-rev lines kP (f = k Omega / 2 pi), each named at its end inside the figure, the rotor's N-per-rev
/// multiples heavier, and their crossings with the lines (the critical speeds) at or below the axis's top.
void add_per_rev(Campbell& c, const std::vector<int>& harmonics)
{
    double omega_top = 0.0;
    for (const CampbellLine& l : c.lines)
        for (const CampbellPoint& p : l.points) omega_top = std::max(omega_top, p.omega);
    std::vector<std::pair<double, double>> crossings;
    for (const int k : harmonics) {
        c.f.elements.push_back(c.spin.per_rev(k) + " with lines " + per_rev_style(k, c.choice.blades) + " notitle");
        // Its name at its end inside the figure: at the highest rate, or where it leaves through the top.
        if (omega_top > 0.0) {
            const double hz_end = k * omega_top / (2.0 * M_PI);
            const bool leaves_at_top = hz_end > c.top;
            const double omega = leaves_at_top ? c.top * 2.0 * M_PI / k : omega_top, y = leaves_at_top ? c.top : hz_end;
            c.f.axes += "set label '" + std::to_string(k) + "P' at " + shortest(c.spin.of(omega)) + "," + shortest(y) +
                        (leaves_at_top ? " right offset -0.6,-0.9" : " right offset -0.6,0.9") + " front\n";
        }
        for (const CampbellLine& l : c.lines)
            for (const auto& [omega, hz] : campbell_crossings(l, k))
                if (hz <= c.top) crossings.emplace_back(c.spin.of(omega), hz);
    }
    if (c.choice.blades > 1)
        c.add_key(
            "lines " + per_rev_style(c.choice.blades, c.choice.blades),
            std::to_string(c.choice.blades) + "P and its multiples (" + std::to_string(c.choice.blades) + " blades)");
    if (!crossings.empty()) {
        c.f.data += datablock("$critical", crossings);
        c.f.elements.push_back("$critical using 1:2 with points pt 7 ps 1.2 lc rgb 'red' notitle");
        c.add_key("points pt 7 ps 1.2 lc rgb 'red'", "critical speeds");
    }
}

}  // namespace

double campbell_cutoff(int highest_per_rev, double omega_max, double lowest_top)
{
    if (highest_per_rev <= 0 || !(omega_max > 0.0)) return HUGE_VAL;
    return 1.1 * std::max(highest_per_rev * omega_max / (2.0 * M_PI), lowest_top);
}

/// A Campbell diagram: the chosen modes' frequencies (Hz) against the spin rate (rad/s or rpm) above, their damping
/// ratios (%) below, a line per file, variant (method, Ny, Nx, order, drive) and tracked mode, in its family's
/// shade and its whirl's dashes, named at its end; the per-rev lines kP (f = k Omega / 2 pi) named at theirs, their
/// crossings with the modes (the critical speeds) and the modes' unstable points marked, the operating range shaded.
/// The frequency axis ends at the cutoff (given, or campbell_cutoff's), and the lines wholly above it are left out.
/// A mode's rows are interleaved with the other modes' in the file, and gnuplot breaks a line at every row a
/// condition leaves out: so each line's rows are first selected into a datablock of their own (`with table if`,
/// gnuplot 5.4).
Figure campbell_figure(const std::vector<std::string>& files, const std::vector<std::string>& labels, bool label_lines,
                       const std::vector<int>& harmonics, const CampbellChoice& choice, const Kind& kind)
{
    std::vector<double> divergent;
    std::vector<CampbellLine> lines = campbell_lines(files, kind, choice, divergent);
    double omega_lo = HUGE_VAL, omega_hi = 0.0, hz_lo = HUGE_VAL, hz_hi = 0.0, lowest_at_rest = HUGE_VAL,
           lowest_top = 0.0;
    for (const CampbellLine& l : lines) {
        for (const CampbellPoint& p : l.points) {
            omega_lo = std::min(omega_lo, p.omega), omega_hi = std::max(omega_hi, p.omega);
            hz_lo = std::min(hz_lo, p.hz), hz_hi = std::max(hz_hi, p.hz);
        }
        if (l.points.front().hz < lowest_at_rest) {
            lowest_at_rest = l.points.front().hz;
            lowest_top = std::max_element(l.points.begin(), l.points.end(), [](const auto& a, const auto& b) {
                             return a.hz < b.hz;
                         })->hz;
        }
    }
    const int highest = harmonics.empty() ? 0 : *std::max_element(harmonics.begin(), harmonics.end());
    const double cutoff = choice.max_hz < HUGE_VAL ? choice.max_hz : campbell_cutoff(highest, omega_hi, lowest_top);
    lines = lines_below(std::move(lines), cutoff);
    if (lines.empty())  // a cutoff given below every mode (the automatic one keeps the lowest)
        bad_option<PlotInputError>("--max-frequency",
                                   "a frequency at or above the lowest mode drawn (" + shortest(hz_lo) + " Hz)",
                                   shortest(cutoff));
    Figure f;
    Campbell c{lines, choice, SpinAxis{choice.rpm}, cutoff < HUGE_VAL ? cutoff : 1.05 * hz_hi, f, {}, divergent};
    const std::string spin_label = "'hub spin rate Omega (" + c.spin.unit() + ")'";
    f.axes = "set key off\nset ytics autofreq\nset xlabel " + spin_label + "\nset ylabel 'natural frequency f (Hz)'\n";
    f.axes += "set yrange [0:" + shortest(c.top) + "]\n";
    f.axes += omega_hi > omega_lo
                  ? "set xrange [" + shortest(c.spin.of(omega_lo)) + ":" + shortest(c.spin.of(omega_hi)) + "]\n"
                  : std::string("set autoscale x\n");
    if (choice.has_range) {
        f.axes += "set object 1 rect from " + shortest(choice.range_lo) + ", graph 0 to " + shortest(choice.range_hi) +
                  ", graph 1 fillcolor rgb '#fde9b0' fillstyle solid 1.0 noborder behind\n";
        c.add_key("boxes fillstyle solid 1.0 noborder fillcolor rgb '#fde9b0'", "operating range");
    }
    add_mode_lines(c, files, labels, label_lines);
    add_instabilities(c);
    add_per_rev(c, harmonics);
    // The damping panel: the stability boundary at 0, the key in its right margin below the modes' labels.
    // Its range from the damping ratios drawn, 0 among them (gnuplot's autoscale would warn of an undamped table's).
    double zeta_lo = 0.0, zeta_hi = 0.0;
    for (const CampbellLine& l : lines)
        for (const CampbellPoint& p : l.points)
            if (std::isfinite(p.zeta))
                zeta_lo = std::min(zeta_lo, 100.0 * p.zeta), zeta_hi = std::max(zeta_hi, 100.0 * p.zeta);
    const double pad = zeta_hi > zeta_lo ? 0.08 * (zeta_hi - zeta_lo) : 1.0;
    // About four tics in the low panel: 1, 2 or 5 times a power of 10 (gnuplot's own crowd it with ten).
    const double raw = (zeta_hi - zeta_lo + 2.0 * pad) / 4.0, decade = std::pow(10.0, std::floor(std::log10(raw)));
    const double tic = raw <= decade         ? decade
                       : raw <= 2.0 * decade ? 2.0 * decade
                       : raw <= 5.0 * decade ? 5.0 * decade
                                             : 10.0 * decade;
    f.lower_axes = "unset label\nset xlabel " + spin_label + "\nset ylabel 'damping ratio zeta (%)'\nset yrange [" +
                   shortest(zeta_lo - pad) + ":" + shortest(zeta_hi + pad) + "]\nset ytics " + shortest(tic) + "\n" +
                   (c.key.empty() ? std::string("unset key\n")
                                  : "set key at screen " + shortest(std::stod(right_edge(f)) + 0.02) +
                                        ", screen 0.33 left top Left reverse samplen 2 box\n");
    f.lower_elements.push_back("0 with lines lw 1 lc rgb 'black' notitle");
    for (const std::string& k : c.key) f.lower_elements.push_back(k);
    return f;
}

}  // namespace hubbeam::plotting
