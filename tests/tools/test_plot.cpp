// hubbeam plot's scripts run through gnuplot: the rows each figure draws (a Campbell line per bending mode and
// variant, never an axial mode; the bending moment at the time closest to --time, else the last), and the string
// expressions that carry file names and labels with quotes into a script.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <hubbeam/output_file.hpp>
#include <hubbeam/printable.hpp>
#include <hubbeam/shortest.hpp>
#include <hubbeam/simulate.hpp>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "plot.hpp"

using namespace hubbeam;
namespace fs = std::filesystem;

namespace {

std::string fixture(const char* name) { return std::string(HUBBEAM_SOURCE_DIR) + "/tests/plots/" + name; }

/// plot campbell's arguments for the modes table file, the figure in dir, the excitation 1P alone.
PlotArgs campbell_of(const fs::path& file, const fs::path& dir)
{
    PlotArgs args;
    args.kind = "campbell";
    args.files = {file.string()};
    args.prefix = (dir / "campbell").string();
    args.harmonics = "1";
    return args;
}

/// A modes CSV's header, as hubbeam modes writes it.
constexpr const char* modes_csv_header =
    "method,ny,nx,order,drive,omega,mode,kind,rad_s,hz,dimensionless,growth,undamped_rad_s,damping_ratio,label,mac\n";

/// One row of a modes CSV for a test's table: variant ("amm,8,4,first,torque"), spin, mode number, label ("edge 2",
/// whose first word is the kind), frequency, growth rate and damping ratio, each number to `digits` significant
/// digits (17: as written); the undamped rate |lambda| is taken as 2 pi hz.
std::string modes_csv_row(const std::string& variant, double omega, std::size_t mode, const std::string& label,
                          double hz, double growth, double zeta, int digits = 6)
{
    std::ostringstream row;
    row.precision(digits);
    row << variant << ',' << omega << ',' << mode << ',' << label.substr(0, label.find(' ')) << ',' << 2 * M_PI * hz
        << ',' << hz << ",1," << growth << ',' << 2 * M_PI * hz << ',' << zeta << ',' << label << ",1\n";
    return row.str();
}

/// How many times text occurs in s.
std::size_t count(const std::string& s, const std::string& text)
{
    std::size_t n = 0;
    for (std::size_t at = s.find(text); at != std::string::npos; at = s.find(text, at + 1)) ++n;
    return n;
}

/// A folder for one test case's figures, removed afterwards.
struct ScratchDir {
    fs::path dir = fs::temp_directory_path() / ("hubbeam_test_plot_" + std::to_string(::getpid()));
    ScratchDir() { fs::create_directories(dir); }
    ~ScratchDir() { fs::remove_all(dir); }
};

/// What gnuplot prints when it has run script and then commands, spaces removed ("0,0.46335\n4,0.53201\n").
std::string gnuplot_prints(const fs::path& dir, const std::string& script, const std::string& commands)
{
    const fs::path path = dir / "check.gp";
    std::ofstream(path) << script << commands << "\n";
    FILE* pipe = ::popen(("gnuplot '" + path.string() + "' 2>&1").c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::string out;
    char buf[256];
    while (std::fgets(buf, sizeof buf, pipe) != nullptr) out += buf;
    REQUIRE(::pclose(pipe) == 0);
    std::string compact;
    for (const char c : out)
        if (c != ' ') compact += c;
    return compact;
}

}  // namespace

TEST_CASE("campbell: a line per bending mode of each variant, through its rows in order of spin rate")
{
    ScratchDir scratch;
    PlotArgs args;
    args.kind = "campbell";
    args.files = {fixture("modes.csv")};
    args.prefix = (scratch.dir / "campbell").string();
    const std::string script = plot_script(args);
    // modes.csv: amm and fem, bending modes 1 and 2 at omega 0 and 4, and an axial mode 1 (308 Hz) at each
    const std::string rows = gnuplot_prints(scratch.dir, script, "print $mode1\nprint $mode2\nprint $mode3\nprint $mode4\n"
                                                                  "print exists('mode5') ? 'mode5' : 'four lines'");
    CHECK(rows == "0,0.46335\n4,0.53201\n\n"  // amm mode 1, not its axial mode 1
                  "0,2.9038\n4,3.075\n\n"
                  "0,0.46349\n4,0.53225\n\n"  // fem mode 1
                  "0,2.9175\n4,3.0879\n\n"
                  "fourlines\n");
    CHECK(fs::file_size(args.prefix + ".png") > 0);
    // the default title names the scene: modes.csv's stem here, SCENE of SCENE-modes.csv as `modes` names it
    CHECK(script.find("set title 'Campbell diagram, modes' noenhanced") != std::string::npos);
    fs::copy_file(fixture("modes.csv"), scratch.dir / "spinup_omega4-modes.csv");
    PlotArgs named = args;
    named.files = {(scratch.dir / "spinup_omega4-modes.csv").string()};
    CHECK(plot_script(named).find("set title 'Campbell diagram, spinup_omega4' noenhanced") != std::string::npos);
    // each tracked label once at the lines' end, whichever variants draw it; the variants in the key by their markers
    CHECK(count(script, "set label 'bending 1' at graph 1, first ") == 1);
    CHECK(count(script, "set label 'bending 2' at graph 1, first ") == 1);
    CHECK(script.find("NaN with points pt 6 ps 1.60 lc rgb '#404040' title 'amm Ny = 4' noenhanced") != std::string::npos);
    CHECK(script.find("NaN with points pt 4 ps 1.35 lc rgb '#404040' title 'fem Ny = 4' noenhanced") != std::string::npos);
    // amm's and fem's lines coincide to the eye: each its own open marker, amm's larger and wider under fem's
    CHECK(script.find("$mode2 using 1:2 smooth unique with linespoints lw 2.5 lc rgb '") != std::string::npos);
    CHECK(script.find("$mode4 using 1:2 smooth unique with linespoints lw 2.1 lc rgb '") != std::string::npos);
    CHECK(count(script, "dt solid pt 6 ps 1.60 pi 1 notitle") == 2 * 2);  // amm's two lines, in both panels
    CHECK(count(script, "dt solid pt 4 ps 1.35 pi 1 notitle") == 2 * 2);
}

TEST_CASE("campbell: a line per tracked mode through a crossing, the excitation lines and their crossings marked")
{
    ScratchDir scratch;
    // Two modes that cross between 0 and 10 rad/s: bending 1 rises from 1 to 2.5 Hz, bending 2 falls from 2 to
    // 1.5 Hz, so the frequency numbers swap while the labels stay.
    const fs::path file = scratch.dir / "crossing.csv";
    std::ofstream(file) << "method,ny,nx,order,drive,omega,mode,kind,rad_s,hz,dimensionless,growth,undamped_rad_s,"
                           "damping_ratio,label,mac\n"
                           "amm,4,0,first,prescribed,0,1,bending,6.28,1,1,0,6.28,0,bending 1,nan\n"
                           "amm,4,0,first,prescribed,0,2,bending,12.6,2,2,0,12.6,0,bending 2,nan\n"
                           "amm,4,0,first,prescribed,10,1,bending,9.42,1.5,1.5,0,9.42,0,bending 2,0.99\n"
                           "amm,4,0,first,prescribed,10,2,bending,15.7,2.5,2.5,0,15.7,0,bending 1,0.99\n";
    PlotArgs args;
    args.kind = "campbell";
    args.files = {file.string()};
    args.prefix = (scratch.dir / "campbell").string();
    args.harmonics = "1";
    const std::string script = plot_script(args);
    CHECK(gnuplot_prints(scratch.dir, script, "print $mode1\nprint $mode2") == "0,1\n10,2.5\n\n0,2\n10,1.5\n\n");
    // 1P only: bending 2 meets omega / 2 pi where the straight segment from (0, 2) to (10, 1.5) crosses it.
    CHECK(script.find("x/(2*pi) with lines") != std::string::npos);
    CHECK(script.find("2*x/(2*pi)") == std::string::npos);
    const std::size_t block = script.find("$critical << EOD\n");
    REQUIRE(block != std::string::npos);
    std::istringstream marks(script.substr(block + 17));
    double omega = 0.0, hz = 0.0;
    char comma = 0;
    marks >> omega >> comma >> hz;
    const double gap0 = 2.0, gap10 = 1.5 - 10.0 / (2.0 * M_PI);
    CHECK(omega == Approx(10.0 * gap0 / (gap0 - gap10)).epsilon(1e-12));
    CHECK(hz == Approx(omega / (2.0 * M_PI)).epsilon(1e-12));
    std::string next;
    marks >> next;
    CHECK(next == "EOD");  // one crossing: bending 1 stays above 1P
    args.harmonics.clear();  // the default: 1P, 2P and 3P
    CHECK(plot_script(args).find("3*x/(2*pi) with lines") != std::string::npos);
    args.harmonics = "0";
    CHECK_THROWS_WITH(plot_script(args), "--harmonics: expected a comma-separated list of integers from 1 to 1000, or none, got 0");
    // A modes CSV of an older hubbeam, without the label column: a line per frequency number of kind bending.
    args.harmonics.clear();
    args.files = {fixture("modes_untracked.csv")};
    CHECK(gnuplot_prints(scratch.dir, plot_script(args), "print $mode1\nprint $mode2") ==
          "0,0.46335\n4,0.53201\n\n0,2.9038\n4,3.075\n\n");
}

namespace {

/// What the plot command of a script draws: per element of the Campbell lines ($modeN), its datablock, its
/// colour and the tracked label its rows are selected by.
struct DrawnLine {
    std::string block, colour, title;
};
std::vector<DrawnLine> drawn_lines(const std::string& script)
{
    std::vector<DrawnLine> lines;
    for (std::size_t at = script.find("$mode"); at != std::string::npos; at = script.find("$mode", at + 1)) {
        const std::size_t end = script.find('\n', at);
        const std::string element = script.substr(at, end - at);
        if (element.find(" using 1:2 smooth unique") == std::string::npos) continue;  // the datablock's definition
        const std::string block = element.substr(0, element.find(' '));
        const std::size_t colour = element.find("lc rgb '") + 8;
        const std::size_t table = script.find("set table " + block + " separator comma\n");
        const std::size_t label = script.find("strcol('label') eq '", table) + 20;
        lines.push_back({block, element.substr(colour, element.find('\'', colour) - colour),
                         script.substr(label, script.find('\'', label) - label)});
    }
    return lines;
}

}  // namespace

TEST_CASE("campbell: --modes, --kinds and --max-frequency choose the lines - each its shade and its label", "[plot]")
{
    ScratchDir scratch;
    // A blade's Campbell table: one variant, bending lines at 10, 300, 900 and 1800 Hz at rest, an axial line and a
    // hub line. Only bending 1 meets 1P (f = omega / 2 pi) between the rates: 10 + 0.05 omega = omega / 2 pi.
    const fs::path file = scratch.dir / "blade-modes.csv";
    std::ofstream table(file);
    table << modes_csv_header;
    const std::vector<std::pair<std::string, double>> at_rest = {
        {"hub 1", 0.5}, {"bending 1", 10}, {"bending 2", 300}, {"bending 3", 900}, {"axial 1", 1200}, {"bending 4", 1800}};
    for (const double omega : {0.0, 100.0, 200.0})
        for (std::size_t m = 0; m < at_rest.size(); ++m) {
            const auto& [label, hz] = at_rest[m];
            table << modes_csv_row("amm,8,4,first,torque", omega, m + 1, label, hz + 0.05 * omega, 0.0, 0.0);
        }
    table.close();
    PlotArgs args = campbell_of(file, scratch.dir);

    // By default the lines below 1.1 times 1P's frequency at the highest rate (200 rad/s: 35 Hz), or bending 1's
    // highest (20 Hz) if it were higher: bending 1 alone
    std::string script = plot_script(args);
    std::vector<DrawnLine> lines = drawn_lines(script);
    REQUIRE(lines.size() == 1);
    CHECK(lines[0].title == "bending 1");
    CHECK(script.find("set yrange [0:" + shortest(1.1 * (200.0 / (2.0 * M_PI))) + "]") != std::string::npos);

    // Below 2000 Hz every bending line: a shade each, its label at its end, the variant in the title
    args.max_hz = "2000";
    script = plot_script(args);
    lines = drawn_lines(script);
    REQUIRE(lines.size() == 4);
    std::set<std::string> colours;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        CHECK(lines[i].title == "bending " + std::to_string(i + 1));
        CHECK(count(script, "set label 'bending " + std::to_string(i + 1) + "' at graph 1") == 1);
        colours.insert(lines[i].colour);
    }
    CHECK(colours.size() == 4);
    CHECK(script.find("set title 'Campbell diagram, blade (amm, Ny = 8)' noenhanced") != std::string::npos);
    CHECK(gnuplot_prints(scratch.dir, script, "print $mode1") == "0,10\n100,15\n200,20\n\n");

