// Figures with gnuplot: the shared look, the run of gnuplot, and hubbeam plot's kinds of figure with the CSV
// formats they read.
#include "plot.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <iterator>
#include <memory>
#include <string>

#include <unistd.h>

#include <hubbeam/fields.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include "io/field_recorder.hpp"
#include "io/output_file.hpp"
#include "text/csv_columns.hpp"
#include "text/option_lists.hpp"
#include "text/printable.hpp"
#include "text/shortest.hpp"

namespace hubbeam {

std::string gnuplot_string(std::string_view text, const std::string& name)
{
    // Inside single quotes gnuplot reads every byte as it is but a quote (below) and the line's end: a newline in
    // a name would end the string's command, and the next line is gnuplot's to run ('!' hands it to the shell).
    check_handed_text<PlotInputError>(name, text, "text");
    if (text.find('\'') == std::string_view::npos) return "'" + std::string(text) + "'";
    // Not 'it''s': gnuplot 5.4 misreads two doubled quotes in a row. Each quote is a "'" of its own, concatenated
    // (a double-quoted string holding more would run any `command` in backquotes).
    std::string s = "(";
    std::size_t start = 0;
    while (true) {
        const std::size_t quote = text.find('\'', start);
        const std::string_view part = text.substr(start, quote == std::string_view::npos ? quote : quote - start);
        if (!part.empty()) s += (s.size() > 1 ? "." : "") + ("'" + std::string(part) + "'");
        if (quote == std::string_view::npos) return s + ")";
        s += (s.size() > 1 ? "." : "") + std::string("\"'\"");
        start = quote + 1;
    }
}

void check_prefix(const std::string& option, const std::string& prefix)
{
    if (prefix.empty()) bad_option<OutputRefused>(option, "a path prefix for the figure's files", "");
    check_handed_text<OutputRefused>(option, prefix, "a path prefix");
    // The files are PREFIX.png and so on: a prefix that names a folder (DIR/, DIR/., ..) would make them the hidden
    // DIR/.png or the names ..png, ...png beside it.
    if (const std::string name = std::filesystem::path(prefix).filename().string();
        name.empty() || name == "." || name == "..")
        throw OutputRefused(option + ": expected a path prefix that ends in a file name (as DIR/NAME for " +
                            "DIR/NAME.png), got \"" + printable(prefix, 400) + "\", which names a folder");
}

std::string figure_style()
{
    return "set datafile separator ','\n"
           "set key outside right top box width 2\n"
           "set grid\n";
}

std::string in_png_and_svg(const std::string& figures)
{
    return "do for [term in 'pngcairo svg'] {\n"
           "  ext = (term eq 'svg') ? 'svg' : 'png'\n"
           "  if (term eq 'svg') { set terminal svg size 1000,640 font 'Sans,12' } else { set terminal pngcairo size "
           "1000,640 font 'Sans,11' }\n" +
           figures + "}\n";
}

std::string figure_output(const std::string& prefix)
{
    return "  set output " + gnuplot_string(prefix + ".") + ".ext\n";
}

std::string run_gnuplot(const std::string& script_path)
{
    // The path in the shell's single quotes, its own quotes as '\'' (close, escaped quote, reopen).
    std::string quoted = "'";
    for (const char c : script_path) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    const std::string command = "gnuplot " + quoted + "' 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) return "cannot run gnuplot";
    std::string messages;
    char buf[256];
    while (std::fgets(buf, sizeof buf, pipe) != nullptr) messages += buf;
    const int status = ::pclose(pipe);
    while (!messages.empty() && (messages.back() == '\n' || messages.back() == ' ')) messages.pop_back();
    if (status != 0) return "gnuplot failed (is it installed? apt-get install gnuplot-nox): " + messages;
    return {};
}

namespace {

/// A CSV format that kinds read: what it is called in messages, and its header (the writer's one definition).
struct CsvFormat {
    const char* name;                // "a run CSV"
    const char* (*header)();         // the first line the writer puts
};

const CsvFormat run_csv{"a run CSV", row_header};
const CsvFormat modes_csv{"a modes CSV", modes_header};
const CsvFormat field_csv{"a field CSV", FieldRecorder::header};

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

const std::vector<Kind>& kinds()
{
    static const std::vector<Kind> table{
        {"tip", &run_csv, {"t"}, {"t"}, {}, "Tip deflection",
         {{"tip_uy", "tip deflection u_y(L) (m)", "u_y(L)", "m", "Tip deflection"},
          // a blade's (docs/model.md section 12): its run CSV has them where the blade has the field
          {"tip_uz", "tip flapwise deflection u_z(L) (m)", "u_z(L)", "m", "Tip flapwise deflection"},
          {"tip_phi", "tip twist phi(L) (rad)", "phi(L)", "rad", "Tip twist"}}},
        {"axial", &run_csv, {"t", "tip_ux1", "tip_ux"}, {"t", "tip_ux1", "tip_ux"}, {},
         "Longitudinal tip deformation with and without foreshortening", {}},
        // label is optional (a modes CSV of an older hubbeam has none); its text goes into the script where it is
        {"campbell", &modes_csv, {"method", "ny", "nx", "order", "drive", "omega", "mode", "kind", "hz"},
         {"ny", "omega", "mode", "hz"}, {"method", "nx", "order", "drive", "kind", "label"}, "Campbell diagram", {}},
        {"moment", &field_csv, {"t", "x"}, {"t", "x"}, {}, "Bending moment along the beam",
         // bending_moment is EI u_y'' of a beam in the plane; moment_figure labels a blade's as the edgewise moment
         {{"bending_moment", "bending moment M = EI d^2u_y/dx^2 (N m)", "M", "N m", "Bending moment along the beam"},
          {"flap_moment", "flapwise bending moment EI_{flap} kappa_n (N m)", "M_flap", "N m",
           "Flapwise bending moment along the blade"},
          {"torque", "torque GJ dphi/dx (N m)", "T", "N m", "Torque along the blade"}}},
    };
    return table;
}

/// kind reading column q as well (a copy: the table stays as it is).
Kind reading(const Kind& kind, const Quantity& q)
{
    Kind k = kind;
    k.columns.emplace_back(q.column);
    k.numeric.emplace_back(q.column);
    return k;
}

bool is_number(const std::string& s, double& v)
{
    const char* end = s.data() + s.size();
    const auto [ptr, ec] = std::from_chars(s.data(), end, v);
    return ec == std::errc() && ptr == end;
}

/// What a header without the column `missing` is, for the message: another format the kinds read, or its count of
/// fields. Never the line itself: a message quotes no file's content (that of a file the user was not meant to
/// read, named by mistake or by someone else).
std::string header_seen(const std::string& header, const Kind& kind, const std::string& missing)
{
    std::vector<std::string> readers;
    const CsvFormat* format = nullptr;
    for (const Kind& k : kinds())
        if (header == k.format->header() && k.format != kind.format) {
            format = k.format;
            readers.emplace_back(k.name);
        }
    if (format == nullptr) {
        const std::size_t n = csv_fields(header).size();
        return "a first line of " + std::to_string(n) + " comma-separated field" + (n == 1 ? "" : "s") +
               ", none of them " + missing;
    }
    return "the header of " + std::string(format->name) + ", which kind" + (readers.size() > 1 ? "s " : " ") +
           joined(readers) + " read" + (readers.size() > 1 ? "" : "s");
}

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
void read_csv(const std::string& path, const Kind& kind, const std::function<void(const Record&)>& row)
{
    const std::string file = printable(path, 400);
    const auto bad = [&](const std::string& what) { throw PlotInputError(file + ": " + what); };
    // Checked before opening (open() on a FIFO waits for a writer); and a file is read twice, here and by gnuplot:
    // a pipe would be empty the second time, /dev/zero has no lines.
    if (const std::string kind = not_a_regular_file(path); !kind.empty()) bad("expected a regular file, got " + kind);
    std::ifstream in(path, std::ios::binary);
    if (!in) bad(std::string("cannot open: ") + std::strerror(errno));
    const std::string expected =
        "expected " + std::string(kind.format->name) + " for kind " + kind.name + " (header " + kind.format->header();
    std::string line;
    if (!std::getline(in, line)) bad(expected + "), got an empty file");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const CsvColumns columns(file, line);
    for (const std::string& name : kind.columns)
        if (!columns.has(name))
            bad(expected + "; it needs the column " + name + "), got " + header_seen(line, kind, name));
    long line_number = 1, rows = 0;
    while (std::getline(in, line)) {
        ++line_number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) continue;  // a blank line (gnuplot's block separator) is no row
        const std::string at = "line " + std::to_string(line_number) + ": ";
        const std::vector<std::string> fields = csv_fields(line);
        if (fields.size() != columns.size())
            bad(at + "expected " + std::to_string(columns.size()) + " comma-separated fields as in the header, got " +
                std::to_string(fields.size()));
        // A cell is named by its line, column number and name, never quoted (a message quotes no file's content).
        const auto cell = [&](const std::string& name) {
            return "line " + std::to_string(line_number) + ", column " + std::to_string(columns.at(name) + 1) + " (" +
                   name + "): ";
        };
        for (const std::string& name : kind.numeric)
            if (double v = 0.0; !is_number(fields[columns.at(name)], v))
                bad(cell(name) + "expected a number (as 0.25 or -1.5e-3), got " +
                    (fields[columns.at(name)].empty() ? std::string("an empty field")
                                                      : std::to_string(fields[columns.at(name)].size()) +
                                                            " characters that are not one"));
        for (const std::string& name : kind.texts)
            if (columns.has(name))
                if (const std::string why = unsafe_character(fields[columns.at(name)]); !why.empty())
                    bad(cell(name) + "expected text without control or format characters (it goes into the gnuplot "
                                     "script), got " + why);
        row(Record(columns, fields));
        ++rows;
    }
    if (in.bad()) bad(std::string("cannot read: ") + std::strerror(errno));
    if (rows == 0) bad("expected rows after the header, got none");
}

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

/// The most characters of a legend entry: a longer one (a long file name, a tabulated blade's variant) would widen
/// the legend's box on the right until it pushed the axes out of the figure.
constexpr std::size_t legend_cap = 60;
/// The most characters of the scene's name in a default title.
constexpr std::size_t title_cap = 80;

/// text cut to at most cap characters (UTF-8 code points) by "..." in its middle, so that its start and its end
/// (a file's name, then the mode's label) both stay.
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
std::string title_of(const std::string& text, const std::string& name = "--labels")
{
    return "title " + gnuplot_string(shortened(text, legend_cap), name) + " noenhanced";
}

/// The characters of a legend entry as title_of writes it.
std::size_t legend_size(const std::string& text)
{
    return std::min(text.size(), legend_cap);
}

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

/// Figures 3-4, 7-8 and 9-12 of the paper: tip_uy against t, a line per file; or a blade's tip_uz or tip_phi (q).
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

/// Figures 5-6: per file, the tip's displacement u_x with the foreshortening u_x2 = -1/2 int u_y'^2 (thick) and
/// its axial stretch u_x1 alone (thin, with points), both in the file's colour and dash pattern.
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

/// The kinds of mode a modes CSV names (NaturalMode::kind). A table that marks a real decaying eigenvalue's rows as
/// kind overdamped labels a mode that begins so "overdamped N": --kinds overdamped draws such lines where they
/// oscillate (campbell_lines leaves out every row of frequency 0, whatever its kind).
const std::vector<std::string>& mode_kinds()
{
    static const std::vector<std::string> k = {"bending", "edge", "flap", "twist", "axial", "hub", "overdamped"};
    return k;
}

/// Which lines a Campbell diagram draws (plot's --kinds, --modes, --max-hz).
struct CampbellChoice {
    std::vector<std::string> kinds = {"bending", "edge", "flap"};  // a planar beam's, or a blade's out of the plane
    int modes = 0;                // the lowest this many lines of each variant; 0: all
    double max_hz = HUGE_VAL;     // the frequency axis ends here, and lines wholly above it are left out
};

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
    const std::vector<bool> named = named_columns(lines);
    Figure f;
    f.axes = "set xlabel 'hub spin rate omega (rad/s)'\nset ylabel 'natural frequency f (Hz)'\n";
    if (choice.max_hz < HUGE_VAL) f.axes += "set yrange [0:" + shortest(choice.max_hz) + "]\n";
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

/// Where the panels of a two-panel figure end on the right (screen fraction): room for the widest legend entry.
std::string right_edge(const Figure& f)
{
    const double chars = static_cast<double>(f.longest_label);
    const double edge = std::clamp(0.93 - 0.0085 * chars - 0.06, 0.55, 0.85);
    char buf[16];
    std::snprintf(buf, sizeof buf, "%.3f", edge);
    return buf;
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
                                        {"--max-hz", args.max_hz}})
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
        bad_option<PlotInputError>("--max-hz", "a frequency > 0 (Hz)", printable(args.max_hz, 40));
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
    if (name == "campbell")
        // the labels name the lines once there is more than one file, or when given
        return campbell_figure(
            args.files, labels, args.files.size() > 1 || !args.labels.empty(),
            parse_harmonics<PlotInputError>("--harmonics", args.harmonics.empty() ? default_harmonics : args.harmonics),
            campbell_choice(args), kind);
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

