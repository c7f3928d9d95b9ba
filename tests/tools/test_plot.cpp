// hubbeam plot's scripts run through gnuplot: the rows each figure draws (a Campbell line per bending mode and
// variant, never an axial mode; the bending moment at the time closest to --time, else the last), and the string
// expressions that carry file names and labels with quotes into a script.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "plot.hpp"

using namespace hubbeam;
namespace fs = std::filesystem;

namespace {

std::string fixture(const char* name) { return std::string(HUBBEAM_SOURCE_DIR) + "/tests/plots/" + name; }

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
    // a legend entry per line: its variant and its tracked label
    CHECK(script.find("title 'amm Ny = 4, bending 1' noenhanced") != std::string::npos);
    CHECK(script.find("title 'fem Ny = 4, bending 2' noenhanced") != std::string::npos);
    // amm's and fem's lines coincide to the eye: each its own open marker, amm's larger and wider under fem's
    CHECK(script.find("$mode2 using 1:2 smooth unique with linespoints lw 2.5 lc rgb '") != std::string::npos);
    CHECK(script.find("$mode4 using 1:2 smooth unique with linespoints lw 2.1 lc rgb '") != std::string::npos);
    CHECK(script.find("dt 1 pt 6 ps 1.60 title 'amm Ny = 4, bending 2'") != std::string::npos);
    CHECK(script.find("dt 1 pt 4 ps 1.35 title 'fem Ny = 4, bending 2'") != std::string::npos);
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
    CHECK_THROWS_WITH(plot_script(args), "--harmonics: expected a comma-separated list of integers from 1 to 1000, got 0");
    // A modes CSV of an older hubbeam, without the label column: a line per frequency number of kind bending.
    args.harmonics.clear();
    args.files = {fixture("modes_untracked.csv")};
    CHECK(gnuplot_prints(scratch.dir, plot_script(args), "print $mode1\nprint $mode2") ==
          "0,0.46335\n4,0.53201\n\n0,2.9038\n4,3.075\n\n");
}

namespace {

/// What the plot command of a script draws: per element of the Campbell lines ($modeN), its datablock, its
/// colour and its legend title.
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
        const std::size_t colour = element.find("lc rgb '") + 8, title = element.find("title '") + 7;
        lines.push_back({element.substr(0, element.find(' ')),
                         element.substr(colour, element.find('\'', colour) - colour),
                         element.substr(title, element.find('\'', title) - title)});
    }
    return lines;
}

}  // namespace

TEST_CASE("campbell: --modes, --kinds and --max-hz choose the lines - each its own colour and its label", "[plot]")
{
    ScratchDir scratch;
    // A blade's Campbell table: one variant, bending lines at 10, 300, 900 and 1800 Hz at rest, an axial line and a
    // hub line. Only bending 1 meets 1P (f = omega / 2 pi) between the rates: 10 + 0.05 omega = omega / 2 pi.
    const fs::path file = scratch.dir / "blade-modes.csv";
    std::ofstream table(file);
    table << "method,ny,nx,order,drive,omega,mode,kind,rad_s,hz,dimensionless,growth,undamped_rad_s,damping_ratio,"
             "label,mac\n";
    const std::vector<std::pair<std::string, double>> at_rest = {
        {"hub 1", 0.5}, {"bending 1", 10}, {"bending 2", 300}, {"bending 3", 900}, {"axial 1", 1200}, {"bending 4", 1800}};
    for (const double omega : {0.0, 100.0, 200.0})
        for (std::size_t m = 0; m < at_rest.size(); ++m) {
            const auto& [label, hz] = at_rest[m];
            const double f = hz + 0.05 * omega;
            table << "amm,8,4,first,torque," << omega << ',' << m + 1 << ',' << label.substr(0, label.find(' ')) << ','
                  << 2 * M_PI * f << ',' << f << ",1,0," << 2 * M_PI * f << ",0," << label << ",1\n";
        }
    table.close();
    PlotArgs args;
    args.kind = "campbell";
    args.files = {file.string()};
    args.prefix = (scratch.dir / "campbell").string();
    args.harmonics = "1";

    // By default every bending line: a colour each, its label the legend entry, the variant in the title
    std::string script = plot_script(args);
    std::vector<DrawnLine> lines = drawn_lines(script);
    REQUIRE(lines.size() == 4);
    std::set<std::string> colours;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        CHECK(lines[i].title == "bending " + std::to_string(i + 1));
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
    CHECK_THROWS_WITH(plot_script(args), "--max-hz: expected a frequency > 0 (Hz), got 0");
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
    CHECK_THROWS_WITH(plot_script(tip), "--max-hz: expected no max-hz for kind tip (only kind campbell draws them), got 50");
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

/// How many times text occurs in s.
std::size_t count(const std::string& s, const std::string& text)
{
    std::size_t n = 0;
    for (std::size_t at = s.find(text); at != std::string::npos; at = s.find(text, at + 1)) ++n;
    return n;
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