    // --modes 2: the two lowest; --kinds adds the hub's and the axial line, ranked with the others by frequency
    args.modes = "2";
    lines = drawn_lines(plot_script(args));
    REQUIRE(lines.size() == 2);
    CHECK(lines[1].title == "bending 2");
    args.kinds = "hub,bending,axial";
    args.modes = "5";
    lines = drawn_lines(plot_script(args));
    std::vector<std::string> titles;
    for (const DrawnLine& l : lines) titles.push_back(l.title);
    CHECK(titles == std::vector<std::string>{"hub 1", "bending 1", "bending 2", "bending 3", "axial 1"});

    // --max-hz 50: the axis ends there, the lines wholly above it are left out, the critical speed stays
    args.kinds.clear();
    args.modes.clear();
    args.max_hz = "50";
    script = plot_script(args);
    lines = drawn_lines(script);
    REQUIRE(lines.size() == 1);
    CHECK(lines[0].title == "bending 1");
    CHECK(script.find("set yrange [0:50]") != std::string::npos);
    const std::size_t block = script.find("$critical << EOD\n");
    REQUIRE(block != std::string::npos);
    const double omega = std::stod(script.substr(block + 17));
    CHECK(omega == Approx(10.0 / (1.0 / (2.0 * M_PI) - 0.05)).epsilon(1e-9));

    // the options' bad values, and the options on another kind
    args.max_hz = "0";
    CHECK_THROWS_WITH(plot_script(args), "--max-frequency: expected a frequency > 0 (Hz), got 0");
    args.max_hz.clear();
    args.modes = "0";
    CHECK_THROWS_WITH(plot_script(args), "--modes: expected an integer from 1 to 1000, got 0");
    args.modes.clear();
    args.kinds = "bending,torsion";
    CHECK_THROWS_WITH(plot_script(args), Catch::StartsWith("--kinds: expected a comma-separated list of bending, edge, flap, twist, axial, hub"));
    args.kinds = "hub";
    args.files = {fixture("modes_untracked.csv")};
    CHECK_THROWS_WITH(plot_script(args), Catch::Contains("modes_untracked.csv: expected rows of kind 'hub'"));
    args.kinds = "axial";  // a file without tracking: the rows of that kind, a line per frequency number
    CHECK(gnuplot_prints(scratch.dir, plot_script(args), "print $mode1\nprint $mode2") ==
          "0,308.46\n4,308.46\n\n0,310.63\n4,310.63\n\n");
    PlotArgs tip;
    tip.kind = "tip";
    tip.files = {fixture("run_amm.csv")};
    tip.prefix = args.prefix;
    tip.max_hz = "50";
    CHECK_THROWS_WITH(plot_script(tip), "--max-frequency: expected no max-frequency for kind tip (only kind campbell draws them), got 50");
}

TEST_CASE("moment: each file's rows at the t closest to --time, by default at its last t")
{
    ScratchDir scratch;
    PlotArgs args;
    args.kind = "moment";
    args.files = {fixture("fields_fem.csv"), fixture("fields_amm.csv")};
    args.prefix = (scratch.dir / "moment").string();
    // FEM's rows up to its node x = 4, where its moment jumps (two rows there)
    const auto first_rows = [&] {
        const std::string all = gnuplot_prints(scratch.dir, plot_script(args), "print $moment1");
        std::size_t end = 0;
        for (int line = 0; line < 6 && end != std::string::npos; ++line) end = all.find('\n', end + 1);
        return all.substr(0, end);
    };
    // the files hold t = 0.5 and t = 1
    const std::string at_half = "0,-12\n1,-9.8\n2,-7.6\n3,-5.4\n4,-3.2\n4,-4";
    const std::string at_one = "0,-19.2\n1,-15.68\n2,-12.16\n3,-8.64\n4,-5.12\n4,-6.4";
    SECTION("default: the last t")
    {
        CHECK(first_rows() == at_one);
        // the files' names share "fields", which the default title takes for the scene's name
        CHECK(plot_script(args).find("set title 'Bending moment along the beam, fields at t = 1 s'") !=
              std::string::npos);
    }
    SECTION("--time 0.6 is closer to 0.5 than to 1")
    {
        args.time = "0.6";
        CHECK(first_rows() == at_half);
    }
    SECTION("--time 0.9 is closer to 1")
    {
        args.time = "0.9";
        CHECK(first_rows() == at_one);
    }
    SECTION("--time 0.75, as close to both, takes the earlier")
    {
        args.time = "0.75";
        CHECK(first_rows() == at_half);
    }
}

TEST_CASE("gnuplot strings read back as the text, quotes and all")
{
    ScratchDir scratch;
    for (const std::string text : {"plain", "it's", "u_y''", "'", "''quoted''", "a `ls` $HOME @macro \\n"}) {
        INFO(text);
        CHECK(gnuplot_prints(scratch.dir, "", "print " + gnuplot_string(text)) == [&] {
            std::string compact;
            for (const char c : text)
                if (c != ' ') compact += c;
            return compact + "\n";
        }());
    }
}

