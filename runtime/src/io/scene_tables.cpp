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
#include <hubbeam/blade_files.hpp>
#include <hubbeam/csv_columns.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/printable.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/shortest.hpp>
#include <limits>
#include <optional>

#include "io/scene_io.hpp"
#include "profile.hpp"

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

/// A column a table reader needs or takes: its name in the header and what it holds (with its unit), for messages.
struct WantedColumn {
    std::string name;
    std::string meaning;
    bool optional = false;
};

/// A wanted column's place when an optional one is absent: its value reads as NaN.
constexpr std::size_t absent_column = static_cast<std::size_t>(-1);

/// A table's header line (its fields trimmed): each wanted column found once by name (an optional one at most once,
/// absent_column if missing), its place appended to at.
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
        if (count == 0 && w.optional) {
            at.push_back(absent_column);
            continue;
        }
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
        if (at[c] == absent_column) {
            row.push_back(std::numeric_limits<double>::quiet_NaN());
            continue;
        }
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

/// The most stations a profile table may have: a model's construction integrates the table once, in time linear in
/// its stations (under a second at this bound for a blade of Ny = Nz = 16), and no variant depends on them.
constexpr std::size_t max_profile_stations = scene_io::max_profile_stations;

/// p.profile from a table's values (max_profile_value_count per station), and the root's values where a single value
/// of the beam is reported (the frequency unit sqrt(EI / (m L^4))): S = 1 m^2 keeps the three products the table's.
void set_profile(std::vector<double> values, Parameters& p)
{
    p.profile = std::move(values);
    p.rho = p.profile[static_cast<std::size_t>(ProfileValue::m)];
    p.S = 1.0;
    p.E = p.profile[static_cast<std::size_t>(ProfileValue::ES)];
    p.I = p.profile[static_cast<std::size_t>(ProfileValue::EI)] / p.E;
    p.I_flap = p.profile[static_cast<std::size_t>(ProfileValue::EI_flap)] / p.E;
}

/// Why a profile row's values v (in the order of want, x/L first) are out of their ranges, or empty: the twist
/// angles within a turn either way, the torsional values >= 0 (a blade without a twist field may give 0; fit_profile
/// asks for more with one), every other > 0; any finite offset; an absent optional column (NaN) is not checked.
std::string profile_row_problem(const std::vector<WantedColumn>& want, const std::vector<double>& v)
{
    for (std::size_t c = 1; c < want.size(); ++c) {
        const std::string& col = want[c].name;
        if (std::isnan(v[c]) || col == "cg_offset" || col == "tc_offset") continue;
        if (col == "twist" || col == "inertia_twist") {
            if (!(std::abs(v[c]) <= max_section_angle))
                return "expected " + col + " from -2 pi to 2 pi (rad: one turn either way)";
            continue;
        }
        const bool zero_allowed = col == "GJ" || col == "j_c" || col == "j_n";
        if (zero_allowed ? !(v[c] >= 0.0) : !(v[c] > 0.0))
            return "expected " + col + (zero_allowed ? " >= 0" : " > 0") + ", got " + shortest(v[c]);
    }
    return {};
}

}  // namespace

