// hubbeam plot's scripts run through gnuplot: the rows each figure draws (a Campbell line per bending mode and
// variant, never an axial mode; the bending moment at the time closest to --time, else the last), and the string
// expressions that carry file names and labels with quotes into a script.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

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
    // a legend entry per method, not per mode
    CHECK(script.find("title 'amm Ny = 4' noenhanced") != std::string::npos);
    CHECK(script.find("title 'fem Ny = 4' noenhanced") != std::string::npos);
    CHECK(script.find("$mode2 using 1:2 with linespoints lw 2 lc 1 dt 1 pt 7 ps 0.8 notitle") != std::string::npos);
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
        CHECK(plot_script(args).find("set title 'Bending moment along the beam at t = 1 s'") != std::string::npos);
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
