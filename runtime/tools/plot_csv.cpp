// hubbeam plot's kinds of figure and the CSV files they read: each kind's format and columns, and the reading that
// checks a file's header and every row before a figure is drawn from it.
#include "plot_figures.hpp"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <hubbeam/field_recorder.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/option_lists.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/printable.hpp>
#include <hubbeam/simulate.hpp>

#include "gnuplot.hpp"

namespace hubbeam::plotting {

namespace {

const CsvFormat run_csv{"a run CSV", row_header};
const CsvFormat modes_csv{"a modes CSV", modes_header};
const CsvFormat field_csv{"a field CSV", FieldRecorder::header};

}  // namespace

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
        {"campbell", &modes_csv,
         {"method", "ny", "nx", "order", "drive", "omega", "mode", "kind", "hz", "growth", "damping_ratio"},
         {"ny", "omega", "mode", "hz", "growth", "damping_ratio"}, {"method", "nx", "order", "drive", "kind", "label"}, "Campbell diagram", {}},
        {"moment", &field_csv, {"t", "x"}, {"t", "x"}, {}, "Bending moment along the beam",
         // bending_moment is EI u_y'' of a beam in the plane; moment_figure labels a blade's as the edgewise moment
         {{"bending_moment", "bending moment M = EI d^2u_y/dx^2 (N m)", "M", "N m", "Bending moment along the beam"},
          {"flap_moment", "flapwise bending moment EI_{flap} kappa_n (N m)", "M_flap", "N m",
           "Flapwise bending moment along the blade"},
          {"torque", "torque GJ dphi/dx (N m)", "T", "N m", "Torque along the blade"}}},
    };
    return table;
}

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

namespace {

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

}  // namespace

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

}  // namespace hubbeam::plotting