/// beam.profile's table (docs/model.md sections 11.2 and 12.4): stations x/L from 0 to 1, strictly increasing, and
/// positive finite m, EI, ES at each, and a blade's optional columns, into p.stations and p.profile (run-time values, max_profile_value_count per station: absent blade columns at their defaults; fit_profile
/// keeps what the variant reads). Every error names the scene, the key and the table's file and line.
ProfileTable scene_io::read_profile(const std::string& scene_path, const std::string& name, Parameters& p,
                                    Extras& extras)
{
    const std::string file = table_path(scene_path, name);  // as scene_files names it: what writers leave alone
    const std::string label = printable(file, 400);
    const auto bad = [&](long line, const std::string& what) {
        table_problem(scene_path, "beam.profile", label + (line > 0 ? ":" + std::to_string(line) : std::string()),
                      what);
    };
    // In the order of ProfileValue, after x/L.
    const std::vector<WantedColumn> want = {
        {"x/L", "the station along the span, 0 at the root to 1 at the tip"},
        {"m", "mass per length, kg/m"},
        {"EI", "bending stiffness (edgewise out of the plane), N m^2"},
        {"ES", "axial stiffness, N"},
        {"EI_flap", "flapwise bending stiffness, N m^2", true},
        {"GJ", "torsional stiffness, N m^2", true},
        {"twist", "the chord's angle added to beam.pitch, rad", true},
        {"j_c", "mass moment of inertia per length about the chord (or the principal axis nearer it), kg m", true},
        {"j_n", "mass moment of inertia per length about the chord's normal (or the other principal axis), kg m", true},
        {"inertia_twist", "the principal inertia axes' angle added to beam.pitch, rad (default: twist)", true},
        {"cg_offset", "the centre of mass's offset along the chord, towards the trailing edge, m", true},
        {"tc_offset", "the tension centre's offset along the chord, towards the trailing edge, m", true}};
    const NumericTable table =
        read_numeric_table(scene_path, "beam.profile", file, max_profile_bytes, "a profile table", want);
    ProfileTable read{"beam.profile", file, {}};
    if (!table.rows.empty())
        for (std::size_t c = 4; c < want.size(); ++c)
            if (!std::isnan(table.rows.front()[c])) read.blade_columns.push_back(want[c].name);
    if (table.header_columns != 4 + read.blade_columns.size())
        bad(table.header_line,
            "expected the columns x/L, m, EI, ES and, for a blade, any of EI_flap, GJ, twist, j_c, "
            "j_n, inertia_twist, cg_offset, tc_offset in its header, got " +
                std::to_string(table.header_columns - 4 - read.blade_columns.size()) + " other columns");
    std::vector<double> x, values, offsets;
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        const std::vector<double>& v = table.rows[r];
        const long line = table.lines[r];
        if (x.size() == max_profile_stations)
            bad(line, "more than " + std::to_string(max_profile_stations) + " stations");
        if (const std::string why = profile_row_problem(want, v); !why.empty()) bad(line, why);
        if (x.empty() && v[0] != 0.0) bad(line, "the first station must be x/L = 0, got " + shortest(v[0]));
        if (!x.empty() && !(v[0] > x.back()))
            bad(line,
                "the stations must increase strictly, got x/L = " + shortest(v[0]) + " after " + shortest(x.back()));
        if (v[0] > 1.0) bad(line, "expected x/L <= 1, got " + shortest(v[0]));
        x.push_back(v[0]);
        // Absent blade columns: EI_flap = EI, GJ, twist, j_c and j_n 0, the inertia axes along the chord (fit_profile
        // asks for what the variant needs).
        const auto given = [&](std::size_t c, double otherwise) { return std::isnan(v[c]) ? otherwise : v[c]; };
        values.insert(values.end(), {v[1], v[2], v[3], given(4, v[2]), given(5, 0.0), given(6, 0.0), given(7, 0.0),
                                     given(8, 0.0), given(9, given(6, 0.0))});
        offsets.insert(offsets.end(), {given(10, 0.0), given(11, 0.0)});  // in the order of SectionOffset
    }
    if (x.size() < 2) bad(0, "expected at least 2 stations, got " + std::to_string(x.size()));
    if (x.back() != 1.0) bad(0, "the last station must be x/L = 1, got " + shortest(x.back()));
    // Offsets all 0 run the variant without them (docs/model.md section 12.5).
    if (std::any_of(offsets.begin(), offsets.end(), [](double d) { return d != 0.0; })) p.offsets = std::move(offsets);
    extras.offsets = !p.offsets.empty();
    extras.tabulated = true;
    p.stations = std::move(x);
    set_profile(std::move(values), p);
    return read;
}

