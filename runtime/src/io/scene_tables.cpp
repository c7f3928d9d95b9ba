// The files a scene reads: the scene file itself and the CSV tables it names (beam.profile, motion.file), each
// read whole and checked before anything runs.
#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <hubbeam/scene.hpp>
#include <optional>

#include "io/output_file.hpp"
#include "io/scene_io.hpp"
#include "text/csv_columns.hpp"
#include "text/printable.hpp"
#include "text/shortest.hpp"

namespace hubbeam {

using namespace scene_io;

std::string scene_io::read_file(const std::string& path, std::size_t cap)
{
    // Checked before opening: open() on a FIFO waits for a writer, and a device or a directory is no scene.
    if (const std::string kind = not_a_regular_file(path); !kind.empty())
        throw SceneError::with_detail(path, "", "cannot open: it is " + kind + ", not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SceneError::with_detail(path, "", std::string("cannot open: ") + std::strerror(errno));
    // Read by the file's own size, in chunks, and at most one byte past the cap: a scene is a few kilobytes (a
    // buffer of the cap's size zero-filled for it cost a run's start-up millions of instructions), and /dev/zero
    // never ends.
    std::string text;
    std::array<char, 1 << 14> chunk;
    while (text.size() <= cap) {
        const std::size_t want = std::min(chunk.size(), cap + 1 - text.size());
        in.read(chunk.data(), static_cast<std::streamsize>(want));
        text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
        if (static_cast<std::size_t>(in.gcount()) < want) break;  // the end of the file, or an error (below)
    }
    if (in.bad()) throw SceneError::with_detail(path, "", std::string("cannot read: ") + std::strerror(errno));
    return text;
}

std::string_view scene_io::trimmed(std::string_view s)
{
    const std::size_t first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

namespace {

/// A numeric CSV table named by a scene key (beam.profile, motion.file): its header's column count and line and,
/// for each row, the values of the wanted columns and the row's line. Read whole by read_file (FIFOs, devices and
/// folders refused; at most cap bytes) and checked before anything runs; blank lines, lines starting with '#' and a
/// spreadsheet's byte-order mark are skipped. Every problem is "SCENE: KEY: FILE[:LINE]: what", what saying what was
/// expected and where (line, column, field), never what the file holds: a scene may name any file its reader can
/// read, and the message may reach someone who cannot.
struct NumericTable {
    std::size_t header_columns = 0;
    long header_line = 0;                   // comment and blank lines may come before the header
    std::vector<std::vector<double>> rows;  // the wanted columns' values, in the order asked for
    std::vector<long> lines;
};

/// The failure of a table's check, as read_numeric_table words it.
[[noreturn]] void table_problem(const std::string& scene, const std::string& key, const std::string& where,
                                const std::string& what)
{
    throw SceneError::with_detail(scene, key, where + ": " + what);
}

/// A column a table reader needs: its name in the header and what it holds (with its unit), for messages.
struct WantedColumn {
    std::string name;
    std::string meaning;
};

/// A table's header line (its fields trimmed): each wanted column found once by name, its place appended to at.
CsvColumns header_of(const std::string& scene, const std::string& key, const std::string& where,
                     const std::vector<std::string>& fields, const std::vector<WantedColumn>& wanted,
                     std::vector<std::size_t>& at)
{
    std::string header;
    for (const std::string& f : fields) header += (header.empty() ? "" : ",") + f;
    CsvColumns columns(where, header);
    for (const WantedColumn& w : wanted) {
        const std::vector<std::string>& names = columns.names();
        const auto count = std::count(names.begin(), names.end(), w.name);
        if (count != 1)  // a second column of the name would be ignored without a word
            table_problem(scene, key, where,
                          (count == 0 ? "expected a column " : "expected one column ") + w.name + " in its header (" +
                              w.meaning + "), got " +
                              (count == 0 ? "none among its " + std::to_string(names.size()) + " columns"
                                          : std::to_string(count)));
        at.push_back(columns.at(w.name));
    }
    return columns;
}

/// A data line's values of the wanted columns (at their places at), each a finite number.
std::vector<double> row_of(const std::string& scene, const std::string& key, const std::string& where,
                           const std::vector<std::string>& fields, const std::vector<WantedColumn>& wanted,
                           const std::vector<std::size_t>& at)
{
    std::vector<double> row;
    for (std::size_t c = 0; c < wanted.size(); ++c) {
        const std::string& f = fields[at[c]];
        double x = 0.0;
        const auto [stop, ec] = std::from_chars(f.data(), f.data() + f.size(), x);
        if (ec != std::errc() || stop != f.data() + f.size() || !std::isfinite(x))
            table_problem(scene, key, where,
                          "expected a finite number in column " + wanted[c].name + " (" + wanted[c].meaning +
                              "), field " + std::to_string(at[c] + 1) + " of the line");
        row.push_back(x);
    }
    return row;
}

/// Reads file (resolved already) as a table with the columns `wanted` (found by name in its header, among others,
/// each once); each value a finite number.
NumericTable read_numeric_table(const std::string& scene, const std::string& key, const std::string& file,
                                std::size_t cap, const char* what_it_is, const std::vector<WantedColumn>& wanted)
{
    const std::string label = printable(file, 400);
    std::string text;
    try {
        text = read_file(file, cap);
    } catch (const SceneError& e) {
        table_problem(scene, key, label, e.detail);
    }
    if (text.size() > cap)
        table_problem(
            scene, key, label,
            "is larger than " + std::string(what_it_is) + " can be (" +
                (cap >= (1u << 20) ? std::to_string(cap >> 20) + " MB)" : std::to_string(cap >> 10) + " KB)"));
    if (text.rfind("\xef\xbb\xbf", 0) == 0) text.erase(0, 3);

    std::optional<CsvColumns> columns;
    std::vector<std::size_t> at;
    NumericTable table;
    long line_no = 0;
    for (std::size_t pos = 0; pos < text.size();) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        const std::string_view line = trimmed(std::string_view(text.data() + pos, end - pos));
        pos = end + 1;
        ++line_no;
        if (line.empty() || line.front() == '#') continue;
        const std::string where = label + ":" + std::to_string(line_no);
        std::vector<std::string> fields = csv_fields(line);
        for (std::string& f : fields) f = std::string(trimmed(f));
        if (!columns) {  // the header: "t, theta" as well as "t,theta"
            columns.emplace(header_of(scene, key, where, fields, wanted, at));
            table.header_columns = columns->size();
            table.header_line = line_no;
            continue;
        }
        if (fields.size() != columns->size())
            table_problem(scene, key, where,
                          "expected " + std::to_string(columns->size()) + " fields as the header has, got " +
                              std::to_string(fields.size()));
        table.rows.push_back(row_of(scene, key, where, fields, wanted, at));
        table.lines.push_back(line_no);
    }
    if (!columns) {
        std::string names;
        for (const WantedColumn& w : wanted) names += (names.empty() ? "" : ", ") + w.name;
        table_problem(scene, key, label, "expected a header line with columns " + names + ", got an empty file");
    }
    return table;
}

/// The most stations a profile table may have: the generator's cost and the variant's name grow with them.
constexpr std::size_t max_profile_stations = 64;
/// The largest profile table read: a blade table of max_profile_stations rows is a few kilobytes.
constexpr std::size_t max_profile_bytes = 1 << 16;

}  // namespace

/// beam.profile's table (docs/model.md section 11.2): stations x/L from 0 to 1, strictly increasing, and positive
/// finite m, EI, ES at each, into the variant's stations (structure) and p.profile (run-time values). Every error
/// names the scene, the key and the table's file and line.
std::string scene_io::read_profile(const std::string& scene_path, const std::string& name, Parameters& p,
                                   Extras& extras)
{
    const std::string file = (std::filesystem::path(scene_path).parent_path() / name).string();
    const std::string label = printable(file, 400);
    const auto bad = [&](long line, const std::string& what) {
        table_problem(scene_path, "beam.profile", label + (line > 0 ? ":" + std::to_string(line) : std::string()),
                      what);
    };
    const std::vector<WantedColumn> want = {{"x/L", "the station along the span, 0 at the root to 1 at the tip"},
                                            {"m", "mass per length, kg/m"},
                                            {"EI", "bending stiffness, N m^2"},
                                            {"ES", "axial stiffness, N"}};
    const NumericTable table =
        read_numeric_table(scene_path, "beam.profile", file, max_profile_bytes, "a profile table", want);
    if (table.header_columns != want.size())
        bad(table.header_line, "expected exactly the columns x/L, m, EI, ES in its header, got " +
                                   std::to_string(table.header_columns) + " columns");
    std::vector<double> x, values;
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        const std::vector<double>& v = table.rows[r];
        const long line = table.lines[r];
        if (x.size() == max_profile_stations)
            bad(line, "more than " + std::to_string(max_profile_stations) + " stations");
        for (std::size_t c = 1; c < want.size(); ++c)
            if (!(v[c] > 0.0)) bad(line, "expected " + want[c].name + " > 0, got " + shortest(v[c]));
        if (x.empty() && v[0] != 0.0) bad(line, "the first station must be x/L = 0, got " + shortest(v[0]));
        if (!x.empty() && !(v[0] > x.back()))
            bad(line,
                "the stations must increase strictly, got x/L = " + shortest(v[0]) + " after " + shortest(x.back()));
        if (v[0] > 1.0) bad(line, "expected x/L <= 1, got " + shortest(v[0]));
        x.push_back(v[0]);
        values.insert(values.end(), {v[1], v[2], v[3]});
    }
    if (x.size() < 2) bad(0, "expected at least 2 stations, got " + std::to_string(x.size()));
    if (x.back() != 1.0) bad(0, "the last station must be x/L = 1, got " + shortest(x.back()));
    if (const std::string why = set_stations(x, extras); !why.empty()) bad(0, why);
    p.profile = std::move(values);
    // The root's values stand for rho S, E I and E S wherever a single value of the beam is reported (the
    // frequency unit sqrt(EI / (m L^4))): S = 1 m^2 keeps the three products the table's.
    p.rho = p.profile[static_cast<std::size_t>(ProfileValue::m)];
    p.S = 1.0;
    p.E = p.profile[static_cast<std::size_t>(ProfileValue::ES)];
    p.I = p.profile[static_cast<std::size_t>(ProfileValue::EI)] / p.E;
    return file;
}

/// WHERE is the CSV file, with its line if one is at fault.
[[noreturn]] void scene_io::table_fail(const std::string& scene, const std::string& where, const std::string& what)
{
    table_problem(scene, "motion.file", where, what);
}

/// The table of motion.file: columns t and `column` (found by name, in any order among others), one row a line,
/// read and checked whole before anything runs. file is already resolved against the scene's folder.
std::shared_ptr<const DriveTable> scene_io::read_drive_table(const std::string& scene, const std::string& file,
                                                             const char* column, const char* meaning,
                                                             DriveTable::Interpolation interpolation)
{
    const std::string label = printable(file, 400);
    const NumericTable table = read_numeric_table(scene, "motion.file", file, max_table_bytes, "a motion table",
                                                  {{"t", "time, s"}, {column, meaning}});
    std::vector<double> t, v;
    const bool angle = std::string_view(column) == "theta";
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        t.push_back(table.rows[r][0]);
        v.push_back(table.rows[r][1]);
        if (angle && std::abs(v[r]) > max_hub_angle)
            table_fail(scene, label + ":" + std::to_string(table.lines[r]), "expected |theta| <= " + angle_bound());
        if (r > 0 && !(t[r] > t[r - 1]))
            table_fail(scene, label + ":" + std::to_string(table.lines[r]),
                       "expected times that increase strictly, got t = " + shortest(t[r]) +
                           " after t = " + shortest(t[r - 1]) + " (line " + std::to_string(table.lines[r - 1]) + ")");
    }
    const std::size_t need = DriveTable::min_rows(interpolation);
    if (t.size() < need)
        table_fail(scene, label,
                   "expected at least " + std::to_string(need) + " rows" +
                       (interpolation == DriveTable::Interpolation::cubic_spline ? " (a cubic spline)" : "") +
                       ", got " + std::to_string(t.size()));
    try {
        return std::make_shared<const DriveTable>(std::move(t), std::move(v), interpolation);
    } catch (const std::invalid_argument& e) {
        table_fail(scene, label, e.what());
    }
}

/// motion.file as a path: relative to the scene file's folder (a scene and its table travel together).
std::string scene_io::table_path(const std::string& scene, const std::string& file)
{
    const std::filesystem::path p(file);
    if (p.is_absolute() || scene.empty()) return file;
    return (std::filesystem::path(scene).parent_path() / p).lexically_normal().string();
}

}  // namespace hubbeam