TEST_CASE("plot input errors name the file or option")
{
    PlotArgs args;
    args.kind = "tip";
    args.files = {fixture("run_amm.csv"), fixture("fields_amm.csv")};
    args.prefix = "never-written";
    CHECK_THROWS_WITH(plot_script(args), Catch::Contains("fields_amm.csv: expected a run CSV for kind tip") &&
                                             Catch::Contains("got the header of a field CSV, which kind moment reads"));
    args.kind = "campbell";
    args.files = {fixture("modes.csv"), fixture("modes.csv")};
    args.labels = "a,b,c";
    CHECK_THROWS_WITH(plot_script(args), "--labels: expected 2 comma-separated labels, one per file, got 3 (a,b,c)");
    args.labels = "a,";
    CHECK_THROWS_WITH(plot_script(args), "--labels: expected a non-empty label per file, got an empty item");
    PlotArgs timed = args;
    timed.labels.clear();
    timed.time = "1";
    CHECK_THROWS_WITH(plot_script(timed), Catch::StartsWith("--time: expected no time for kind campbell"));
}

namespace {

/// The rows of a CSV file as fields, the header first (a reader of its own, independent of plot.cpp's).
std::vector<std::vector<std::string>> csv_rows(const std::string& path)
{
    std::vector<std::vector<std::string>> rows;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> fields;
        std::size_t start = 0;
        for (std::size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1)
            fields.push_back(line.substr(start, comma - start));
        fields.push_back(line.substr(start));
        rows.push_back(fields);
    }
    return rows;
}

/// Writes rows to path with the columns in the order `order` gives (order[i]: the source column of column i).
void write_permuted(const std::vector<std::vector<std::string>>& rows, const std::vector<std::size_t>& order,
                    const fs::path& path)
{
    std::ofstream out(path);
    for (const auto& r : rows) {
        for (std::size_t i = 0; i < order.size(); ++i) out << (i ? "," : "") << r[order[i]];
        out << "\n";
    }
}

}  // namespace

TEST_CASE("tip: curves that coincide get their own dash patterns and a panel of their differences")
{
    ScratchDir scratch;
    PlotArgs args;
    args.kind = "tip";
    // named as setup.sh names a scene's runs: the default title names the scene
    fs::copy_file(fixture("run_amm.csv"), scratch.dir / "spinup_omega4-amm.csv");
    fs::copy_file(fixture("run_fem.csv"), scratch.dir / "spinup_omega4-fem.csv");
    args.files = {(scratch.dir / "spinup_omega4-amm.csv").string(), (scratch.dir / "spinup_omega4-fem.csv").string()};
    args.labels = "AMM,FEM";
    args.prefix = (scratch.dir / "tip").string();
    const std::string script = plot_script(args);
    CHECK(script.find("set title 'Tip deflection, spinup_omega4' noenhanced") != std::string::npos);
    // AMM's and FEM's tips differ by at most 1e-4 m of 0.5 m: a line each, solid and dashed, then the panel
    CHECK(script.find("using 't':'tip_uy' with lines lw 3.0 dt 1 lc 1 title 'AMM'") != std::string::npos);
    CHECK(script.find("using 't':'tip_uy' with lines lw 2.5 dt 2 lc 2 title 'FEM'") != std::string::npos);
    CHECK(count(script, "  set multiplot\n") == 1);
    CHECK(script.find("$difference2 using 1:2 with lines lw 2.5 dt 2 lc 2 title 'FEM - AMM'") != std::string::npos);
    // the panel's rows: FEM's tip_uy minus AMM's at each time, from the files as this test reads them
    const auto amm = csv_rows(fixture("run_amm.csv")), fem = csv_rows(fixture("run_fem.csv"));
    REQUIRE(amm.size() == fem.size());
    std::string expected;
    for (std::size_t i = 1; i < fem.size(); ++i) {
        REQUIRE(amm[i][0] == fem[i][0]);  // the same times
        char line[64];
        std::snprintf(line, sizeof line, "%s,%.4e\n", fem[i][0].c_str(), std::stod(fem[i][3]) - std::stod(amm[i][3]));
        expected += line;
    }
    const std::string printed = gnuplot_prints(
        scratch.dir, script, "print $difference2");
    std::string rounded;  // gnuplot prints the block's lines as written: round them as expected is
    std::size_t start = 0;
    for (std::size_t end; (end = printed.find('\n', start)) != std::string::npos; start = end + 1) {
        const std::string row = printed.substr(start, end - start);
        if (row.empty()) continue;
        const std::size_t comma = row.find(',');
        char line[64];
        std::snprintf(line, sizeof line, "%s,%.4e\n", row.substr(0, comma).c_str(), std::stod(row.substr(comma + 1)));
        rounded += line;
    }
    CHECK(rounded == expected);
    CHECK(fs::file_size(args.prefix + ".png") > 0);

    SECTION("curves apart (a tip ten times AMM's) need no difference panel")
    {
        auto rows = amm;
        for (std::size_t i = 1; i < rows.size(); ++i) rows[i][3] = std::to_string(10.0 * std::stod(rows[i][3]));
        write_permuted(rows, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}, scratch.dir / "spinup_omega4-big.csv");
        args.files[1] = (scratch.dir / "spinup_omega4-big.csv").string();
        const std::string apart = plot_script(args);
        CHECK(apart.find("multiplot") == std::string::npos);
        CHECK(apart.find("$difference") == std::string::npos);
        CHECK(apart.find(" dt 2 lc 2 title 'FEM'") != std::string::npos);  // still dashed
    }
}

TEST_CASE("every kind reads its columns by name, in any order, and names a missing one")
{
    ScratchDir scratch;
    PlotArgs args;
    args.kind = "campbell";
    args.prefix = (scratch.dir / "campbell").string();
    // modes.csv with its columns reversed: the same lines of the same rows
    const auto rows = csv_rows(fixture("modes.csv"));
    std::vector<std::size_t> reversed;
    for (std::size_t i = rows[0].size(); i-- > 0;) reversed.push_back(i);
    write_permuted(rows, reversed, scratch.dir / "reversed.csv");
    args.files = {(scratch.dir / "reversed.csv").string()};
    CHECK(gnuplot_prints(scratch.dir, plot_script(args), "print $mode1\nprint $mode4") ==
          "0,0.46335\n4,0.53201\n\n0,2.9175\n4,3.0879\n\n");

    // a modes CSV without its kind column: refused, naming the file and the column
    std::vector<std::size_t> without_kind;
    for (std::size_t i = 0; i < rows[0].size(); ++i)
        if (rows[0][i] != "kind") without_kind.push_back(i);
    write_permuted(rows, without_kind, scratch.dir / "no_kind.csv");
    args.files = {(scratch.dir / "no_kind.csv").string()};
    CHECK_THROWS_WITH(plot_script(args), Catch::StartsWith((scratch.dir / "no_kind.csv").string() +
                                                           ": expected a modes CSV for kind campbell") &&
                                             Catch::Contains("it needs the column kind"));

    // a field CSV with its columns rotated draws the same moment
    const auto fields = csv_rows(fixture("fields_fem.csv"));
    std::vector<std::size_t> rotated;
    for (std::size_t i = 0; i < fields[0].size(); ++i) rotated.push_back((i + 3) % fields[0].size());
    write_permuted(fields, rotated, scratch.dir / "rotated.csv");
    args.kind = "moment";
    args.files = {(scratch.dir / "rotated.csv").string()};
    args.time = "0.6";
    CHECK(gnuplot_prints(scratch.dir, plot_script(args), "print $moment1").substr(0, 17) == "0,-12\n1,-9.8\n2,-7");
}

TEST_CASE("legend entries fit their box: the key is widened for proportional fonts")
{
    PlotArgs args;
    args.kind = "axial";
    args.files = {fixture("run_amm.csv")};
    args.prefix = "never-written";
    const std::string script = plot_script(args);
    CHECK(script.find("set key outside right top box width 2") != std::string::npos);
}