namespace {

/// Station k's value v of blade file b as a profile holds it (L: the beam's length, for a stand-in ES).
double blade_value(const BladeTable& b, std::size_t k, ProfileValue v, double L)
{
    const auto optional = [&](const std::vector<double>& c) { return c.empty() ? 0.0 : c[k]; };
    switch (v) {
        case ProfileValue::m:
            return b.mass_per_length[k];
        case ProfileValue::EI:
            return b.EI_edge[k];
        case ProfileValue::ES:
            // A stand-in ES where the file has none: 1e4 times the edgewise stiffness over L^2, never read with nx = 0.
            return b.EA.empty() ? 1e4 * b.EI_edge[0] / (L * L) : b.EA[k];
        case ProfileValue::EI_flap:
            return b.EI_flap[k];
        case ProfileValue::GJ:
            return optional(b.GJ);
        case ProfileValue::twist:
            return b.twist[k];
        case ProfileValue::j_c:
            return optional(b.mass_moment_flap);
        case ProfileValue::j_n:
            return optional(b.mass_moment_edge);
        case ProfileValue::inertia_twist:
            return b.inertia_twist.empty() ? b.twist[k] : b.inertia_twist[k];
    }
    return 0.0;
}

/// Blade file b's table as a profile's values, station after station (max_profile_value_count each).
std::vector<double> blade_values(const BladeTable& b, double L)
{
    std::vector<double> values;
    for (std::size_t k = 0; k < b.x_over_L.size(); ++k)
        for (std::size_t j = 0; j < max_profile_value_count; ++j)
            values.push_back(blade_value(b, k, static_cast<ProfileValue>(j), L));
    return values;
}

/// count equally spaced stations from 0 to 1.
std::vector<double> equally_spaced(int count)
{
    std::vector<double> x;
    for (int k = 0; k < count; ++k) x.push_back(k + 1 == count ? 1.0 : static_cast<double>(k) / (count - 1));
    return x;
}

/// The table (stations x, values as blade_values) linear between its stations, taken at count equally spaced ones,
/// which replace x and values.
void resample_table(std::vector<double>& x, std::vector<double>& values, int count)
{
    const std::vector<double> from = x;
    x = equally_spaced(count);
    std::vector<double> resampled;
    for (double xk : x)
        for (std::size_t j = 0; j < max_profile_value_count; ++j)
            resampled.push_back(linear_between(from, values, j, xk));
    values = std::move(resampled);
}

/// Whether a column of offsets is absent or all 0.
bool all_zero(const std::vector<double>& column)
{
    return std::all_of(column.begin(), column.end(), [](double v) { return v == 0.0; });
}

/// Blade file b's section offsets at its stations (section_offset_count each, in the order of SectionOffset), empty
/// where the file has none or all are 0 (the variant without offsets then runs, as before them); taken at the stations
/// `to` where they differ.
std::vector<double> blade_offsets(const BladeTable& b, const std::vector<double>& to)
{
    if (all_zero(b.cg_offset) && all_zero(b.tc_offset)) return {};
    const auto at = [&](const std::vector<double>& column, double xk) {
        return column.empty() ? 0.0 : linear_between(b.x_over_L, column, 0, xk);
    };
    std::vector<double> offsets;
    for (double xk : to) offsets.insert(offsets.end(), {at(b.cg_offset, xk), at(b.tc_offset, xk)});
    return offsets;
}

}  // namespace

/// beam.blade_file (docs/scene.md): a BModes section-properties file or an ElastoDyn blade file (read_blade_file) as
/// a blade's profile, each of its columns where the profile has one; a file without EA gives a stand-in ES (fit_profile
/// asks for nx = 0). resample > 0: the table linear between its stations, taken at resample equally spaced ones (a
/// coarser table, a user's choice).
ProfileTable scene_io::read_blade(const std::string& scene_path, const std::string& name, int resample,
                                  const BladeScale& scale, Parameters& p, Extras& extras)
{
    const std::string file = table_path(scene_path, name);  // as scene_files names it: what writers leave alone
    const auto bad = [&](const std::string& what) {
        table_problem(scene_path, "beam.blade_file", printable(file, 400), what);
    };
    if (const std::string kind = not_a_regular_file(file); !kind.empty())
        bad("cannot open: it is " + kind + ", not a regular file");
    BladeTable b;
    try {
        b = read_blade_file(file);
    } catch (const BladeFileError& e) {
        throw SceneError::with_detail(scene_path, "beam.blade_file", e.what());
    }
    scale_columns(b, scale);  // [blade_scale], before any check of the values: the scene runs the scaled blade
    ProfileTable read{"beam.blade_file", file, {"EI_flap", "twist"}, !b.EA.empty(), resample};
    if (!b.GJ.empty()) read.blade_columns.push_back("GJ");
    if (!b.mass_moment_flap.empty()) read.blade_columns.insert(read.blade_columns.end(), {"j_c", "j_n"});
    const std::vector<double> offsets = blade_offsets(b, resample > 0 ? equally_spaced(resample) : b.x_over_L);
    if (!all_zero(b.cg_offset)) read.blade_columns.push_back("cg_offset");
    if (!all_zero(b.tc_offset)) read.blade_columns.push_back("tc_offset");
    const std::size_t n = b.x_over_L.size();
    if (n < 2 || b.x_over_L.front() != 0.0 || b.x_over_L.back() != 1.0)
        bad("expected stations from x/L = 0 at the root to 1 at the tip, got " + std::to_string(n) + " from " +
            shortest(b.x_over_L.front()) + " to " + shortest(b.x_over_L.back()));
    std::vector<double> values = blade_values(b, p.L);
    std::vector<double> x = b.x_over_L;
    if (resample > 0) resample_table(x, values, resample);  // the file's table linear between its stations
    if (x.size() > max_profile_stations)
        bad("at most " + std::to_string(max_profile_stations) + " stations, got " + std::to_string(x.size()) +
            ": set beam.blade_stations to resample it");
    for (std::size_t k = 1; k < x.size(); ++k)
        if (!(x[k] > x[k - 1]))
            bad("the stations must increase strictly, got x/L = " + shortest(x[k]) + " after " + shortest(x[k - 1]));
    extras.tabulated = true;
    extras.offsets = !offsets.empty();
    p.stations = std::move(x);
    p.offsets = offsets;
    set_profile(std::move(values), p);
    return read;
}

