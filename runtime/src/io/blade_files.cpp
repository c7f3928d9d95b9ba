// Blade-property files (blade_files.hpp): a BModes section-properties file and the distributed blade properties of an
// ElastoDyn blade file, read whole, checked, and refused in one line where hubbeam does not model what they hold.
//
// The formats as their own programs read them, checked against these public files:
//   BModes   old-NWTC/BModes src/bmodes/BModes.f90 (reading the section properties: ReadCom for the title, ReadVar for
//            n_secs, ReadCom for the blank, titles and units lines, then n_secs list-directed rows of 13 values;
//            flp_iner, edge_iner about the inertia axes at tw_iner; n_secs >= 2); the samples old-NWTC/BModes
//            CertTest/blade_sec_props.dat and CertTest/tower_sec_props.dat;
//            SMI-Lab-Inha/pyBModes src/pybmodes/io/sec_props.py (which calls the first column span_loc).
//   ElastoDyn OpenFAST/openfast modules/elastodyn/src/ElastoDyn_IO.f90 (ReadBladeFile: the table's columns found by
//            name, case-insensitively; StrcTwst in degrees; BMassDen, FlpStff, EdgStff times AdjBlMs, AdjFlSt, AdjEdSt;
//            ValidateBladeData) and modules/nwtc-library/src/NWTC_IO.f90 (comments from !, # or %, blank lines
//            skipped); docs/source/user/api_change.rst (FAST v7's 17 columns; PitchAxis dropped in OpenFAST v5, by
//            commit b98ecb0f0 "Remove unused blade PitchAxis input"); the blade files OpenFAST/r-test
//            glue-codes/openfast/5MW_Baseline/NRELOffshrBsline5MW_Blade.dat (5 columns), old-NWTC/FAST
//            CertTest/5MW_Baseline/NRELOffshrBsline5MW_Blade.dat (6, with PitchAxis) and sandialabs/NuMAD
//            examples/referenceModels/SNL61p5m/SNL61p5m_NuMAD_121212/FASTBlade_precomp.dat (FAST v7's 17).
//
// Where the formats leave room, decided so:
// - BModes reads its columns by position and never reads their titles. The titles line must name the 13 columns in
//   BModes' order all the same (sec_loc or span_loc first, any case): a table in another order would otherwise be read
//   wrong without a word. Line 3 is skipped whatever it holds, as BModes skips it; blank lines among the rows are
//   skipped and each row is one line; what follows the n_secs rows is ignored (BModes' samples end with notes), but
//   for one more row, which means n_secs is wrong.
// - BModes gives flp_iner and edge_iner about the principal inertia axes (at tw_iner); they are kept so, with the
//   axes' angle (BladeTable::inertia_twist), and the energies turn the inertia by that angle, the stiffnesses by
//   str_tw. BModes turns them to the structural axes instead, dropping the product of inertia, and refuses a turn
//   beyond 45 degrees; hubbeam needs neither (docs/model.md 12.4).
// - ElastoDyn's table is read by its column names, so FAST v7's 17 columns, FAST v8 to OpenFAST v4's 6 and OpenFAST
//   v5's 5 read alike; a name hubbeam does not know is refused rather than its column dropped. NBlInpSt and the
//   adjustment factors are found by name between BLADE PARAMETERS and DISTRIBUTED BLADE PROPERTIES (FAST v7 has one
//   more header line, and CalcBMode); the damping, FlStTunr (tuners of ElastoDyn's own mode shapes) and the mode
//   shapes are not read. The units line is not read either: ElastoDyn takes StrcTwst in degrees whatever it says.
// - PitchAxis (FAST v7: AeroCent) places the chord, so the aerodynamic centre, about the pitch axis; ElastoDyn derives
//   no structural property from it (its stiffnesses and masses are about the reference axis already), and neither
//   does hubbeam: it is read as a number and not used, constant or not (the NREL 5 MW blade's moves from 25 % to
//   37.5 % of the chord).
// - Values: stations from 0 to 1, strictly increasing (hubbeam's profile table's rule, and ElastoDyn's); mass and
//   stiffnesses finite and > 0 (after the adjustment factors, themselves > 0); mass moments of inertia >= 0 (files
//   give 0 where rotary inertia is neglected); twist from -360 to 360 deg (ElastoDyn asks for -180 to 180 deg, which
//   hubbeam needs not; one turn is max_section_angle, and a larger value names no other section); BModes' cg_offst
//   and tc_offst finite (docs/model.md sections 12.5 and 12.6, positive towards the trailing edge), its sc_offst
//   finite and not used (12.6), ElastoDyn's offsets, pre-curve, pre-sweep and Alpha exactly 0; at least two stations (ElastoDyn takes one, a uniform blade,
//   which stations at 0 and 1 cannot be). Numbers as Fortran writes them: 1.5D+03, +2., .5.
// - Both formats' twist keeps its sign (pyBModes copies ElastoDyn's StrcTwst into BModes' str_tw unchanged).
#include <hubbeam/blade_files.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string_view>
#include <utility>