namespace {

/// The message of what f throws (an exception derived from std::exception), or "" when it throws nothing.
template <class F>
std::string thrown(F&& f)
{
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

/// The current folder changed to dir while it lives (gnuplot runs a shell command in the folder it was started in).
struct InFolder {
    fs::path before = fs::current_path();
    explicit InFolder(const fs::path& dir) { fs::current_path(dir); }
    ~InFolder() { fs::current_path(before); }
};

}  // namespace

TEST_CASE("text handed to gnuplot: a control or format character is refused, and said where", "[plot]")
{
    // the one check (printable.hpp): what printable() would escape, at its byte, and nothing else of the text
    CHECK(unsafe_character("").empty());
    CHECK(
        unsafe_character("runs/blade \xc3\xbc 'it''s' `ls` $HOME @m.csv").empty());  // quotes and all: gnuplot_string's
    CHECK(unsafe_character("x\n!touch pwned") == "a control character (\\x0a) at byte 2");
    CHECK(unsafe_character("ok\x1b[2J") == "a control character (\\x1b) at byte 3");
    CHECK(unsafe_character("a\rb") == "a control character (\\x0d) at byte 2");
    CHECK(unsafe_character("a\x7f") == "a control character (\\x7f) at byte 2");
    CHECK(unsafe_character("\xc2\x85") == "a control character (\\x85) at byte 1");  // NEL, a C1 control
    CHECK(unsafe_character("ab\xe2\x80\xae"
                           "cd") == "an invisible or format character (\\u202e) at byte 3");
    CHECK(unsafe_character("a\xe2\x80\xa8") == "an invisible or format character (\\u2028) at byte 2");
    CHECK(unsafe_character("a\xff") == "a byte that is not UTF-8 (\\xff) at byte 2");
    CHECK(unsafe_character(std::string("a\0b", 3)) == "a control character (\\x00) at byte 2");
    CHECK(thrown([] { gnuplot_string("a\nb", "--title"); }) ==
          "--title: expected text without control or format characters, got a control character (\\x0a) at byte 2");
    CHECK_THROWS_AS(gnuplot_string("a\nb"), PlotInputError);

    ScratchDir scratch;
    PlotArgs args;
    args.kind = "tip";
    args.files = {fixture("run_amm.csv")};
    args.prefix = (scratch.dir / "tip").string();
    REQUIRE_NOTHROW(plot_script(args));
    SECTION("the prefix")
    {
        args.prefix = "x\n!touch pwned\n";
        CHECK_THROWS_AS(plot_script(args), OutputRefused);
        CHECK(thrown([&] { plot_script(args); }) ==
              "-o: expected a path prefix without control or format characters, got a control character (\\x0a) at "
              "byte 2");
    }
    SECTION("a folder of the prefix")
    {
        args.prefix = (scratch.dir / "d\n!touch pwned\n" / "tip").string();
        CHECK(thrown([&] { plot_script(args); }) ==
              "-o: expected a path prefix without control or format characters, got a control character (\\x0a) at "
              "byte " +
                  std::to_string(scratch.dir.string().size() + 3));
    }
    SECTION("the title")
    {
        args.title = "Tip\n!touch pwned";
        CHECK(thrown([&] { plot_script(args); }) ==
              "--title: expected a title without control or format characters, got a control character (\\x0a) at "
              "byte 4");
    }
    SECTION("the labels")
    {
        args.labels = "AMM\xe2\x80\xae";
        CHECK(thrown([&] { plot_script(args); }) ==
              "--labels: expected labels without control or format characters, got an invisible or format character "
              "(\\u202e) at byte 4");
    }
    SECTION("a file's name")
    {
        args.files = {fixture("run_amm.csv") + "\n!touch pwned"};
        CHECK(thrown([&] { plot_script(args); }) ==
              "FILE: expected a file name without control or format characters, got a control character (\\x0a) at "
              "byte " +
                  std::to_string(fixture("run_amm.csv").size() + 1));
    }
    SECTION("a modes CSV's text cells, which go into the script: named by line and column, never quoted")
    {
        const fs::path file = scratch.dir / "bell-modes.csv";
        std::ifstream in(fixture("modes.csv"));
        std::ofstream out(file);
        std::string line;
        for (int n = 1; std::getline(in, line); ++n) {
            if (n == 3) line.replace(line.rfind(",bending 2,"), 11, ",bending 2\x07SECRET,");
            out << line << "\n";
        }
        out.close();
        args.kind = "campbell";
        args.files = {file.string()};
        const std::string message = thrown([&] { plot_script(args); });
        CHECK(message == file.string() +
                             ": line 3, column 17 (label): expected text without control or format "
                             "characters (it goes into the gnuplot script), got a control character "
                             "(\\x07) at byte 10");
    }
}

TEST_CASE("the attack: a prefix or a folder with a newline and '!' runs no shell command", "[plot]")
{
    ScratchDir scratch;
    const InFolder in(scratch.dir);
    PlotArgs args;
    args.kind = "animate";
    args.files = {fixture("fields_amm.csv"), fixture("run_amm.csv")};
    args.prefix = "x\n!touch pwned\n";
    CHECK_THROWS_AS(draw_animation(args), OutputRefused);
    CHECK_FALSE(fs::exists(scratch.dir / "pwned"));
    // a folder named so, which exists: the prefix is refused before gnuplot sees it
    fs::create_directory(scratch.dir / "d\n!touch pwned\n");
    args.prefix = "d\n!touch pwned\n/anim";
    CHECK_THROWS_AS(draw_animation(args), OutputRefused);
    args.kind = "tip";
    args.files = {fixture("run_amm.csv")};
    CHECK_THROWS_AS(draw_plot(args), OutputRefused);
    args.prefix = "fig";
    args.title = "Tip\n!touch pwned\n";
    CHECK_THROWS_AS(draw_plot(args), PlotInputError);
    args.kind = "animate";
    args.files = {fixture("fields_amm.csv")};
    CHECK_THROWS_AS(draw_animation(args), PlotInputError);
    CHECK_FALSE(fs::exists(scratch.dir / "pwned"));
    CHECK(fs::directory_iterator(scratch.dir / "d\n!touch pwned\n") == fs::directory_iterator());
    CHECK_FALSE(fs::exists(scratch.dir / "fig.gp"));
}

TEST_CASE("a prefix that names a folder is refused: no hidden DIR/.png", "[plot]")
{
    ScratchDir scratch;
    PlotArgs args;
    args.kind = "tip";
    args.files = {fixture("run_amm.csv")};
    for (const std::string& folder :
         {(scratch.dir / "").string(), (scratch.dir / ".").string(), (scratch.dir / "..").string(), std::string(".")}) {
        INFO(folder);
        args.prefix = folder;
        CHECK(thrown([&] { draw_plot(args); }) ==
              "-o: expected a path prefix that ends in a file name (as DIR/NAME for DIR/NAME.png), got \"" + folder +
                  "\", which names a folder");
    }
    args.prefix = (scratch.dir / "").string();
    args.kind = "animate";
    args.files = {fixture("fields_amm.csv")};
    CHECK_THROWS_AS(draw_animation(args), OutputRefused);
    CHECK(fs::directory_iterator(scratch.dir) == fs::directory_iterator());  // no .png, .svg, .gp, .gif
    CHECK_THROWS_AS(draw_figures({(scratch.dir / "").string()}, (scratch.dir / "x.gp").string(), "",
                                 [](const std::vector<std::string>&) { return std::string(); }),
                    OutputRefused);
}

TEST_CASE("plot messages name a bad file's line and column, never its content", "[plot]")
{
    ScratchDir scratch;
    PlotArgs args;
    args.kind = "tip";
    args.prefix = (scratch.dir / "p").string();
    // a file that is no CSV at all: its first line is not quoted
    const fs::path secret = scratch.dir / "secret";
    std::ofstream(secret) << "TOPSECRET password=hunter2\nmore\n";
    args.files = {secret.string()};
    std::string message = thrown([&] { plot_script(args); });
    CHECK(message == secret.string() + ": expected a run CSV for kind tip (header " + std::string(row_header()) +
                         "; it needs the column t), got a first line of 1 comma-separated field, none of them t");
    CHECK(message.find("TOPSECRET") == std::string::npos);
    // a run CSV whose tip_uy cell is text
    const fs::path run = scratch.dir / "run.csv";
    {
        std::ifstream in(fixture("run_amm.csv"));
        std::ofstream out(run);
        std::string line;
        for (int n = 1; std::getline(in, line); ++n) {
            if (n == 4) {
                std::vector<std::string> cells = csv_rows(fixture("run_amm.csv"))[3];
                cells[3] = "SECRETSECRETSECRETSECRETSECRETSECRETSECR";  // 40 characters
                line.clear();
                for (std::size_t i = 0; i < cells.size(); ++i) line += (i ? "," : "") + cells[i];
            }
            out << line << "\n";
        }
    }
    args.files = {run.string()};
    message = thrown([&] { plot_script(args); });
    CHECK(message == run.string() +
                         ": line 4, column 4 (tip_uy): expected a number (as 0.25 or -1.5e-3), got 40 "
                         "characters that are not one");
    // plot animate: a cell of 40 characters, and a header without the columns it reads
    const fs::path fields = scratch.dir / "secret-fields.csv";
    {
        std::ifstream in(fixture("fields_amm.csv"));
        std::ofstream out(fields);
        std::string line;
        for (int n = 1; std::getline(in, line); ++n) {
            if (n == 3) line = "0.5,1,SECRETSECRETSECRETSECRETSECRETSECRETSECR,0,0,0,0,0";
            out << line << "\n";
        }
    }
    args.kind = "animate";
    args.files = {fields.string()};
    message = thrown([&] { draw_animation(args); });
    CHECK(message == fields.string() +
                         ": line 3, column 3 (uy): expected a finite number, got 40 characters that "
                         "are not a number");
    args.files = {secret.string()};
    message = thrown([&] { draw_animation(args); });
    CHECK(message == printable(secret.string(), 400) +
                         ": expected a column t in its header (time, s), got none among its 1 columns");
    CHECK_FALSE(fs::exists(scratch.dir / "p.gif"));
}

namespace {

/// Writes a CSV: header, then rows of numbers as text.
void write_csv(const fs::path& path, const std::string& header, const std::vector<std::vector<std::string>>& rows)
{
    std::ofstream out(path);
    out << header << "\n";
    for (const auto& r : rows) {
        for (std::size_t i = 0; i < r.size(); ++i) out << (i ? "," : "") << r[i];
        out << "\n";
    }
}

const char* const fields_header = "t,x,uy,ux,slope,curvature,bending_moment,axial_force";

}  // namespace

TEST_CASE("plot animate: finite numbers, times in order, and a file of a sensible size", "[plot]")
{
    ScratchDir scratch;
    PlotArgs args;
    args.kind = "animate";
    const fs::path fields = scratch.dir / "f.csv", run = scratch.dir / "r.csv";
    const std::string gif = (scratch.dir / "a.gif").string();
    args.prefix = (scratch.dir / "a").string();
    // two frames of two points; the run's theta at t = 0 and 1
    const std::vector<std::vector<std::string>> good = {{"0", "0", "0", "0", "0", "0", "0", "0"},
                                                        {"0", "1", "0.1", "0", "0", "0", "0", "0"},
                                                        {"1", "0", "0", "0", "0", "0", "0", "0"},
                                                        {"1", "1", "0.2", "0", "0", "0", "0", "0"}};
    write_csv(fields, fields_header, good);
    write_csv(run, "t,theta", {{"0", "0"}, {"0.5", "0.25"}, {"1", "0.5"}});
    args.files = {fields.string(), run.string()};
    const std::string script = animation_script(args, gif);
    // the tip of frame 1, (x + ux, uy) = (1, 0.1) at theta(0) = 0; of frame 2, (1, 0.2) turned by theta(1) = 0.5
    const std::string first = "$tip << EOD\n1 0.1 0\n";
    REQUIRE(script.find(first) != std::string::npos);
    const std::size_t at = script.find(first) + first.size();
    double x = 0.0, y = 0.0;
    std::istringstream(script.substr(at)) >> x >> y;
    CHECK(x == Approx(std::cos(0.5) - std::sin(0.5) * 0.2).epsilon(1e-15));
    CHECK(y == Approx(std::sin(0.5) + std::cos(0.5) * 0.2).epsilon(1e-15));

    SECTION("NaN and infinities, in the fields or the run, are refused by line and column")
    {
        for (const char* bad : {"nan", "NaN", "inf", "-inf", "1e999"}) {
            INFO(bad);
            auto rows = good;
            rows[1][2] = bad;
            write_csv(fields, fields_header, rows);
            const std::string got = std::string(bad) == "nan" || std::string(bad) == "NaN" ? "NaN" : "an infinity";
            const std::string message = thrown([&] { animation_script(args, gif); });
            if (std::string(bad) == "1e999")  // out of range: from_chars reads no number
                CHECK(message == fields.string() +
                                     ": line 3, column 3 (uy): expected a finite number, got 5 "
                                     "characters that are not a number");
            else
                CHECK(message == fields.string() + ": line 3, column 3 (uy): expected a finite number, got " + got);
        }
        write_csv(fields, fields_header, good);
        write_csv(run, "t,theta", {{"0", "0"}, {"0.5", "nan"}, {"1", "0.5"}});
        CHECK(thrown([&] { animation_script(args, gif); }) ==
              run.string() + ": line 3, column 2 (theta): expected a finite number, got NaN");
    }
    SECTION("a run CSV whose times do not increase is refused (the hub angle would be wrong)")
    {
        write_csv(run, "t,theta", {{"0", "0"}, {"1", "0.5"}, {"0.5", "0.25"}});
        CHECK(thrown([&] { animation_script(args, gif); }) ==
              run.string() +
                  ": line 4: expected times t increasing from row to row, as hubbeam run writes them, got "
                  "an earlier time");
        write_csv(run, "t,theta", {{"0", "0"}, {"0", "0.5"}, {"1", "0.25"}});
        CHECK(thrown([&] { animation_script(args, gif); }) ==
              run.string() +
                  ": line 3: expected times t increasing from row to row, as hubbeam run writes them, got "
                  "the time of the row before");
    }
    SECTION("fields whose frames go back in time are refused")
    {
        auto rows = good;
        rows.push_back({"0", "0", "0", "0", "0", "0", "0", "0"});
        write_csv(fields, fields_header, rows);
        CHECK(thrown([&] { animation_script(args, gif); }) ==
              fields.string() +
                  ": line 6: expected the frames' times t increasing (the rows of a time together, as "
                  "hubbeam run writes them), got an earlier time");
    }
    SECTION("a file too large is refused before it is read, one of too many rows at the first row past the limit")
    {
        // 257 MiB, sparse: no disk is used, and the size alone refuses it
        {
            std::ofstream out(fields);
            out << fields_header << "\n";
        }
        fs::resize_file(fields, (257u << 20));
        CHECK(thrown([&] { animation_script(args, gif); }) ==
              fields.string() +
                  ": expected a fields CSV of hubbeam run --fields-at of at most 256 MiB (plot animate's "
                  "limit), got 257 MiB");
        // 200,001 rows: 1000 frames of 200 points and one more
        {
            std::ofstream out(fields);
            out << fields_header << "\n";
            for (int frame = 0; frame <= 1000; ++frame)
                for (int point = 0; point < (frame < 1000 ? 200 : 1); ++point)
                    out << frame << "," << point << ",0,0,0,0,0,0\n";
        }
        write_csv(run, "t,theta", {{"0", "0"}, {"3000", "1"}});
        CHECK(thrown([&] { animation_script(args, gif); }) ==
              fields.string() + ": expected at most 200000 rows (plot animate's limit), got more");
        // 200,000 rows are read
        fs::resize_file(fields, fs::file_size(fields) - std::string("1000,0,0,0,0,0,0,0\n").size());
        CHECK(animation_script(args, gif).find("array T[1000]") != std::string::npos);
        // the run CSV: 1,000,001 rows are refused, 1,000,000 read
        write_csv(fields, fields_header, good);
        {
            std::ofstream out(run);
            out << "t,theta\n";
            for (int k = 0; k <= 1000000; ++k) out << k << ",0\n";
        }
        CHECK(thrown([&] { animation_script(args, gif); }) ==
              run.string() + ": expected at most 1000000 rows (plot animate's limit), got more");
        fs::resize_file(run, fs::file_size(run) - std::string("1000000,0\n").size());
        CHECK_NOTHROW(animation_script(args, gif));
    }
}

TEST_CASE("plot tip --column draws a blade's tip_uz or tip_phi, its axis and title naming it", "[plot]")
{
    ScratchDir scratch;
    // two blade runs whose tips coincide to the eye: the panel below holds B's minus A's, of the column drawn
    const std::string header = std::string(row_header()) + ",tip_uz,tip_phi";
    const auto run = [&](const char* name, double uz, double phi) {
        std::vector<std::vector<std::string>> rows;
        for (int k = 0; k <= 4; ++k) {
            std::vector<std::string> r(10, "0");
            r[0] = std::to_string(k);
            r[3] = std::to_string(0.5 * k);  // tip_uy
            r.push_back(shortest(uz * k));
            r.push_back(shortest(phi * k));
            rows.push_back(r);
        }
        write_csv(scratch.dir / name, header, rows);
        return (scratch.dir / name).string();
    };
    PlotArgs args;
    args.kind = "tip";
    args.files = {run("blade-a.csv", 1.0, 0.25), run("blade-b.csv", 1.0078125, 0.2509765625)};  // + 2^-7, 2^-10
    args.labels = "A,B";
    args.prefix = (scratch.dir / "tip").string();
    args.column = "tip_uz";
    std::string script = plot_script(args);
    CHECK(script.find("using 't':'tip_uz' with lines") != std::string::npos);
    CHECK(script.find("'tip_uy'") == std::string::npos);
    CHECK(script.find("set ylabel 'tip flapwise deflection u_z(L) (m)'") != std::string::npos);
    CHECK(script.find("set ylabel 'u_z(L) - A (m)' noenhanced") != std::string::npos);
    CHECK(script.find("set title 'Tip flapwise deflection, blade' noenhanced") != std::string::npos);
    CHECK(gnuplot_prints(scratch.dir, script, "print $difference2") ==
          "0,0\n1,0.0078125\n2,0.015625\n3,0.0234375\n4,0.03125\n\n");
    args.column = "tip_phi";
    script = plot_script(args);
    CHECK(script.find("set ylabel 'tip twist phi(L) (rad)'") != std::string::npos);
    CHECK(script.find("set ylabel 'phi(L) - A (rad)' noenhanced") != std::string::npos);
    CHECK(gnuplot_prints(scratch.dir, script, "print $difference2") ==
          "0,0\n1,0.0009765625\n2,0.001953125\n3,0.0029296875\n4,0.00390625\n\n");
    // a planar run has no tip_uz: refused, naming the column
    args.files = {fixture("run_amm.csv")};
    args.labels.clear();
    args.column = "tip_uz";
    CHECK(thrown([&] { plot_script(args); }) ==
          fixture("run_amm.csv") + ": expected a run CSV for kind tip (header " + row_header() +
              "; it needs the column tip_uz), got a first line of 10 comma-separated fields, none of them tip_uz");
    args.column = "tip_ux";
    CHECK(thrown([&] { plot_script(args); }) ==
          "--column: expected one of tip_uy, tip_uz, tip_phi for kind tip, got tip_ux");
    args.kind = "axial";
    args.column = "tip_uz";
    CHECK(
        thrown([&] { plot_script(args); }) ==
        "--column: expected no column for kind axial (only kinds tip and moment draw a column of choice), got tip_uz");
}

TEST_CASE(
    "plot moment --column draws a blade's flapwise moment or torque, and says a blade's bending moment is edgewise",
    "[plot]")
{
    ScratchDir scratch;
    const fs::path file = scratch.dir / "blade-fields.csv";
    // t, x, uy, ux, slope, curvature, bending_moment, axial_force, uz, phi, flap_moment, torque
    write_csv(file, std::string(fields_header) + ",uz,phi,flap_moment,torque",
              {{"1", "0", "0", "0", "0", "0", "-5", "0", "0", "0", "7", "0.25"},
               {"1", "2", "0", "0", "0", "0", "-2", "0", "0", "0", "3", "0.125"},
               {"2", "0", "0", "0", "0", "0", "-6", "0", "0", "0", "8", "0.5"},
               {"2", "2", "0", "0", "0", "0", "-3", "0", "0", "0", "4", "0.375"}});
    PlotArgs args;
    args.kind = "moment";
    args.files = {file.string()};
    args.prefix = (scratch.dir / "moment").string();
    args.time = "1";
    std::string script = plot_script(args);
    CHECK(script.find("set ylabel 'edgewise bending moment EI_{edge} kappa_c (N m)'") != std::string::npos);
    CHECK(gnuplot_prints(scratch.dir, script, "print $moment1") == "0,-5\n2,-2\n\n");
    args.column = "flap_moment";
    script = plot_script(args);
    CHECK(script.find("set ylabel 'flapwise bending moment EI_{flap} kappa_n (N m)'") != std::string::npos);
    CHECK(script.find("set title 'Flapwise bending moment along the blade, blade at t = 1 s' noenhanced") !=
          std::string::npos);
    CHECK(gnuplot_prints(scratch.dir, script, "print $moment1") == "0,7\n2,3\n\n");
    args.column = "torque";
    args.time.clear();
    script = plot_script(args);
    CHECK(script.find("set ylabel 'torque GJ dphi/dx (N m)'") != std::string::npos);
    CHECK(gnuplot_prints(scratch.dir, script, "print $moment1") == "0,0.5\n2,0.375\n\n");
    // a beam in the plane: EI u_y'', as before
    args.files = {fixture("fields_amm.csv")};
    args.column.clear();
    CHECK(plot_script(args).find("set ylabel 'bending moment M = EI d^2u_y/dx^2 (N m)'") != std::string::npos);
    args.column = "flap_moment";
    CHECK_THROWS_WITH(plot_script(args), Catch::Contains("it needs the column flap_moment), got a first line of 8 "
                                                         "comma-separated fields, none of them flap_moment"));
}

TEST_CASE("plot's unknown KIND names every kind, animate too", "[plot]")
{
    PlotArgs args;
    args.kind = "spectrum";
    args.files = {fixture("modes.csv")};
    args.prefix = "never-written";
    CHECK(thrown([&] { plot_script(args); }) ==
          "KIND: expected one of tip, axial, campbell, moment, animate, got spectrum");
    CHECK(plot_kinds() == std::vector<std::string>{"tip", "axial", "campbell", "moment", "animate"});
    args.kind = "animate";
    args.labels = "a";
    CHECK(thrown([&] { draw_animation(args); }) ==
          "--labels: expected no labels for kind animate (only kinds of a line per file take them), got a");
}

TEST_CASE("campbell: overdamped rows (0 Hz) draw no line and no critical speed, whatever --modes", "[plot]")
{
    ScratchDir scratch;
    // A damped blade's table at 0, 5 and 10 rad/s: a flap and an edge mode overdamped throughout (0 Hz), a flap mode
    // overdamped at rest only, and edge and flap modes oscillating at 3 and 5 Hz. None meets 1P (f = omega / 2 pi
    // stays below 1.6 Hz up to 10 rad/s) but a mode at 0 Hz at rest would: that crossing is spurious.
    const fs::path file = scratch.dir / "damped-modes.csv";
    std::ofstream table(file);
    table << modes_csv_header;
    for (const int omega : {0, 5, 10}) {
        const std::vector<std::pair<std::string, double>> modes = {
            {"flap 1", 0}, {"edge 1", 0}, {"flap 2", omega == 0 ? 0.0 : 4.0}, {"edge 2", 3.0}, {"flap 3", 5.0}};
        for (std::size_t m = 0; m < modes.size(); ++m) {
            const auto& [label, hz] = modes[m];
            table << modes_csv_row("fem,8,0,first,prescribed", omega, m + 1, label, hz, -1.0, 1.5);
        }
    }
    table.close();
    PlotArgs args = campbell_of(file, scratch.dir);
    args.max_hz = "50";  // above every line (the default cutoff, 1.1 x the lowest line's 3 Hz, leaves out the others)
    std::string script = plot_script(args);
    std::vector<std::string> titles;
    for (const DrawnLine& l : drawn_lines(script)) titles.push_back(l.title);
    CHECK(titles == std::vector<std::string>{"edge 2", "flap 3", "flap 2"});  // by their first row drawn
    CHECK(script.find("$critical") == std::string::npos);
    // flap 2's line starts where it oscillates: its row at rest, 0 Hz, is not in its datablock
    CHECK(gnuplot_prints(scratch.dir, script, "print $mode1\nprint $mode3") == "0,3\n5,3\n10,3\n\n5,4\n10,4\n\n");
    // --modes 2: the two lowest that oscillate
    args.modes = "2";
    titles.clear();
    for (const DrawnLine& l : drawn_lines(plot_script(args))) titles.push_back(l.title);
    CHECK(titles == std::vector<std::string>{"edge 2", "flap 2"});
    // a mode that begins overdamped (labelled so, as a table that names the kind labels it) and oscillates later:
    // not among the default kinds; --kinds overdamped draws it where it oscillates
    args.modes.clear();
    std::ofstream(file, std::ios::app) << "fem,8,0,first,prescribed,0,6,overdamped,0,0,0,-1,1,1,overdamped 1,nan\n"
                                          "fem,8,0,first,prescribed,5,6,flap,12.6,2,1,-1,13,0.3,overdamped 1,0.9\n"
                                          "fem,8,0,first,prescribed,10,6,flap,18.8,3,1,-1,19,0.3,overdamped 1,0.9\n";
    titles.clear();
    for (const DrawnLine& l : drawn_lines(plot_script(args))) titles.push_back(l.title);
    CHECK(titles == std::vector<std::string>{"edge 2", "flap 3", "flap 2"});
    args.kinds = "overdamped";
    script = plot_script(args);
    titles.clear();
    for (const DrawnLine& l : drawn_lines(script)) titles.push_back(l.title);
    CHECK(titles == std::vector<std::string>{"overdamped 1"});
    CHECK(gnuplot_prints(scratch.dir, script, "print $mode1") == "5,2\n10,3\n\n");
    args.kinds.clear();
    // a file of overdamped rows alone has nothing to draw
    args.modes.clear();
    args.kinds = "edge";
    std::ofstream(file) << "method,ny,nx,order,drive,omega,mode,kind,rad_s,hz,dimensionless,growth,undamped_rad_s,"
                           "damping_ratio,label,mac\nfem,8,0,first,prescribed,0,1,edge,0,0,0,-1,1,1.5,edge 1,1\n";
    CHECK_THROWS_WITH(plot_script(args), Catch::Contains("damped-modes.csv: expected rows of kind 'edge' with a "
                                                         "frequency above 0"));
}

TEST_CASE("campbell: every line its family's shade by mode number, the per-rev lines named at their ends", "[plot]")
{
    ScratchDir scratch;
    const fs::path file = scratch.dir / "many-modes.csv";
    std::ofstream table(file);
    table << modes_csv_header;
    constexpr std::size_t modes = 60;
    for (const int omega : {0, 30})
        for (std::size_t m = 1; m <= modes; ++m)
            table << modes_csv_row("fem,8,0,first,prescribed", omega, m, "bending " + std::to_string(m),
                                   static_cast<double>(m), 0.0, 0.0);
    table.close();
    PlotArgs args;
    args.kind = "campbell";
    args.files = {file.string()};
    args.prefix = (scratch.dir / "campbell").string();
    args.max_hz = "100";
    const std::string script = plot_script(args);
    const std::vector<DrawnLine> lines = drawn_lines(script);
    REQUIRE(lines.size() == modes);
    std::set<std::string> colours;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const std::string& colour = lines[i].colour;
        colours.insert(colour);
        // a green (a planar beam's in-plane bending, as a blade's edge): neither the per-rev lines' greys nor the red
        // of the critical speeds and the instabilities
        REQUIRE(colour.size() == 7);
        const unsigned rgb = std::stoul(colour.substr(1), nullptr, 16);
        const unsigned r = rgb >> 16, g = rgb >> 8 & 0xff, b = rgb & 0xff;
        CHECK((g > r && g > b));
        CHECK(std::max({r, g, b}) - std::min({r, g, b}) > 40);  // not a grey
        if (i > 0) CHECK(colour != lines[i - 1].colour);       // the next mode its next shade
    }
    CHECK(colours.size() == 5);  // five shades, darkest first, again from mode 6
    CHECK(lines[5].colour == lines[0].colour);
    // the per-rev lines 1P to 6P by default, thin, solid and grey, each named once at its end
    for (int k = 1; k <= 6; ++k) {
        INFO(k);
        const std::string per_rev = (k == 1 ? "" : std::to_string(k) + "*") + "x/(2*pi) with lines ";
        CHECK(script.find("  " + per_rev + "lw 1 dt solid lc rgb '#909090' notitle") != std::string::npos);
        CHECK(count(script, "set label '" + std::to_string(k) + "P' at ") == 1);
    }
    CHECK(script.find("7*x/(2*pi)") == std::string::npos);
    // 1P ends at the highest rate inside the figure (30 / 2 pi Hz, far below the modes' 60 Hz)
    CHECK(script.find("set label '1P' at 30," + shortest(30 / (2 * M_PI)) + " right") != std::string::npos);
}