/// A profile's values as the scene's variant reads them (docs/model.md section 12.4): a planar beam's m, EI, ES per
/// station (a blade column is refused: it would be ignored), a blade's all of them, with GJ, j_c and j_n given and
/// GJ > 0, j_c + j_n > 0 at every station where it has a twist field.
void scene_io::fit_profile(const std::string& scene_path, const ProfileTable& table, const VariantKey& key,
                           Parameters& p)
{
    const auto bad = [&](const std::string& what) {
        table_problem(scene_path, table.key, printable(table.file, 400), what);
    };
    const std::size_t n = max_profile_value_count, stations = p.profile.size() / n;
    if (!table.axial && key.nx > 0)
        bad("an axial stiffness (EA) for discretization.nx > 0: the file gives none; set nx = 0");
    // With nx = 0 the axis cannot stretch and the tension centre's offset would leave the bending stiffness about the
    // reference axis, not about the tension centre (docs/model.md 12.6): refused rather than silently stiffer.
    bool tension = false;
    for (std::size_t k = static_cast<std::size_t>(SectionOffset::tension); k < p.offsets.size(); k += section_offset_count)
        tension = tension || p.offsets[k] != 0.0;
    if (key.nx == 0 && tension)
        bad("column tc_offset (the tension centre's offset) is not 0: expected discretization.nx > 0, an axial field "
            "that stretches (with nx = 0 the offset would be ignored and the blade bend too stiffly)");
    if (!key.out_of_plane()) {
        if (!table.blade_columns.empty())
            bad("column " + table.blade_columns.front() +
                " describes a blade that leaves the plane: expected discretization.nz or nt > 0, a beam.pitch or a "
                "beam.precone with it (or no such column)");
        std::vector<double> planar;
        for (std::size_t k = 0; k < stations; ++k)
            planar.insert(planar.end(), p.profile.begin() + static_cast<std::ptrdiff_t>(n * k),
                          p.profile.begin() + static_cast<std::ptrdiff_t>(n * k + profile_value_count(false)));
        p.profile = std::move(planar);
        return;
    }
    if (key.nt == 0) return;
    for (const char* column : {"GJ", "j_c", "j_n"})
        if (std::find(table.blade_columns.begin(), table.blade_columns.end(), column) == table.blade_columns.end())
            bad(std::string("expected a column ") + column + " with discretization.nt > 0 (the twist field's " +
                (column[0] == 'G' ? "stiffness)" : "inertia)"));
    for (std::size_t k = 0; k < stations; ++k) {
        const auto at = [&](ProfileValue v) { return p.profile[n * k + static_cast<std::size_t>(v)]; };
        if (!(at(ProfileValue::GJ) > 0.0))
            bad("expected GJ > 0 at every station with discretization.nt > 0, got 0 at station " +
                std::to_string(k + 1));
        if (!(at(ProfileValue::j_c) + at(ProfileValue::j_n) > 0.0))
            bad("expected j_c + j_n > 0 at every station with discretization.nt > 0, got 0 at station " +
                std::to_string(k + 1));
    }
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