#include <hubbeam/printable.hpp>

namespace hubbeam {

BladeFileError::BladeFileError(std::string file_, long line_, std::string column_, long station_, std::string expected_)
    : std::runtime_error(file_ + (line_ > 0 ? ":" + std::to_string(line_) : std::string()) + ": " +
                         (column_.empty()
                              ? std::string()
                              : "column " + column_ +
                                    (station_ > 0 ? ", station " + std::to_string(station_) : std::string()) + ": ") +
                         "expected " + expected_),
      file(std::move(file_)),
      line(line_),
      column(std::move(column_)),
      station(station_),
      expected(std::move(expected_))
{
}

namespace {

constexpr double degree = std::numbers::pi / 180.0;

/// A blade file read whole, and its name as messages give it. Never moved once read: its lines are views into text.
struct BladeText {
    std::string label;
    std::string text;
};

/// Refuses t's file: throws its BladeFileError at line (0: the whole file), column and station (0: none).
[[noreturn]] void fail(const BladeText& t, long line, const std::string& column, long station,
                       const std::string& expected)
{
    throw BladeFileError(t.label, line, column, station, expected);
}

/// Reads path into t (a regular file of at most max_blade_file_bytes; a spreadsheet's byte-order mark dropped).
void read_text(const std::string& path, BladeText& t)
{
    t.label = printable(path, 400);
    std::error_code ec;
    const std::filesystem::file_type type = std::filesystem::status(path, ec).type();
    if (type == std::filesystem::file_type::not_found) fail(t, 0, "", 0, "an existing file");
    if (ec) fail(t, 0, "", 0, "a file it may reach (" + ec.message() + ")");
    // Checked before opening: open() on a FIFO waits for a writer, and a device or a folder is no blade file.
    if (type != std::filesystem::file_type::regular) fail(t, 0, "", 0, "a regular file (not a folder, FIFO or device)");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(t, 0, "", 0, std::string("a file it may open (") + std::strerror(errno) + ")");
    std::array<char, 1 << 14> chunk;
    while (t.text.size() <= max_blade_file_bytes) {  // at most one byte past the cap: /dev/zero never ends
        const std::size_t want = std::min(chunk.size(), max_blade_file_bytes + 1 - t.text.size());
        in.read(chunk.data(), static_cast<std::streamsize>(want));
        t.text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
        if (static_cast<std::size_t>(in.gcount()) < want) break;
    }
    if (in.bad()) fail(t, 0, "", 0, std::string("a file it may read (") + std::strerror(errno) + ")");
    if (t.text.size() > max_blade_file_bytes)
        fail(t, 0, "", 0, "a file of at most " + std::to_string(max_blade_file_bytes >> 20) + " MiB");
    if (t.text.starts_with("\xef\xbb\xbf")) t.text.erase(0, 3);
}

/// s without the blanks (and a Windows line end) around it.
std::string_view trimmed(std::string_view s)
{
    const std::size_t first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

/// One line of a blade file: its 1-based number and its text without the line end and the blanks around it.
struct Line {
    long number = 0;
    std::string_view text;
};

/// Walks a blade file's lines in order, numbering them and refusing one longer than max_blade_line_bytes.
class LineCursor {
public:
    explicit LineCursor(const BladeText& t) : t_(t) {}

    /// The next line, blank or not; false at the end of the file.
    bool next(Line& line)
    {
        if (pos_ >= t_.text.size()) return false;
        std::size_t end = t_.text.find('\n', pos_);
        if (end == std::string::npos) end = t_.text.size();
        ++number_;
        if (end - pos_ > max_blade_line_bytes)
            fail(t_, number_, "", 0, "a line of at most " + std::to_string(max_blade_line_bytes) + " bytes");
        line = {number_, trimmed(std::string_view(t_.text).substr(pos_, end - pos_))};
        pos_ = end + 1;
        return true;
    }

    /// The next line that is not blank.
    bool next_nonblank(Line& line)
    {
        while (next(line))
            if (!line.text.empty()) return true;
        return false;
    }

    /// The next line that holds anything before a comment (from !, # or %, cut off), as ElastoDyn reads its files.
    bool next_significant(Line& line)
    {
        while (next(line)) {
            if (const std::size_t cut = line.text.find_first_of("!#%"); cut != std::string_view::npos)
                line.text = trimmed(line.text.substr(0, cut));
            if (!line.text.empty()) return true;
        }
        return false;
    }

private:
    const BladeText& t_;
    std::size_t pos_ = 0;
    long number_ = 0;
};

/// A line's fields, separated by blanks, tabs or commas (as Fortran's list-directed reads separate them).
std::vector<std::string_view> fields(std::string_view s)
{
    std::vector<std::string_view> out;
    std::size_t pos = 0;
    while ((pos = s.find_first_not_of(" \t,", pos)) != std::string_view::npos) {
        const std::size_t end = std::min(s.find_first_of(" \t,", pos), s.size());
        out.push_back(s.substr(pos, end - pos));
        pos = end;
    }
    return out;
}


/// A field as a whole number >= 0 (a count of stations); false when it is none.
bool count(std::string_view field, long& n)
{
    const auto [stop, ec] = std::from_chars(field.data(), field.data() + field.size(), n);
    return ec == std::errc() && stop == field.data() + field.size() && n >= 0;
}

/// Whether a and b are the same name in any case.
bool same_name(std::string_view a, std::string_view b)
{
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::toupper(static_cast<unsigned char>(x)) == std::toupper(static_cast<unsigned char>(y));
           });
}

/// Whether line holds words (a section's title, "BLADE PARAMETERS") in any case.
bool has_words(std::string_view line, std::string_view words)
{
    const auto found = std::search(line.begin(), line.end(), words.begin(), words.end(), [](char x, char y) {
        return std::toupper(static_cast<unsigned char>(x)) == std::toupper(static_cast<unsigned char>(y));
    });
    return found != line.end();
}

/// What a column's values must be: a station, an angle of at most one turn either way (twist, degrees), > 0 (mass,
/// stiffness), >= 0 (mass moments of inertia), 0 (what hubbeam does not model), or any number (what no structural
/// property depends on: a pitch axis).
enum class Rule { station, angle, positive, non_negative, zero, unused, length };

/// A column of a format's table: its name there, what it holds (with its unit, for messages), its rule and, for
/// zero, why hubbeam refuses another value.
struct Column {
    const char* name;
    const char* meaning;
    Rule rule;
    const char* why = "";
};

constexpr const char* no_cg_offset =
    "hubbeam reads the centre of mass's offset along the chord from a BModes file's cg_offst only";
constexpr const char* straight_axis = "hubbeam's blade has a straight reference axis";

/// BModes' 13 columns, in the order BModes reads them (BModes.f90).
constexpr std::array<Column, 13> bmodes_columns = {{
    {"sec_loc", "station, 0 at the root to 1 at the tip", Rule::station},
    {"str_tw", "structural twist, deg", Rule::angle},
    {"tw_iner", "twist of the inertia axes, deg", Rule::angle},
    {"mass_den", "mass per length, kg/m", Rule::positive},
    {"flp_iner", "flap mass moment of inertia per length, kg m", Rule::non_negative},
    {"edge_iner", "edge mass moment of inertia per length, kg m", Rule::non_negative},
    {"flp_stff", "flap bending stiffness, N m^2", Rule::positive},
    {"edge_stff", "edge bending stiffness, N m^2", Rule::positive},
    {"tor_stff", "torsional stiffness, N m^2", Rule::positive},
    {"axial_stff", "axial stiffness, N", Rule::positive},
    {"cg_offst", "centre-of-mass offset, m", Rule::length},
    // The shear centre's offset enters Euler-Bernoulli bending with St Venant torsion only at the warping's order
    // (docs/model.md 12.6): read, checked finite, not used.
    {"sc_offst", "shear-centre offset, m", Rule::unused},
    {"tc_offst", "tension-centre offset, m", Rule::length},
}};

/// The columns an ElastoDyn blade table may have (ElastoDyn_IO.f90; FAST v7's in api_change.rst); the first five
/// are required.
constexpr std::array<Column, 18> elastodyn_columns = {{
    {"BlFract", "station, 0 at the root to 1 at the tip", Rule::station},
    {"StrcTwst", "structural twist, deg", Rule::angle},
    {"BMassDen", "mass per length times AdjBlMs, kg/m", Rule::positive},
    {"FlpStff", "flap bending stiffness times AdjFlSt, N m^2", Rule::positive},
    {"EdgStff", "edge bending stiffness times AdjEdSt, N m^2", Rule::positive},
    {"PitchAxis", "pitch axis, fraction of the chord from the leading edge", Rule::unused},
    {"AeroCent", "aerodynamic centre about the pitch axis, fraction of the chord", Rule::unused},
    {"GJStff", "torsional stiffness, N m^2", Rule::positive},
    {"EAStff", "axial stiffness, N", Rule::positive},
    {"Alpha", "flap-twist coupling coefficient", Rule::zero, "hubbeam models no coupling of bending and twist"},
    {"FlpIner", "flap mass moment of inertia per length, kg m", Rule::non_negative},
    {"EdgIner", "edge mass moment of inertia per length, kg m", Rule::non_negative},
    {"PrecrvRef", "pre-curve of the reference axis, m", Rule::zero, straight_axis},
    {"PreswpRef", "pre-sweep of the reference axis, m", Rule::zero, straight_axis},
    {"FlpcgOf", "flapwise centre-of-mass offset, m", Rule::zero, no_cg_offset},
    {"EdgcgOf", "edgewise centre-of-mass offset, m", Rule::zero, no_cg_offset},
    {"FlpEAOf", "flapwise elastic-axis offset, m", Rule::zero,
     "hubbeam models no offset of the elastic (tension) axis from the reference axis"},
    {"EdgEAOf", "edgewise elastic-axis offset, m", Rule::zero,
     "hubbeam models no offset of the elastic (tension) axis from the reference axis"},
}};
constexpr std::size_t elastodyn_required = 5;

/// A table's values by column (in the order of the columns read) and each row's line.
struct Rows {
    std::vector<std::vector<double>> by_column;
    std::vector<long> lines;
};

/// Whether a line is a row of `columns` numbers (to tell one row too many from the text after a table).
bool is_row(std::string_view text, std::size_t columns)
{
    const std::vector<std::string_view> f = fields(text);
    double x = 0.0;
    return f.size() == columns && std::all_of(f.begin(), f.end(), [&](std::string_view s) { return fortran_number(s, x); });
}

/// Reads the n rows of a table with `columns` from the lines next gives, each row one line of finite numbers, and
/// checks that the line after them is no further row (n, the file's count_name, would be wrong).
template <class Next>
Rows read_rows(const BladeText& t, Next&& next, const std::vector<const Column*>& columns, long n,
               const char* count_name)
{
    Rows rows;
    rows.by_column.resize(columns.size());
    const std::string rows_wanted = std::string(count_name) + " = " + std::to_string(n) + " rows in the table";
    Line line;
    for (long r = 0; r < n; ++r) {
        if (!next(line)) fail(t, 0, "", 0, rows_wanted + ", the file ends after " + std::to_string(r));
        const std::vector<std::string_view> f = fields(line.text);
        double x = 0.0;
        if (f.empty() || !fortran_number(f[0], x))
            fail(t, line.number, "", 0, rows_wanted + ", found " + std::to_string(r) + " before this line");
        if (f.size() != columns.size())
            fail(t, line.number, "", 0,
                 std::to_string(columns.size()) + " numbers on a row, one per column, got " + std::to_string(f.size()));
        for (std::size_t c = 0; c < columns.size(); ++c) {
            if (!fortran_number(f[c], x))
                fail(t, line.number, columns[c]->name, r + 1,
                     std::string("a finite number (") + columns[c]->meaning + ")");
            rows.by_column[c].push_back(x);
        }
        rows.lines.push_back(line.number);
    }
    if (next(line) && is_row(line.text, columns.size()))
        fail(t, line.number, "", 0, rows_wanted + " as the file says, not one more");
    return rows;
}

/// Checks station s (0-based) of a column against its rule; v holds the column's values up to s at least.
void check_value(const BladeText& t, const Column& col, const std::vector<double>& v, std::size_t s, long line)
{
    const double x = v[s];
    const auto bad = [&](const std::string& what) { fail(t, line, col.name, static_cast<long>(s) + 1, what); };
    switch (col.rule) {
        case Rule::station:
            if (s == 0 && x != 0.0) bad("0 at the first station (the root)");
            if (s > 0 && !(x > v[s - 1])) bad("a value above the previous station's (stations increase strictly)");
            if (x > 1.0) bad("a value <= 1 (1 is the tip)");
            break;
        case Rule::positive:
            if (!(x > 0.0) || !std::isfinite(x)) bad(std::string("a finite value > 0 (") + col.meaning + ")");
            break;
        case Rule::non_negative:
            if (!(x >= 0.0)) bad(std::string("a value >= 0 (") + col.meaning + ")");
            break;
        case Rule::zero:
            if (x != 0.0) bad(std::string("0 (") + col.meaning + "): " + col.why);
            break;
        case Rule::unused:
            break;
        case Rule::length:  // any number: fortran_number has refused the non-finite
            break;
        case Rule::angle:
            // One turn either way (max_section_angle), in the file's degrees.
            if (!(std::abs(x) <= 360.0)) bad(std::string("a value from -360 to 360 (") + col.meaning + ", one turn)");
            break;
    }
}

/// Checks a table's values against their columns' rules, in the file's order, and that the stations end at 1.
void validate(const BladeText& t, const std::vector<const Column*>& columns, const Rows& rows)
{
    const std::size_t n = rows.lines.size();
    for (std::size_t s = 0; s < n; ++s)
        for (std::size_t c = 0; c < columns.size(); ++c)
            check_value(t, *columns[c], rows.by_column[c], s, rows.lines[s]);
    for (std::size_t c = 0; c < columns.size(); ++c)
        if (columns[c]->rule == Rule::station && rows.by_column[c].back() != 1.0)
            fail(t, rows.lines.back(), columns[c]->name, static_cast<long>(n), "1 at the last station (the tip)");
}

/// Skips the units line under a table's column names; a line of numbers there means it is missing.
template <class Next>
void skip_units(const BladeText& t, Next&& next, const char* example)
{
    Line line;
    const std::string wanted = std::string("a units line such as ") + example + " under the column names";
    if (!next(line)) fail(t, 0, "", 0, wanted + ", then the table's rows");
    double x = 0.0;
    const std::vector<std::string_view> f = fields(line.text);
    if (!f.empty() && fortran_number(f[0], x)) fail(t, line.number, "", 0, wanted + ", before the first row");
}

/// The names of BModes' columns, for messages.
std::string bmodes_titles()
{
    std::string names;
    for (const Column& c : bmodes_columns) {
        if (!names.empty()) names += ' ';
        names += c.name;
    }
    return names;
}

/// Whether a line is BModes' column titles (it names str_tw and mass_den): how read_blade_file knows the format.
bool is_bmodes_titles(std::string_view text)
{
    const std::vector<std::string_view> f = fields(text);
    const auto has = [&](std::string_view name) {
        return std::any_of(f.begin(), f.end(), [&](std::string_view s) { return same_name(s, name); });
    };
    return has("str_tw") && has("mass_den");
}

/// Checks BModes' column titles, the next line that is not blank: the 13 names in BModes' order.
void check_bmodes_titles(const BladeText& t, LineCursor& lines)
{
    Line line;
    if (!lines.next_nonblank(line)) fail(t, 0, "", 0, "the column titles " + bmodes_titles() + " after line 3");
    const std::vector<std::string_view> f = fields(line.text);
    if (f.size() != bmodes_columns.size())
        fail(t, line.number, "", 0,
             "the 13 column titles " + bmodes_titles() + " (BModes skips line 3, then reads them), got " +
                 std::to_string(f.size()) + " fields");
    for (std::size_t c = 0; c < f.size(); ++c)
        if (!same_name(f[c], bmodes_columns[c].name) && !(c == 0 && same_name(f[c], "span_loc")))
            fail(t, line.number, bmodes_columns[c].name, 0,
                 "the title " + std::string(bmodes_columns[c].name) + " in field " + std::to_string(c + 1) +
                     " (BModes skips line 3, then reads its columns by position, in the order " + bmodes_titles() +
                     ")");
}

/// BModes' table into a BladeTable: twist in radians, the mass moments of inertia about their own axes at tw_iner.
BladeTable bmodes_table(const Rows& rows)
{
    const std::vector<std::vector<double>>& v = rows.by_column;
    BladeTable b;
    b.source = bmodes_source;
    b.x_over_L = v[0];
    b.mass_per_length = v[3];
    b.EI_flap = v[6];
    b.EI_edge = v[7];
    b.GJ = v[8];
    b.EA = v[9];
    b.cg_offset = v[10];
    b.tc_offset = v[12];  // from the reference axis, as the energies take it, not BModes' tc_offst - sc_offst (12.6)
    // flp_iner and edge_iner are about the principal inertia axes, at tw_iner: kept so, with their angle.
    b.mass_moment_flap = v[4];
    b.mass_moment_edge = v[5];
    for (std::size_t s = 0; s < rows.lines.size(); ++s) {
        b.twist.push_back(v[1][s] * degree);
        b.inertia_twist.push_back(v[2][s] * degree);
    }
    return b;
}

/// A BModes section-properties file read from t (format and decisions at the top of this file).
BladeTable parse_bmodes(const BladeText& t)
{
    LineCursor lines(t);
    Line line;
    lines.next(line);  // line 1: the title
    long n = 0;
    if (!lines.next(line) || fields(line.text).empty() || !count(fields(line.text)[0], n))
        fail(t, 2, "", 0, "n_secs, the number of stations, as the first field of line 2 (after the title)");
    if (n < 2) fail(t, 2, "", 0, "n_secs >= 2 (a station at the root and one at the tip)");
    lines.next(line);  // line 3: read and ignored by BModes (blank by convention)
    check_bmodes_titles(t, lines);
    const auto next = [&](Line& l) { return lines.next_nonblank(l); };
    skip_units(t, next, "(-) (deg) (deg) (kg/m) (kg-m) (kg-m) (Nm^2) (Nm^2) (Nm^2) (N) (m) (m) (m)");
    std::vector<const Column*> columns;
    for (const Column& c : bmodes_columns) columns.push_back(&c);
    const Rows rows = read_rows(t, next, columns, n, "n_secs");
    validate(t, columns, rows);
    return bmodes_table(rows);
}

/// What an ElastoDyn blade file's parameters give the table: its row count and adjustment factors.
struct ElastoDynParameters {
    long stations = 0;
    double adj_mass = 1.0, adj_flap = 1.0, adj_edge = 1.0;
};

/// Reads the parameters (VALUE NAME - description lines) up to the DISTRIBUTED BLADE PROPERTIES line: NBlInpSt,
/// AdjBlMs, AdjFlSt and AdjEdSt by name, each once.
template <class Next>
ElastoDynParameters elastodyn_parameters(const BladeText& t, Next&& next)
{
    struct Wanted {
        const char* name;
        const char* meaning;
        long line = 0;
        std::string_view value;
    };
    std::array<Wanted, 4> wanted = {{{"NBlInpSt", "the number of blade input stations", 0, {}},
                                     {"AdjBlMs", "the factor ElastoDyn applies to BMassDen", 0, {}},
                                     {"AdjFlSt", "the factor ElastoDyn applies to FlpStff", 0, {}},
                                     {"AdjEdSt", "the factor ElastoDyn applies to EdgStff", 0, {}}}};
    Line line;
    bool table = false;
    while (!table && next(line)) {
        table = has_words(line.text, "DISTRIBUTED BLADE PROPERTIES");
        const std::vector<std::string_view> f = fields(line.text);
        for (Wanted& w : wanted)
            if (f.size() >= 2 && same_name(f[1], w.name)) {
                if (w.line != 0) fail(t, line.number, "", 0, std::string("one line with ") + w.name + ", not a second");
                w.line = line.number;
                w.value = f[0];
            }
    }
    if (!table) fail(t, 0, "", 0, "a section line DISTRIBUTED BLADE PROPERTIES after BLADE PARAMETERS");
    ElastoDynParameters p;
    double* factors[] = {nullptr, &p.adj_mass, &p.adj_flap, &p.adj_edge};
    for (std::size_t k = 0; k < wanted.size(); ++k) {
        const Wanted& w = wanted[k];
        const std::string what = std::string(w.name) + " (" + w.meaning + ")";
        if (w.line == 0)
            fail(t, 0, "", 0, "a line with " + what + " between BLADE PARAMETERS and DISTRIBUTED BLADE PROPERTIES");
        if (k == 0 && !count(w.value, p.stations)) fail(t, w.line, "", 0, "a whole number before " + what);
        if (k == 0 && p.stations < 2)
            fail(t, w.line, "", 0, "NBlInpSt >= 2 (a station at the root and one at the tip)");
        if (k > 0 && (!fortran_number(w.value, *factors[k]) || !(*factors[k] > 0.0)))
            fail(t, w.line, "", 0, "a number > 0 before " + what);
    }
    return p;
}

/// The columns an ElastoDyn table's names line names, each known and once, the required ones among them.
std::vector<const Column*> elastodyn_header(const BladeText& t, const Line& line)
{
    std::vector<const Column*> columns;
    const std::vector<std::string_view> f = fields(line.text);
    for (std::size_t k = 0; k < f.size(); ++k) {
        const auto known = std::find_if(elastodyn_columns.begin(), elastodyn_columns.end(),
                                        [&](const Column& c) { return same_name(f[k], c.name); });
        if (known == elastodyn_columns.end()) {
            std::string names;
            for (const Column& c : elastodyn_columns) {
                if (!names.empty()) names += ", ";
                names += c.name;
            }
            fail(t, line.number, "", 0,
                 "in field " + std::to_string(k + 1) + " of the column names one of " + names +
                     " (a column hubbeam does not know is refused rather than dropped)");
        }
        if (std::find(columns.begin(), columns.end(), &*known) != columns.end())
            fail(t, line.number, known->name, 0, "the column once among the column names");
        columns.push_back(&*known);
    }
    for (std::size_t r = 0; r < elastodyn_required; ++r)
        if (std::find(columns.begin(), columns.end(), &elastodyn_columns[r]) == columns.end())
            fail(t, line.number, elastodyn_columns[r].name, 0,
                 std::string("the column among the column names (") + elastodyn_columns[r].meaning + ")");
    return columns;
}

/// The values of the column name in rows, or nullptr when the table has no such column.
std::vector<double>* column_of(Rows& rows, const std::vector<const Column*>& columns, std::string_view name)
{
    for (std::size_t c = 0; c < columns.size(); ++c)
        if (name == columns[c]->name) return &rows.by_column[c];
    return nullptr;
}

/// ElastoDyn's table into a BladeTable (its adjustment factors applied already): twist in radians.
BladeTable elastodyn_table(Rows& rows, const std::vector<const Column*>& columns)
{
    const auto column = [&](std::string_view name) { return column_of(rows, columns, name); };
    BladeTable b;
    b.source = elastodyn_source;
    b.x_over_L = *column("BlFract");
    for (const double deg : *column("StrcTwst")) b.twist.push_back(deg * degree);
    b.mass_per_length = *column("BMassDen");
    b.EI_flap = *column("FlpStff");
    b.EI_edge = *column("EdgStff");
    const auto optional = [&](std::string_view name, std::vector<double>& to) {
        if (const std::vector<double>* v = column(name)) to = *v;
    };
    optional("GJStff", b.GJ);
    optional("EAStff", b.EA);
    optional("FlpIner", b.mass_moment_flap);
    optional("EdgIner", b.mass_moment_edge);
    return b;
}

/// An ElastoDyn blade file's distributed properties read from t (format and decisions at the top of this file).
BladeTable parse_elastodyn(const BladeText& t)
{
    LineCursor lines(t);
    const auto next = [&](Line& l) { return lines.next_significant(l); };
    Line line;
    bool parameters = false;
    while (!parameters && next(line)) parameters = has_words(line.text, "BLADE PARAMETERS");
    if (!parameters) fail(t, 0, "", 0, "a section line BLADE PARAMETERS, with which an ElastoDyn blade file begins");
    const ElastoDynParameters p = elastodyn_parameters(t, next);
    if (!next(line)) fail(t, 0, "", 0, "the column names after DISTRIBUTED BLADE PROPERTIES");
    const std::vector<const Column*> columns = elastodyn_header(t, line);
    skip_units(t, next, "(-) (deg) (kg/m) (Nm^2) (Nm^2)");
    Rows rows = read_rows(t, next, columns, p.stations, "NBlInpSt");
    const std::pair<const char*, double> factors[] = {
        {"BMassDen", p.adj_mass}, {"FlpStff", p.adj_flap}, {"EdgStff", p.adj_edge}};
    for (const auto& [name, factor] : factors)
        for (double& x : *column_of(rows, columns, name)) x *= factor;
    validate(t, columns, rows);
    return elastodyn_table(rows, columns);
}

}  // namespace