namespace {

/// The rows "x,y" of what gnuplot prints for one datablock, as numbers.
std::vector<std::pair<double, double>> printed_points(const std::string& printed)
{
    std::vector<std::pair<double, double>> points;
    std::istringstream in(printed);
    for (std::string line; std::getline(in, line) && !line.empty();) {
        const std::size_t comma = line.find(',');
        points.emplace_back(std::stod(line.substr(0, comma)), std::stod(line.substr(comma + 1)));
    }
    return points;
}

/// The points of an inline datablock NAME << EOD ... EOD of a script.
std::vector<std::pair<double, double>> inline_points(const std::string& script, const std::string& name)
{
    const std::size_t start = script.find(name + " << EOD\n");
    if (start == std::string::npos) return {};
    const std::size_t from = start + name.size() + 8;
    return printed_points(script.substr(from, script.find("EOD\n", from) - from));
}

}  // namespace

TEST_CASE("campbell as rotor engineers draw it: rpm, per-rev lines, cutoff, damping panel, instabilities, whirl",
          "[plot]")
{
    ScratchDir scratch;
    // A rotor's synthetic table at 0, 1, 2 and 3 revolutions per second (0, 2 pi, 4 pi, 6 pi rad/s): two flap modes
    // (the second losing its damping and unstable at the highest rate), an edge mode split into its backward and
    // forward whirl (3 Hz at rest, -/+ 0.05 Hz per rad/s), and a flap mode at 40 Hz above the default cutoff.
    const fs::path file = scratch.dir / "rotor-modes.csv";
    std::ofstream table(file);
    table << modes_csv_header;
    const double revs[] = {0.0, 2.0 * M_PI, 4.0 * M_PI, 6.0 * M_PI};
    const auto flap1 = [](double w) { return 1.0 + 0.1 * w; };
    const auto flap2 = [](double w) { return 5.0 + 0.05 * w; };
    for (const double w : revs) {
        const bool last = w == revs[3];
        table << modes_csv_row("amm,8,0,first,prescribed", w, 1, "flap 1", flap1(w), -0.1, 0.02, 17)
              << modes_csv_row("amm,8,0,first,prescribed", w, 2, "BW edge 1", 3.0 - 0.05 * w, -0.1, 0.01, 17)
              << modes_csv_row("amm,8,0,first,prescribed", w, 3, "FW edge 1", 3.0 + 0.05 * w, -0.1, 0.01, 17)
              << modes_csv_row("amm,8,0,first,prescribed", w, 4, "flap 2", flap2(w), last ? 0.2 : -0.1,
                               last ? -0.005 : 0.01, 17)
              << modes_csv_row("amm,8,0,first,prescribed", w, 5, "flap 3", 40.0, -0.1, 0.01, 17);
    }
    // and at the highest rate a divergence: a real root that grows (0 Hz, damping ratio -1)
    table << modes_csv_row("amm,8,0,first,prescribed", revs[3], 6, "overdamped 1", 0.0, 0.3, -1.0, 17);
    table.close();
    PlotArgs args;
    args.kind = "campbell";
    args.files = {file.string()};
    args.prefix = (scratch.dir / "campbell").string();
    args.spin_unit = "rpm";
    args.blades = "3";
    args.operating_range = "150:180";
    const std::string script = plot_script(args);
    const double omega_max = revs[3], rpm_max = omega_max * 60.0 / (2.0 * M_PI);  // 180 rpm

    // Only the modes below the cutoff: 1.1 x 6P at the highest rate, 19.8 Hz; flap 3 (40 Hz) left out
    std::vector<std::string> titles;
    for (const DrawnLine& l : drawn_lines(script)) titles.push_back(l.title);
    CHECK(titles == std::vector<std::string>{"flap 1", "BW edge 1", "FW edge 1", "flap 2"});
    const std::size_t yrange = script.find("  set yrange [0:");
    REQUIRE(yrange != std::string::npos);
    CHECK(std::stod(script.substr(yrange + 16)) == Approx(1.1 * 6.0 * omega_max / (2.0 * M_PI)).epsilon(1e-12));
    CHECK(script.find("flap 3") == std::string::npos);

    // rpm: 2 pi rad/s is 60 rpm on the spin axis, in the lines' rows, the axis's range and label
    const std::string printed = gnuplot_prints(scratch.dir, script, "print $mode1\nprint $zeta4");
    const std::size_t gap = printed.find("\n\n");
    const auto flap1_rows = printed_points(printed.substr(0, gap + 1));
    REQUIRE(flap1_rows.size() == 4);
    for (std::size_t i = 0; i < 4; ++i) {
        CHECK(flap1_rows[i].first == Approx(60.0 * static_cast<double>(i)).epsilon(1e-9));
        CHECK(flap1_rows[i].second == Approx(flap1(revs[i])).epsilon(1e-5));
    }
    const std::size_t xrange = script.find("  set xrange [0:");
    REQUIRE(xrange != std::string::npos);
    CHECK(std::stod(script.substr(xrange + 16)) == Approx(rpm_max).epsilon(1e-12));
    CHECK(script.find("set xlabel 'hub spin rate Omega (rpm)'") != std::string::npos);

    // The per-rev lines 1P to 6P (f = k rpm / 60 Hz), each named at its end, 3P and 6P heavier (3 blades)
    for (int k = 1; k <= 6; ++k) {
        INFO(k);
        const std::string per_rev = "  " + (k == 1 ? std::string() : std::to_string(k) + "*") + "x/60 with lines lw ";
        CHECK(script.find(per_rev + (k % 3 == 0 ? "2.5" : "1") + " ") != std::string::npos);
        CHECK(count(script, "set label '" + std::to_string(k) + "P' at ") == 1);
    }
    CHECK(script.find("7*x/60") == std::string::npos);
    CHECK(script.find("title '3P and its multiples (3 blades)'") != std::string::npos);
    // 1P named at its end: 180 rpm, 3 Hz
    const std::size_t label = script.find("set label '1P' at ");
    REQUIRE(label != std::string::npos);
    const auto one_p = printed_points(script.substr(label + 18, script.find(' ', label + 18) - label - 18));
    REQUIRE(one_p.size() == 1);
    CHECK(one_p[0].first == Approx(rpm_max).epsilon(1e-12));
    CHECK(one_p[0].second == Approx(omega_max / (2.0 * M_PI)).epsilon(1e-12));
    // flap 1 meets 1P where 1 + 0.1 omega = omega / 2 pi: marked in rpm
    const double meets = 1.0 / (1.0 / (2.0 * M_PI) - 0.1);
    bool marked = false;
    for (const auto& [x, y] : inline_points(script, "$critical"))
        marked = marked || (std::abs(x - meets * 60.0 / (2.0 * M_PI)) < 1e-9 && std::abs(y - meets / (2.0 * M_PI)) < 1e-9);
    CHECK(marked);

    // The damping panel below: its own margins, the damping ratios in %, the key of markers in its margin
    const std::size_t lower = script.find("  set tmargin at screen 0.33\n");
    REQUIRE(lower != std::string::npos);
    CHECK(script.find("set ylabel 'damping ratio zeta (%)'", lower) != std::string::npos);
    CHECK(script.find("plot $zeta1 using 1:2", lower) != std::string::npos);
    const auto flap2_zeta = printed_points(printed.substr(gap + 2));
    REQUIRE(flap2_zeta.size() == 4);
    CHECK(flap2_zeta[0].second == Approx(1.0));    // 0.01
    CHECK(flap2_zeta[3].second == Approx(-0.5));   // -0.005
    CHECK(flap2_zeta[3].first == Approx(rpm_max));

    // The unstable point: flap 2 at 180 rpm, a cross in both panels, and its label says so; the divergence a cross at
    // 0 Hz, in the upper panel alone
    const auto unstable = inline_points(script, "$unstable");
    REQUIRE(unstable.size() == 2);
    CHECK(unstable[0].first == Approx(rpm_max).epsilon(1e-12));
    CHECK(unstable[0].second == Approx(flap2(omega_max)).epsilon(1e-12));
    CHECK(unstable[1].first == Approx(rpm_max).epsilon(1e-12));
    CHECK(unstable[1].second == 0.0);
    CHECK(inline_points(script, "$unstable_zeta") == std::vector<std::pair<double, double>>{{unstable[0].first, -0.5}});
    CHECK(script.find("$unstable using 1:2 with points pt 2 ") != std::string::npos);
    CHECK(script.find("$unstable_zeta using 1:2 with points pt 2 ", lower) != std::string::npos);
    CHECK(count(script, "set label 'flap 2 (unstable)' at graph 1") == 1);
    CHECK(count(script, "set label 'flap 1' at graph 1") == 1);

    // The operating range shaded across both panels, in the key
    CHECK(script.find("set object 1 rect from 150, graph 0 to 180, graph 1 ") != std::string::npos);
    CHECK(script.find("title 'operating range'", lower) != std::string::npos);

    // Whirl: BW dashed, FW dotted, a blade's own mode solid; one edge mode's two whirls in one shade, green, the flap
    // modes in blues
    std::map<std::string, std::string> look, colour;
    for (const DrawnLine& l : drawn_lines(script)) {
        const std::size_t at = script.find("  plot " + l.block + " using") != std::string::npos
                                   ? script.find("  plot " + l.block + " using")
                                   : script.find("       " + l.block + " using");
        look[l.title] = script.substr(at, script.find('\n', at) - at);
        colour[l.title] = l.colour;
    }
    CHECK(look["BW edge 1"].find(" dt (12,6) ") != std::string::npos);
    CHECK(look["FW edge 1"].find(" dt (2,4) ") != std::string::npos);
    CHECK(look["flap 1"].find(" dt solid ") != std::string::npos);
    CHECK(colour["BW edge 1"] == colour["FW edge 1"]);
    CHECK(colour["flap 1"] != colour["flap 2"]);
    const auto dominant = [](const std::string& hex) {
        const unsigned rgb = std::stoul(hex.substr(1), nullptr, 16);
        const unsigned r = rgb >> 16, g = rgb >> 8 & 0xff, b = rgb & 0xff;
        return b > r && b > g ? 'b' : g > r && g > b ? 'g' : '?';
    };
    CHECK(dominant(colour["flap 1"]) == 'b');
    CHECK(dominant(colour["flap 2"]) == 'b');
    CHECK(dominant(colour["BW edge 1"]) == 'g');
    CHECK(script.find("title 'backward whirl (BW)'") != std::string::npos);
    CHECK(script.find("title 'forward whirl (FW)'") != std::string::npos);
    // --kinds edge chooses both whirls of the edge mode
    PlotArgs edge = args;
    edge.kinds = "edge";
    titles.clear();
    for (const DrawnLine& l : drawn_lines(plot_script(edge))) titles.push_back(l.title);
    CHECK(titles == std::vector<std::string>{"BW edge 1", "FW edge 1"});

    // --max-frequency 4: only the lines with a point at or below 4 Hz (flap 2 starts at 5 Hz)
    PlotArgs low = args;
    low.max_hz = "4";
    titles.clear();
    for (const DrawnLine& l : drawn_lines(plot_script(low))) titles.push_back(l.title);
    CHECK(titles == std::vector<std::string>{"flap 1", "BW edge 1", "FW edge 1"});

    // a cutoff below every mode leaves nothing to draw: refused, naming the lowest
    low.max_hz = "0.5";
    CHECK_THROWS_WITH(plot_script(low), "--max-frequency: expected a frequency at or above the lowest mode drawn (" +
                                            shortest(flap1(0.0)) + " Hz), got 0.5");

    // rad/s, the default: the rows as the table has them
    PlotArgs rad = args;
    rad.spin_unit.clear();
    rad.operating_range.clear();
    const std::string rad_script = plot_script(rad);
    CHECK(rad_script.find("set xlabel 'hub spin rate Omega (rad/s)'") != std::string::npos);
    CHECK(inline_points(rad_script, "$unstable")[0].first == Approx(omega_max).epsilon(1e-12));
    // a divergence alone: its cross above, nothing below
    PlotArgs diverging = rad;
    diverging.kinds = "edge";
    const std::string diverging_script = plot_script(diverging);
    CHECK(inline_points(diverging_script, "$unstable") ==
          std::vector<std::pair<double, double>>{{inline_points(rad_script, "$unstable")[1]}});
    CHECK(diverging_script.find("$unstable_zeta") == std::string::npos);
    CHECK(diverging_script.find("title 'unstable'") != std::string::npos);
    CHECK(rad_script.find("  3*x/(2*pi) with lines lw 2.5 ") != std::string::npos);

    // Bad values name the option and what it takes
    PlotArgs bad = args;
    bad.spin_unit = "hz";
    CHECK_THROWS_WITH(plot_script(bad), "--spin-unit: expected rpm or rad/s, got hz");
    bad = args;
    bad.operating_range = "180:150";
    CHECK_THROWS_WITH(plot_script(bad), "--operating-range: expected LO:HI, two spin rates >= 0 (rpm, the "
                                        "--spin-unit) with LO < HI, got 180:150");
    bad.operating_range = "150";
    CHECK_THROWS_WITH(plot_script(bad), Catch::StartsWith("--operating-range: expected LO:HI"));
    bad = args;
    bad.blades = "0";
    CHECK_THROWS_WITH(plot_script(bad), "--blades: expected an integer from 1 to 1000, got 0");
    PlotArgs tip;
    tip.kind = "tip";
    tip.files = {fixture("run_amm.csv")};
    tip.prefix = args.prefix;
    tip.spin_unit = "rpm";
    CHECK_THROWS_WITH(plot_script(tip),
                      "--spin-unit: expected no spin-unit for kind tip (only kind campbell draws them), got rpm");
    // the figure draws
    CHECK(draw_plot(args).empty());
    CHECK(fs::file_size(args.prefix + ".png") > 0);
}

