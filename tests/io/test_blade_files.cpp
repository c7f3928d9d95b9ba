// The blade-property readers (hubbeam/blade_files.hpp): the samples in tests/data/blades read to values worked out by hand,
// the format recognised from the content, editors' encodings read alike, and every refusal one line naming the file,
// the line, the column and the station, never what the file holds.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <hubbeam/blade_files.hpp>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "temp_folder.hpp"

using namespace hubbeam;

namespace {

using Reader = BladeTable (*)(const std::string&);
constexpr double pi = std::numbers::pi;

/// A sample file of tests/data/blades.
std::string sample(const std::string& name)
{
    return std::string(HUBBEAM_SOURCE_DIR) + "/tests/data/blades/" + name;
}

std::string read_text(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> split_lines(const std::string& text)
{
    std::vector<std::string> lines;
    std::size_t pos = 0;
    for (std::size_t end; (end = text.find('\n', pos)) != std::string::npos; pos = end + 1)
        lines.push_back(text.substr(pos, end - pos));
    lines.push_back(text.substr(pos));  // after the last line end: empty for a file that ends with one
    return lines;
}

std::string joined(const std::vector<std::string>& lines)
{
    std::string text;
    for (std::size_t k = 0; k < lines.size(); ++k) text += lines[k] + (k + 1 < lines.size() ? "\n" : "");
    return text;
}

/// text with field `field` (0-based, between blanks) of line `line` (1-based) replaced by `by`, the rest as it was.
std::string with_field(const std::string& text, int line, int field, const std::string& by)
{
    std::vector<std::string> lines = split_lines(text);
    std::string& l = lines.at(static_cast<std::size_t>(line - 1));
    std::size_t pos = 0;
    for (int k = 0;; ++k) {
        pos = l.find_first_not_of(" \t", pos);
        REQUIRE(pos != std::string::npos);
        const std::size_t end = std::min(l.find_first_of(" \t", pos), l.size());
        if (k == field) {
            l.replace(pos, end - pos, by);
            return joined(lines);
        }
        pos = end;
    }
}

/// text with line `line` (1-based) replaced by `by`, or removed when `remove`.
std::string with_line(const std::string& text, int line, const std::string& by, bool remove = false)
{
    std::vector<std::string> lines = split_lines(text);
    const auto at = lines.begin() + (line - 1);
    if (remove)
        lines.erase(at);
    else
        *at = by;
    return joined(lines);
}

/// The BladeFileError read throws on path (the test fails if it throws none).
BladeFileError error_of(Reader read, const std::string& path)
{
    try {
        read(path);
    } catch (const BladeFileError& e) {
        return e;
    }
    FAIL("no BladeFileError for " << path);
    throw std::logic_error("unreachable");
}

void check_near(const std::vector<double>& got, const std::vector<double>& want)
{
    REQUIRE(got.size() == want.size());
    for (std::size_t k = 0; k < want.size(); ++k) CHECK(got[k] == Approx(want[k]).margin(1e-15));
}

bool same_table(const BladeTable& a, const BladeTable& b)
{
    return a.x_over_L == b.x_over_L && a.mass_per_length == b.mass_per_length && a.EI_flap == b.EI_flap &&
           a.EI_edge == b.EI_edge && a.GJ == b.GJ && a.EA == b.EA && a.twist == b.twist &&
           a.mass_moment_flap == b.mass_moment_flap && a.mass_moment_edge == b.mass_moment_edge && a.source == b.source;
}

/// A file that a reader refuses: a sample, or a sample with one field (or line) replaced, and where and what the
/// message says after the file's name: ":LINE: column NAME, station K: expected ...".
struct Refusal {
    const char* sample;
    int line = 0, field = 0;  // line 0: the sample as it is
    const char* by = "";
    Reader read = nullptr;
    long at_line = 0;
    const char* column = "";
    long station = 0;
    const char* message = "";
};

/// Checks that r's reader and read_blade_file refuse its file with its place and message, in one line.
void check_refusal(const Refusal& r)
{
    TempFolder folder("blade");
    std::string path = sample(r.sample);
    if (r.line > 0) path = folder.write(r.sample, with_field(read_text(path), r.line, r.field, r.by));
    INFO(r.sample << " line " << r.line << " field " << r.field << " as " << r.by);
    for (const Reader read : {r.read, &read_blade_file}) {
        const BladeFileError e = error_of(read, path);
        CHECK(e.file == path);
        CHECK(e.line == r.at_line);
        CHECK(e.column == r.column);
        CHECK(e.station == r.station);
        CHECK_THAT(e.what(), Catch::StartsWith(path + r.message));
        CHECK(std::string(e.what()).find('\n') == std::string::npos);
    }
}

}  // namespace

TEST_CASE("a BModes file reads to the values worked out by hand", "[blade_files]")
{
    const BladeTable b = read_bmodes_sections(sample("bmodes_blade.dat"));
    CHECK(b.source == "BModes section properties");
    // Columns by position: sec_loc, str_tw, tw_iner, mass_den, flp_iner, edge_iner, flp_stff, edge_stff, tor_stff,
    // axial_stff, then the offsets (all 0).
    CHECK(b.x_over_L == std::vector<double>{0.0, 0.25, 0.5, 1.0});
    CHECK(b.mass_per_length == std::vector<double>{400.0, 300.0, 200.0, 100.0});
    CHECK(b.EI_flap == std::vector<double>{4e9, 2e9, 1e9, 5e8});
    CHECK(b.EI_edge == std::vector<double>{8e9, 6e9, 4e9, 2e9});
    CHECK(b.GJ == std::vector<double>{1e9, 5e8, 2.5e8, 1e8});
    CHECK(b.EA == std::vector<double>{6e9, 4e9, 2e9, 1e9});
    // str_tw 90, 30, -45, 0 deg.
    check_near(b.twist, {pi / 2, pi / 6, -pi / 4, 0.0});
    // flp_iner, edge_iner are about the principal inertia axes, at tw_iner 90, 0, -45, 0 deg: as written, with their
    // angle (at station 2 the axes are 30 deg from the chord, which BModes turns to the chord without the product).
    CHECK(b.mass_moment_flap == std::vector<double>{2.0, 2.0, 1.0, 0.5});
    CHECK(b.mass_moment_edge == std::vector<double>{10.0, 10.0, 5.0, 2.5});
    check_near(b.inertia_twist, {pi / 2, 0.0, -pi / 4, 0.0});
    CHECK(b.cg_offset == std::vector<double>{0.0, 0.0, 0.0, 0.0});
    // cg_offst as written (docs/model.md section 12.5: positive towards the trailing edge, as BModes has it).
    CHECK(read_bmodes_sections(sample("bmodes_cg_offset.dat")).cg_offset == std::vector<double>{0.0, 0.0, 0.032, 0.0});
    CHECK(b.tc_offset == std::vector<double>{0.0, 0.0, 0.0, 0.0});
    // tc_offst as written, from the reference axis (docs/model.md section 12.6), whatever sc_offst holds: the shear
    // centre's offset is read and checked, and enters no value of the table.
    TempFolder folder("blade");
    const std::string text = with_field(read_text(sample("bmodes_blade.dat")), 9, 12, "0.01");
    const BladeTable offset = read_bmodes_sections(folder.write("tc.dat", text));
    CHECK(offset.tc_offset == std::vector<double>{0.0, 0.0, 0.0, 0.01});
    const BladeTable shear = read_bmodes_sections(folder.write("sc.dat", with_field(text, 7, 11, "-0.005")));
    CHECK(same_table(shear, offset));
    CHECK(shear.tc_offset == offset.tc_offset);
    CHECK(shear.cg_offset == offset.cg_offset);
}

TEST_CASE("ElastoDyn blade files of OpenFAST v5, FAST v8 to OpenFAST v4 and FAST v7 read by their column names",
          "[blade_files]")
{
    SECTION("OpenFAST v5: five columns, adjustment factors 1.5, 2 and 0.5")
    {
        const BladeTable b = read_elastodyn_blade(sample("elastodyn_openfast5.dat"));
        CHECK(b.source == "ElastoDyn blade");
        CHECK(b.x_over_L == std::vector<double>{0.0, 0.5, 1.0});
        check_near(b.twist, {pi, -pi / 2, 0.0});                              // StrcTwst 180, -90, 0 deg
        CHECK(b.mass_per_length == std::vector<double>{300.0, 150.0, 75.0});  // BMassDen 200, 100, 50 times 1.5
        CHECK(b.EI_flap == std::vector<double>{2e9, 1e9, 2e8});               // FlpStff 1e9, 5e8, 1e8 times 2
        CHECK(b.EI_edge == std::vector<double>{2e9, 1e9, 5e8});               // EdgStff 4e9, 2e9, 1e9 times 0.5
        CHECK(b.GJ.empty());
        CHECK(b.EA.empty());
        CHECK(b.mass_moment_flap.empty());
        CHECK(b.mass_moment_edge.empty());
    }
    SECTION("FAST v8 to OpenFAST v4: six columns, a constant PitchAxis")
    {
        const BladeTable b = read_elastodyn_blade(sample("elastodyn_pitch_axis.dat"));
        CHECK(b.x_over_L == std::vector<double>{0.0, 0.4, 1.0});
        check_near(b.twist, {pi / 4, pi / 12, 0.0});  // 45, 15, 0 deg
        CHECK(b.mass_per_length == std::vector<double>{600.0, 300.0, 100.0});
        CHECK(b.EI_flap == std::vector<double>{1.2e10, 3e9, 2e8});
        CHECK(b.EI_edge == std::vector<double>{1.5e10, 6e9, 1e9});
        CHECK(b.GJ.empty());
    }
    SECTION("FAST v8 to OpenFAST v4: a pitch axis that moves along the chord reads as a constant one")
    {
        // ElastoDyn derives no structural property from PitchAxis: the file reads as the one whose axis stays put.
        CHECK(same_table(read_elastodyn_blade(sample("elastodyn_pitch_axis_moves.dat")),
                         read_elastodyn_blade(sample("elastodyn_pitch_axis.dat"))));
    }
    SECTION("FAST v7: 17 columns, zero offsets, torsion, axial stiffness and mass moments of inertia")
    {
        const BladeTable b = read_elastodyn_blade(sample("elastodyn_fast7.dat"));
        CHECK(b.x_over_L == std::vector<double>{0.0, 0.6, 1.0});
        check_near(b.twist, {pi / 9, -pi / 30, 0.0});  // 20, -6, 0 deg
        CHECK(b.mass_per_length == std::vector<double>{500.0, 250.0, 50.0});
        CHECK(b.EI_flap == std::vector<double>{1e10, 3e9, 1e8});  // written 1.00000e+010, as Windows' printf does
        CHECK(b.EI_edge == std::vector<double>{2e10, 8e9, 5e8});
        CHECK(b.GJ == std::vector<double>{4e9, 1e9, 5e7});
        CHECK(b.EA == std::vector<double>{6e10, 3e10, 5e9});
        CHECK(b.mass_moment_flap == std::vector<double>{40.0, 10.0, 0.5});
        CHECK(b.mass_moment_edge == std::vector<double>{160.0, 60.0, 4.0});
    }
    SECTION("columns in another order, names in lower case: found by name, as ElastoDyn finds them")
    {
        const std::string text = read_text(sample("elastodyn_openfast5.dat"));
        std::vector<std::string> lines = split_lines(text);
        for (int l = 15; l <= 19; ++l) {  // names, units and rows: EdgStff BlFract FlpStff StrcTwst BMassDen
            std::istringstream in(lines[static_cast<std::size_t>(l - 1)]);
            std::vector<std::string> f;
            for (std::string w; in >> w;) f.push_back(w);
            std::string row = f.at(4) + " " + f.at(0) + " " + f.at(3) + " " + f.at(1) + " " + f.at(2);
            if (l == 15)
                for (char& c : row) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            lines[static_cast<std::size_t>(l - 1)] = row;
        }
        TempFolder folder("blade");
        const std::string path = folder.write("shuffled.dat", joined(lines));
        CHECK(same_table(read_elastodyn_blade(path), read_elastodyn_blade(sample("elastodyn_openfast5.dat"))));
    }
}

TEST_CASE("read_blade_file recognises the format from the content, not the file's name", "[blade_files]")
{
    const struct {
        const char* name;
        Reader read;
        const char* source;
    } samples[] = {{"bmodes_blade.dat", &read_bmodes_sections, "BModes section properties"},
                   {"elastodyn_openfast5.dat", &read_elastodyn_blade, "ElastoDyn blade"},
                   {"elastodyn_pitch_axis.dat", &read_elastodyn_blade, "ElastoDyn blade"},
                   {"elastodyn_fast7.dat", &read_elastodyn_blade, "ElastoDyn blade"}};
    TempFolder folder("blade");
    for (const auto& s : samples) {
        INFO(s.name);
        const BladeTable by_its_reader = s.read(sample(s.name));
        CHECK(by_its_reader.source == s.source);
        CHECK(same_table(read_blade_file(sample(s.name)), by_its_reader));
        const std::string renamed = folder.write(std::string("blade_") + s.name + ".txt", read_text(sample(s.name)));
        CHECK(same_table(read_blade_file(renamed), by_its_reader));
    }
    // BModes' titles as pyBModes names the first column, and in upper case: BModes never reads them.
    const std::string bmodes = read_text(sample("bmodes_blade.dat"));
    const std::string titles = with_field(with_field(bmodes, 4, 0, "span_loc"), 4, 3, "MASS_DEN");
    CHECK(same_table(read_blade_file(folder.write("span_loc.dat", titles)),
                     read_bmodes_sections(sample("bmodes_blade.dat"))));

    const std::string formats =
        "a BModes section-properties file (column titles sec_loc str_tw tw_iner mass_den flp_iner edge_iner flp_stff "
        "edge_stff tor_stff axial_stff cg_offst sc_offst tc_offst) or an ElastoDyn blade file (a DISTRIBUTED BLADE "
        "PROPERTIES section)";
    const std::string neither = folder.write("neither.dat", "title\n3 stations\n0 1 2\n");
    CHECK(std::string(error_of(&read_blade_file, neither).what()) == neither + ": expected " + formats);
    const std::string both = folder.write(
        "both.dat", with_line(read_text(sample("elastodyn_openfast5.dat")), 2, "sec_loc str_tw tw_iner mass_den"));
    CHECK(std::string(error_of(&read_blade_file, both).what()) ==
          both + ": expected either " + formats + ", not the marks of both");
}

TEST_CASE("a blade file with a byte order mark, CRLF line ends, blank lines or comments reads as the plain file",
          "[blade_files]")
{
    const auto encoded = [](const std::string& text, const std::string& how, bool elastodyn) {
        std::vector<std::string> lines = split_lines(text), out;
        for (std::size_t k = 0; k < lines.size(); ++k) {
            const bool extras = how == "blank lines" || how == "comments" || how == "all";
            // ElastoDyn skips blank lines and comments anywhere; BModes counts lines 1 to 3 and has no comments.
            const bool after_header = elastodyn || k >= 4;
            out.push_back(lines[k] + (elastodyn && (how == "comments" || how == "all") ? "  ! note, 1, 2 # % " : ""));
            if (extras && after_header) out.push_back(" \t ");
            if ((how == "comments" || how == "all") && elastodyn)
                out.insert(out.end(), {"! a comment line", "# 0 1", "% 2 3 4 5 6"});
        }
        std::string result = joined(out);
        if (how == "CRLF" || how == "all") {
            std::string crlf;
            for (const char c : result) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
            result = crlf;
        }
        return how == "BOM" || how == "all" ? "\xef\xbb\xbf" + result : result;
    };
    for (const char* name :
         {"bmodes_blade.dat", "elastodyn_openfast5.dat", "elastodyn_pitch_axis.dat", "elastodyn_fast7.dat"}) {
        const bool elastodyn = std::string(name).starts_with("elastodyn");
        const BladeTable plain = read_blade_file(sample(name));
        for (const char* how : {"BOM", "CRLF", "blank lines", "comments", "all"}) {
            INFO(name << " " << how);
            TempFolder folder("blade");
            const std::string path = folder.write(name, encoded(read_text(sample(name)), how, elastodyn));
            CHECK(same_table(read_blade_file(path), plain));
        }
    }
}

TEST_CASE("what hubbeam does not model is refused in one line naming the file, the line, the column and the station",
          "[blade_files]")
{
    const Refusal refusals[] = {
        // The committed bad samples.
        {"elastodyn_fast7_offsets.dat", 0, 0, "", &read_elastodyn_blade, 20, "EdgcgOf", 2,
         ":20: column EdgcgOf, station 2: expected 0 (edgewise centre-of-mass offset, m)"},
        // The good samples with one field changed.
        {"elastodyn_fast7.dat", 21, 8, "0.1", &read_elastodyn_blade, 21, "Alpha", 3,
         ":21: column Alpha, station 3: expected 0 (flap-twist coupling coefficient): hubbeam models no coupling of "
         "bending and twist"},
        {"elastodyn_fast7.dat", 20, 11, "-0.5", &read_elastodyn_blade, 20, "PrecrvRef", 2,
         ":20: column PrecrvRef, station 2: expected 0 (pre-curve of the reference axis, m): hubbeam's blade has a "
         "straight reference axis"},
        {"elastodyn_fast7.dat", 21, 12, "0.2", &read_elastodyn_blade, 21, "PreswpRef", 3,
         ":21: column PreswpRef, station 3: expected 0 (pre-sweep"},
        {"elastodyn_fast7.dat", 19, 13, "0.01", &read_elastodyn_blade, 19, "FlpcgOf", 1,
         ":19: column FlpcgOf, station 1: expected 0 (flapwise centre-of-mass offset, m)"},
        {"elastodyn_fast7.dat", 20, 15, "0.01", &read_elastodyn_blade, 20, "FlpEAOf", 2,
         ":20: column FlpEAOf, station 2: expected 0 (flapwise elastic-axis offset, m): hubbeam models no offset of "
         "the elastic (tension) axis"},
        {"elastodyn_fast7.dat", 21, 16, "-0.01", &read_elastodyn_blade, 21, "EdgEAOf", 3,
         ":21: column EdgEAOf, station 3: expected 0 (edgewise elastic-axis offset, m)"},
    };
    for (const Refusal& r : refusals) check_refusal(r);
}

TEST_CASE("stations, masses and stiffnesses out of their ranges and fields that are no finite number are refused",
          "[blade_files]")
{
    const Reader bm = &read_bmodes_sections, ed = &read_elastodyn_blade;
    const Refusal refusals[] = {
        {"bmodes_stations_decrease.dat", 0, 0, "", bm, 8, "sec_loc", 3,
         ":8: column sec_loc, station 3: expected a value above the previous station's (stations increase strictly)"},
        {"bmodes_blade.dat", 6, 0, "0.01", bm, 6, "sec_loc", 1,
         ":6: column sec_loc, station 1: expected 0 at the first station (the root)"},
        {"bmodes_blade.dat", 9, 0, "0.9", bm, 9, "sec_loc", 4,
         ":9: column sec_loc, station 4: expected 1 at the last station (the tip)"},
        {"bmodes_blade.dat", 8, 0, "1.5", bm, 8, "sec_loc", 3, ":8: column sec_loc, station 3: expected a value <= 1"},
        {"bmodes_blade.dat", 7, 3, "0.0", bm, 7, "mass_den", 2,
         ":7: column mass_den, station 2: expected a finite value > 0 (mass per length, kg/m)"},
        {"bmodes_blade.dat", 6, 6, "-4.0E+09", bm, 6, "flp_stff", 1,
         ":6: column flp_stff, station 1: expected a finite value > 0 (flap bending stiffness, N m^2)"},
        {"bmodes_blade.dat", 8, 7, "0", bm, 8, "edge_stff", 3, ":8: column edge_stff, station 3: expected a finite"},
        {"bmodes_blade.dat", 9, 8, "-1", bm, 9, "tor_stff", 4, ":9: column tor_stff, station 4: expected a finite"},
        {"bmodes_blade.dat", 6, 9, "0.0", bm, 6, "axial_stff", 1, ":6: column axial_stff, station 1: expected a fin"},
        {"bmodes_blade.dat", 9, 4, "-0.5", bm, 9, "flp_iner", 4,
         ":9: column flp_iner, station 4: expected a value >= 0 (flap mass moment of inertia per length, kg m)"},
        {"bmodes_blade.dat", 7, 5, "-1", bm, 7, "edge_iner", 2, ":7: column edge_iner, station 2: expected a value >="},
        {"bmodes_blade.dat", 7, 3, "heavy", bm, 7, "mass_den", 2,
         ":7: column mass_den, station 2: expected a finite number (mass per length, kg/m)"},
        {"bmodes_blade.dat", 7, 1, "nan", bm, 7, "str_tw", 2,
         ":7: column str_tw, station 2: expected a finite number (structural twist, deg)"},
        {"bmodes_blade.dat", 8, 6, "inf", bm, 8, "flp_stff", 3, ":8: column flp_stff, station 3: expected a finite nu"},
        {"elastodyn_openfast5.dat", 18, 2, "-1.0E+02", ed, 18, "BMassDen", 2,
         ":18: column BMassDen, station 2: expected a finite value > 0 (mass per length times AdjBlMs, kg/m)"},
        {"elastodyn_openfast5.dat", 17, 3, "0", ed, 17, "FlpStff", 1, ":17: column FlpStff, station 1: expected a fi"},
        {"elastodyn_openfast5.dat", 19, 4, "-1", ed, 19, "EdgStff", 3, ":19: column EdgStff, station 3: expected a fi"},
        {"elastodyn_openfast5.dat", 18, 1, "1.0E+999", ed, 18, "StrcTwst", 2,
         ":18: column StrcTwst, station 2: expected a finite number (structural twist, deg)"},
        {"bmodes_blade.dat", 7, 1, "1e308", bm, 7, "str_tw", 2,
         ":7: column str_tw, station 2: expected a value from -360 to 360 (structural twist, deg, one turn)"},
        {"elastodyn_openfast5.dat", 18, 1, "-361", ed, 18, "StrcTwst", 2,
         ":18: column StrcTwst, station 2: expected a value from -360 to 360 (structural twist, deg, one turn)"},
        {"elastodyn_openfast5.dat", 17, 0, "0.1", ed, 17, "BlFract", 1,
         ":17: column BlFract, station 1: expected 0 at the first station (the root)"},
        {"elastodyn_fast7.dat", 20, 6, "0", ed, 20, "GJStff", 2,
         ":20: column GJStff, station 2: expected a finite value > 0 (torsional stiffness, N m^2)"},
        {"elastodyn_fast7.dat", 19, 7, "-6e10", ed, 19, "EAStff", 1, ":19: column EAStff, station 1: expected a fin"},
        {"elastodyn_fast7.dat", 21, 9, "-0.5", ed, 21, "FlpIner", 3, ":21: column FlpIner, station 3: expected a va"},
        {"elastodyn_fast7.dat", 20, 10, "-60", ed, 20, "EdgIner", 2, ":20: column EdgIner, station 2: expected a va"},
    };
    for (const Refusal& r : refusals) check_refusal(r);
}

TEST_CASE("a blade table's counts, titles, column names, row lengths and adjustment factors are checked",
          "[blade_files]")
{
    const Reader bm = &read_bmodes_sections, ed = &read_elastodyn_blade;
    const Refusal refusals[] = {
        {"bmodes_blade.dat", 2, 0, "four", bm, 2, "", 0,
         ":2: expected n_secs, the number of stations, as the first field of line 2 (after the title)"},
        {"bmodes_blade.dat", 2, 0, "1", bm, 2, "", 0, ":2: expected n_secs >= 2"},
        {"bmodes_blade.dat", 2, 0, "5", bm, 12, "", 0, ":12: expected n_secs = 5 rows in the table, found 4 before"},
        {"bmodes_blade.dat", 2, 0, "3", bm, 9, "", 0,
         ":9: expected n_secs = 3 rows in the table as the file says, not one more"},
        {"bmodes_blade.dat", 4, 2, "tw_inr", bm, 4, "tw_iner", 0,
         ":4: column tw_iner: expected the title tw_iner in field 3 (BModes skips line 3, then reads its columns by "
         "position"},
        {"bmodes_blade.dat", 4, 12, "", bm, 4, "", 0, ":4: expected the 13 column titles sec_loc str_tw"},
        {"bmodes_blade.dat", 7, 12, "", bm, 7, "", 0, ":7: expected 13 numbers on a row, one per column, got 12"},
        {"elastodyn_openfast5.dat", 4, 0, "three", ed, 4, "", 0,
         ":4: expected a whole number before NBlInpSt (the number of blade input stations)"},
        {"elastodyn_openfast5.dat", 4, 0, "1", ed, 4, "", 0, ":4: expected NBlInpSt >= 2"},
        {"elastodyn_openfast5.dat", 4, 0, "4", ed, 20, "", 0,
         ":20: expected NBlInpSt = 4 rows in the table, found 3 before this line"},
        {"elastodyn_openfast5.dat", 4, 0, "2", ed, 19, "", 0,
         ":19: expected NBlInpSt = 2 rows in the table as the file says, not one more"},
        {"elastodyn_openfast5.dat", 5, 1, "NBlInpSt", ed, 5, "", 0, ":5: expected one line with NBlInpSt, not a sec"},
        {"elastodyn_openfast5.dat", 11, 0, "0", ed, 11, "", 0,
         ":11: expected a number > 0 before AdjBlMs (the factor ElastoDyn applies to BMassDen)"},
        {"elastodyn_openfast5.dat", 12, 0, "-2", ed, 12, "", 0, ":12: expected a number > 0 before AdjFlSt"},
        {"elastodyn_openfast5.dat", 13, 0, "x", ed, 13, "", 0, ":13: expected a number > 0 before AdjEdSt"},
        {"elastodyn_openfast5.dat", 13, 1, "AdjEdgSt", ed, 0, "", 0,
         ": expected a line with AdjEdSt (the factor ElastoDyn applies to EdgStff) between BLADE PARAMETERS and "
         "DISTRIBUTED BLADE PROPERTIES"},
        {"elastodyn_openfast5.dat", 15, 2, "BMassDens", ed, 15, "", 0,
         ":15: expected in field 3 of the column names one of BlFract, StrcTwst, BMassDen, FlpStff, EdgStff, "
         "PitchAxis, AeroCent,"},
        {"elastodyn_openfast5.dat", 15, 4, "FlpStff", ed, 15, "FlpStff", 0,
         ":15: column FlpStff: expected the column once among the column names"},
        {"elastodyn_openfast5.dat", 15, 4, "GJStff", ed, 15, "EdgStff", 0,
         ":15: column EdgStff: expected the column among the column names (edge bending stiffness times AdjEdSt"},
        {"elastodyn_openfast5.dat", 18, 4, "2e9 1", ed, 18, "", 0, ":18: expected 5 numbers on a row, one per column"},
    };
    for (const Refusal& r : refusals) check_refusal(r);
}

TEST_CASE("a blade file without the lines its format has is refused, and by the reader of the other format too",
          "[blade_files]")
{
    // No line 3 in a BModes file (its titles are then taken for the line BModes skips), no units line, no section
    // lines in an ElastoDyn file, and each sample given to the other format's reader.
    const Reader bm = &read_bmodes_sections, ed = &read_elastodyn_blade;
    TempFolder folder("blade");
    const std::string bmodes = read_text(sample("bmodes_blade.dat")),
                      ed5 = read_text(sample("elastodyn_openfast5.dat"));
    const struct {
        std::string text;
        Reader read;
        const char* message;
    } frames[] = {
        {with_line(bmodes, 3, "", true), bm,
         ":4: column sec_loc: expected the title sec_loc in field 1 (BModes skips line 3, then"},
        {with_line(bmodes, 5, "", true), bm,
         ":5: expected a units line such as (-) (deg) (deg) (kg/m) (kg-m) (kg-m) (Nm^2) (Nm^2) (Nm^2) (N) (m) (m) (m) "
         "under the column names, before the first row"},
        {with_line(ed5, 16, "", true), ed, ":16: expected a units line such as (-) (deg) (kg/m) (Nm^2) (Nm^2) under"},
        {with_line(ed5, 14, "---------------------- BLADE TABLE --------"), ed,
         ": expected a section line DISTRIBUTED BLADE PROPERTIES after BLADE PARAMETERS"},
        {with_line(ed5, 3, "---------------------- PARAMETERS --------"), ed,
         ": expected a section line BLADE PARAMETERS, with which an ElastoDyn blade file begins"},
        {bmodes, ed, ": expected a section line BLADE PARAMETERS"},
        {ed5, bm, ":2: expected n_secs, the number of stations, as the first field of line 2"},
    };
    for (const auto& f : frames) {
        const std::string path = folder.write("frame.dat", f.text);
        INFO(f.message);
        CHECK_THAT(error_of(f.read, path).what(), Catch::StartsWith(path + f.message));
    }
}

TEST_CASE("a blade file that cannot be read, is too large or has too long a line is refused in one line",
          "[blade_files]")
{
    TempFolder folder("blade");
    const std::string missing = (folder.path / "missing.dat").string();
    CHECK(std::string(error_of(&read_blade_file, missing).what()) == missing + ": expected an existing file");
    const std::string here = folder.path.string();
    CHECK(std::string(error_of(&read_bmodes_sections, here).what()) ==
          here + ": expected a regular file (not a folder, FIFO or device)");
    // A FIFO is refused before it is opened: opening it would wait for a writer that never comes.
    const std::string fifo = (folder.path / "fifo.dat").string();
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    CHECK(error_of(&read_elastodyn_blade, fifo).line == 0);

    const std::string large = folder.write("large.dat", std::string(max_blade_file_bytes + 1, ' '));
    CHECK(std::string(error_of(&read_blade_file, large).what()) == large + ": expected a file of at most 16 MiB");
    const std::string empty = folder.write("empty.dat", "");
    CHECK_THAT(error_of(&read_blade_file, empty).what(), Catch::StartsWith(empty + ": expected a BModes section"));

    // A line of max_blade_line_bytes is read, one byte more is refused, wherever it is.
    const std::string bmodes = read_text(sample("bmodes_blade.dat"));
    const std::string longest = folder.write("longest.dat", with_line(bmodes, 1, std::string(4096, 't')));
    CHECK(read_blade_file(longest).x_over_L.size() == 4);
    const std::string too_long = folder.write("too_long.dat", with_line(bmodes, 1, std::string(4097, 't')));
    CHECK(std::string(error_of(&read_blade_file, too_long).what()) ==
          too_long + ":1: expected a line of at most 4096 bytes");
    const std::string ed5 = read_text(sample("elastodyn_openfast5.dat"));
    const std::string long_row = folder.write("long_row.dat", with_field(ed5, 18, 0, std::string(5000, '0')));
    CHECK(error_of(&read_elastodyn_blade, long_row).line == 18);
}

TEST_CASE("a blade file's message never holds what the file holds", "[blade_files]")
{
    const std::string secret = "SECRET-hunter2-token";
    const std::string bmodes = read_text(sample("bmodes_blade.dat")),
                      ed5 = read_text(sample("elastodyn_openfast5.dat"));
    TempFolder folder("blade");
    const std::string files[] = {
        "[default]\naws_access_key_id = " + secret + "\npassword=" + secret + "\n",
        secret + "\n" + secret + "\n",
        with_field(bmodes, 2, 0, secret),         // n_secs
        with_field(bmodes, 4, 2, secret),         // a column title
        with_field(bmodes, 7, 3, secret),         // a value
        with_line(bmodes, 5, "", true),           // the first row taken for the units line
        with_field(ed5, 4, 0, secret),            // NBlInpSt
        with_field(ed5, 11, 0, secret),           // AdjBlMs
        with_field(ed5, 15, 2, secret),           // a column name
        with_field(ed5, 18, 2, secret),           // a value
        with_field(ed5, 18, 4, "2e9 " + secret),  // a field too many
        with_line(ed5, 17, secret + " 1 2 3"),    // a row that is none
    };
    for (const std::string& text : files) {
        const std::string path = folder.write("secret.dat", text);
        for (const Reader read : {&read_blade_file, &read_bmodes_sections, &read_elastodyn_blade}) {
            try {
                read(path);
            } catch (const BladeFileError& e) {
                INFO(e.what());
                CHECK(std::string(e.what()).find("SECRET") == std::string::npos);
                CHECK(std::string(e.what()).find("hunter2") == std::string::npos);
                continue;
            }
            // A reader may read a file whose secret stands where the format reads nothing (a title, a units line).
        }
    }
    // The path is the caller's, and is echoed made printable: no control character reaches a terminal.
    const std::string odd = (folder.path / "blade\x1b[2J\nname.dat").string();
    const std::string message = error_of(&read_blade_file, odd).what();
    CHECK(message.find('\x1b') == std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
    CHECK(message.find("\\x1b[2J\\x0aname.dat: expected an existing file") != std::string::npos);
}