BladeTable read_bmodes_sections(const std::string& path)
{
    BladeText t;
    read_text(path, t);
    return parse_bmodes(t);
}

BladeTable read_elastodyn_blade(const std::string& path)
{
    BladeText t;
    read_text(path, t);
    return parse_elastodyn(t);
}

BladeTable read_blade_file(const std::string& path)
{
    BladeText t;
    read_text(path, t);
    bool elastodyn = false, bmodes = false;
    LineCursor lines(t);
    Line line;
    while (lines.next(line)) {
        elastodyn = elastodyn || has_words(line.text, "DISTRIBUTED BLADE PROPERTIES");
        bmodes = bmodes || is_bmodes_titles(line.text);
    }
    const std::string formats = "a BModes section-properties file (column titles " + bmodes_titles() +
                                ") or an ElastoDyn blade file (a DISTRIBUTED BLADE PROPERTIES section)";
    if (elastodyn && bmodes) fail(t, 0, "", 0, "either " + formats + ", not the marks of both");
    if (elastodyn) return parse_elastodyn(t);
    if (bmodes) return parse_bmodes(t);
    fail(t, 0, "", 0, formats);
}

bool fortran_number(std::string_view field, double& x)
{
    if (field.starts_with('+')) field.remove_prefix(1);
    std::string s(field);
    std::replace_if(
        s.begin(), s.end(), [](char c) { return c == 'd' || c == 'D'; }, 'e');
    const auto [stop, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
    return ec == std::errc() && stop == s.data() + s.size() && std::isfinite(x);
}

}  // namespace hubbeam