TEST_CASE("a long file name is cut in its middle in the legend and the title, so the axes keep their room", "[plot]")
{
    ScratchDir scratch;
    // a tabulated blade's variant name, 190 characters, as a run's file name
    std::string stem = "fem_nx0_ny8_nz8_nt2_prescribed_first_profile1000";
    while (stem.size() < 190) {
        stem += 'x';  // appended piece by piece: GCC 12 warns falsely (-Wrestrict) about "x" + string
        stem += std::to_string(stem.size());
    }
    stem.resize(190);
    fs::copy_file(fixture("run_amm.csv"), scratch.dir / (stem + ".csv"));
    fs::copy_file(fixture("run_fem.csv"), scratch.dir / (stem + "-b.csv"));
    PlotArgs args;
    args.kind = "tip";
    args.files = {(scratch.dir / (stem + ".csv")).string(), (scratch.dir / (stem + "-b.csv")).string()};
    args.prefix = (scratch.dir / "tip").string();
    const std::string script = plot_script(args);
    // the legend entries: 60 characters, the start and the end of the name kept
    const std::string first = stem.substr(0, 28) + "..." + stem.substr(190 - 29);
    CHECK(first.size() == 60);
    CHECK(script.find("title '" + first + "' noenhanced") != std::string::npos);
    CHECK(script.find("title '" + stem.substr(0, 28) + "..." + (stem + "-b").substr(192 - 29) + "' noenhanced") !=
          std::string::npos);
    // the title: the kind's, then the shared name cut to 80 characters
    const std::string title = "Tip deflection, " + stem.substr(0, 38) + "..." + stem.substr(190 - 39);
    CHECK(script.find("set title '" + title + "' noenhanced") != std::string::npos);
    // so the panels' right edge stays where a 60-character entry puts it
    CHECK(script.find("set rmargin at screen 0.550") != std::string::npos);
}