namespace {

/// Whether gnuplot's figure at path ends as a whole PNG (its IEND chunk) or SVG (the closing tag) does: a full disk or
/// a file size limit cuts it, and gnuplot does not always say so.
bool complete_figure(const std::string& path, bool png)
{
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) return false;
    if (png) {
        static const std::string iend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
        return text.size() >= 20 && text.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0 &&
               text.compare(text.size() - iend.size(), iend.size(), iend) == 0;
    }
    const std::size_t end = text.find_last_not_of(" \t\r\n");
    return end != std::string::npos && end >= 5 && text.compare(end - 5, 6, "</svg>") == 0;
}

}  // namespace

std::string draw_figures(const std::vector<std::string>& prefixes, const std::string& script_path,
                         const std::string& script,
                         const std::function<std::string(const std::vector<std::string>&)>& script_for)
{
    // Each figure gets its lock and its temporary files DIR/.NAME.tmp-PID.png and .svg first: one prefix, since
    // the script derives both names from it.
    std::vector<std::unique_ptr<OutputFile>> figures;
    std::vector<std::string> temp_prefixes;
    for (const std::string& prefix : prefixes) {
        check_prefix("PREFIX", prefix);  // for every caller (plot, bench --plot, modes --plot), whatever it checked
        const std::filesystem::path p(prefix);
        for (int attempt = 0;; ++attempt) {
            std::string name = ".";
            name += p.filename().string();
            name += ".tmp-" + std::to_string(::getpid()) + (attempt ? "-" + std::to_string(attempt) : "");
            const std::string temp = (p.parent_path() / name).string();
            try {
                auto png = std::make_unique<OutputFile>(prefix + ".png", temp + ".png");
                auto svg = std::make_unique<OutputFile>(prefix + ".svg", temp + ".svg");
                figures.push_back(std::move(png));
                figures.push_back(std::move(svg));
                temp_prefixes.push_back(temp);
                break;
            } catch (const OutputFile::TempExists&) {
                if (attempt >= 100) throw std::runtime_error(prefix + ": cannot create its temporary figures");
            }
        }
    }
    OutputFile gp(script_path);
    if (const int error = gp.write(script); error != 0)
        return printable(script_path, 400) + ": write failed: " + std::strerror(error) + " (no figure replaced)";
    // gnuplot draws into the temporary files, from a script of its own beside them (removed afterwards).
    OutputFile draw(temp_prefixes.front() + ".gp");
    if (const int error = draw.write(script_for(temp_prefixes)); error != 0)
        return printable(draw.temp_path(), 400) + ": write failed: " + std::strerror(error) + " (no figure replaced)";
    const std::string problem = run_gnuplot(draw.temp_path());
    draw.discard();
    if (!problem.empty()) return problem;
    for (std::size_t i = 0; i < figures.size(); ++i)
        if (!complete_figure(figures[i]->temp_path(), i % 2 == 0))
            return printable(figures[i]->path(), 400) + ": gnuplot wrote an incomplete file (a full disk?); the old "
                   "figures are as they were";
    if (const std::string why = gp.commit(); !why.empty()) return printable(script_path, 400) + ": " + why;
    for (const auto& f : figures)
        if (const std::string why = f->commit(); !why.empty()) return printable(f->path(), 400) + ": " + why;
    return {};
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
