// hubbeam modes' CSV files read as a user reads them, by the header's names, each column checked by what it means:
// the modes (-o) and the critical speeds (--critical), where a tracked mode's frequency is n times the spin rate;
// the CLI's table, CSVs and the library's core agree on a damped blade; and the files of every command that prints
// and writes are whole whatever becomes of standard output.
#include <catch2/catch.hpp>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <hubbeam/csv_columns.hpp>
#include <hubbeam/modes_table.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/shortest.hpp>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "modes.hpp"
#include "temp_folder.hpp"

using namespace hubbeam;

namespace {

/// A CSV's rows as maps from the header's names to the fields.
std::vector<std::map<std::string, std::string>> read_csv(const std::filesystem::path& p)
{
    std::ifstream in(p);
    std::string line;
    REQUIRE(std::getline(in, line));
    std::vector<std::string> names;
    for (std::istringstream h(line); std::getline(h, line, ',');) names.push_back(line);
    std::vector<std::map<std::string, std::string>> rows;
    while (std::getline(in, line)) {
        std::map<std::string, std::string> row;
        std::istringstream fields(line);
        for (const std::string& name : names) {
            std::string f;
            REQUIRE(std::getline(fields, f, ','));
            row[name] = f;
        }
        rows.push_back(row);
    }
    return rows;
}

}  // namespace

TEST_CASE("modes' CSV columns hold what their names say, the critical speeds' among them", "[modes][campbell]")
{
    // The paper's beam with two axial coordinates to 450 rad/s (cases/spinup_omega4.toml --nx 2), where bending and
    // axial lines cross the excitation lines of 1P, 2P and 3P (their frequencies: test_campbell.cpp's oracle).
    const auto folder =
        std::filesystem::temp_directory_path() / ("hubbeam-test-modes-csv-" + std::to_string(::getpid()));
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    const Scene scene = load_scene(HUBBEAM_SOURCE_DIR "/cases/spinup_omega4.toml", {{"discretization.nx", "2"}});
    ModesArgs args;
    args.omega = "0:450:50";
    args.output = (folder / "modes.csv").string();
    args.critical = (folder / "critical.csv").string();
    args.harmonics = "1,2,3";
    std::ostringstream out;
    run_modes(scene, parse_modes_options(args, scene), out);
    const auto modes = read_csv(args.output), critical = read_csv(args.critical);
    std::filesystem::remove_all(folder);

    // The modes: hz is rad_s / 2 pi, undamped the same (no damping), the label names the kind, the modes of a
    // rate in increasing frequency, the rates those asked for.
    std::map<std::string, std::map<double, double>> lines;  // label -> omega -> rad_s
    double previous_omega = -1.0, previous_rad_s = 0.0;
    for (const auto& r : modes) {
        const double omega = std::stod(r.at("omega")), rad_s = std::stod(r.at("rad_s"));
        INFO("omega " << omega << ", mode " << r.at("mode") << ", " << r.at("label"));
        CHECK(std::fmod(omega, 50.0) == 0.0);
        CHECK(std::stod(r.at("hz")) == Approx(rad_s / (2.0 * M_PI)).epsilon(1e-12));
        CHECK(std::stod(r.at("undamped_rad_s")) == Approx(rad_s).epsilon(1e-12));
        CHECK(r.at("label").rfind(r.at("kind"), 0) == 0);
        CHECK((r.at("kind") == "bending" || r.at("kind") == "axial"));
        CHECK(std::stoi(r.at("ny")) == 4);
        CHECK(std::stoi(r.at("nx")) == 2);
        CHECK(r.at("method") == "amm");
        if (omega == previous_omega) CHECK(rad_s >= previous_rad_s);
        previous_omega = omega;
        previous_rad_s = rad_s;
        lines[r.at("label")][omega] = rad_s;
    }
    REQUIRE(modes.size() == 10 * 6);  // every mode of the 6 coordinates at each of the 10 rates

    // The critical speeds: where the tracked line's frequency is harmonic x the spin rate, between the line's
    // values at the grid rates around it; one for each change of sign of rad_s - n omega along a line.
    std::multiset<std::pair<std::string, int>> expected, found;
    for (const auto& [label, line] : lines)
        for (int n = 1; n <= 3; ++n)
            for (auto a = line.begin(), b = std::next(a); b != line.end(); ++a, ++b)
                if ((a->second - n * a->first) * (b->second - n * b->first) < 0.0) expected.insert({label, n});
    CHECK(!expected.empty());
    for (const auto& r : critical) {
        const double omega = std::stod(r.at("omega")), rad_s = std::stod(r.at("rad_s"));
        const int n = std::stoi(r.at("harmonic"));
        INFO(r.at("label") << " meets " << n << "P at " << omega << " rad/s, " << rad_s << " rad/s");
        found.insert({r.at("label"), n});
        CHECK(rad_s == Approx(n * omega).epsilon(1e-9));
        CHECK(std::stod(r.at("hz")) == Approx(rad_s / (2.0 * M_PI)).epsilon(1e-12));
        CHECK((r.at("method") == "amm" && r.at("ny") == "4" && r.at("nx") == "2" && r.at("drive") == "prescribed"));
        REQUIRE(lines.count(r.at("label")) == 1);
        const std::map<double, double>& line = lines.at(r.at("label"));
        const auto above = line.upper_bound(omega);
        REQUIRE(above != line.end());
        REQUIRE(above != line.begin());
        const auto below = std::prev(above);
        CHECK((below->second - n * below->first) * (above->second - n * above->first) < 0.0);
        CHECK(std::min(below->second, above->second) <= rad_s);
        CHECK(rad_s <= std::max(below->second, above->second));
    }
    CHECK(found == expected);
}

TEST_CASE("hubbeam modes' CSVs are the modes table's lines, variant by variant, each cell under its column's name",
          "[modes][campbell]")
{
    // Two variants (two methods) of the paper's beam to 300 rad/s, where its lines cross 1P, 2P and 3P: what the
    // command writes is the library's one table, whose cells stand under the names of what they hold.
    const TempFolder folder("modes-table");
    const Scene scene = load_scene(HUBBEAM_SOURCE_DIR "/cases/spinup_omega4.toml");
    ModesArgs args;
    args.omega = "0:300:50";
    args.methods = "amm,bim";
    args.output = (folder.path / "modes.csv").string();
    args.critical = (folder.path / "critical.csv").string();
    args.harmonics = "1,2,3";
    args.quiet = true;
    const ModesOptions options = parse_modes_options(args, scene);
    std::ostringstream out;
    run_modes(scene, options, out);

    std::string modes = std::string(modes_header()) + "\n", critical = std::string(critical_header()) + "\n";
    const CsvColumns m(args.output, modes_header()), c(args.critical, critical_header());
    std::vector<std::string> methods;
    modes_table(scene, options, [&](const ModesBlock& block) {
        methods.push_back(to_string(block.key.method));
        for (const SpinMode& r : block.modes) {
            const std::string line = modes_line(block, r);
            modes += line + "\n";
            const std::vector<std::string> f = csv_fields(line);
            CHECK(f[m.at("method")] == methods.back());
            CHECK(f[m.at("omega")] == shortest(r.omega));
            CHECK(f[m.at("mode")] == std::to_string(r.number));
            CHECK(f[m.at("rad_s")] == shortest(r.mode.rad_s));
            CHECK(f[m.at("hz")] == shortest(r.mode.rad_s / (2.0 * M_PI)));
            CHECK(f[m.at("dimensionless")] == shortest(r.mode.rad_s / frequency_unit(scene.parameters)));
            CHECK(f[m.at("label")] == r.label);
        }
        for (const CriticalSpeed& speed : block.critical) {
            const std::string line = critical_line(block, speed);
            critical += line + "\n";
            const std::vector<std::string> f = csv_fields(line);
            CHECK(f[c.at("harmonic")] == std::to_string(speed.harmonic));
            CHECK(f[c.at("omega")] == shortest(speed.omega));
            CHECK(f[c.at("hz")] == shortest(speed.rad_s / (2.0 * M_PI)));
        }
    });
    CHECK(methods == std::vector<std::string>{"amm", "bim"});
    CHECK(std::count(critical.begin(), critical.end(), '\n') > 2);  // crossings of both variants' lines
    const auto text = [](const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    CHECK(text(args.output) == modes);
    CHECK(text(args.critical) == critical);
}

TEST_CASE("a damped blade's printed critical speeds, its --critical CSV and the core's are the same five",
          "[modes][campbell]")
{
    // cases/helicopter_blade.toml from rest to 30 rad/s: its overdamped modes (rows of kind overdamped) meet no
    // excitation line; what hubbeam modes prints and writes is the core's (modes_block, which hubbeam.modes calls).
    const TempFolder folder("modes-blade");
    const Scene scene = load_scene(HUBBEAM_SOURCE_DIR "/cases/helicopter_blade.toml");
    ModesArgs args;
    args.omega = "0:30:5";
    args.output = (folder.path / "modes.csv").string();
    args.critical = (folder.path / "critical.csv").string();
    const ModesOptions options = parse_modes_options(args, scene);
    std::ostringstream out;
    run_modes(scene, options, out);
    INFO(out.str());
    std::vector<std::string> core;  // the core's critical speeds as CSV lines
    int overdamped_rows = 0;
    modes_table(scene, options, [&](const ModesBlock& block) {
        for (const CriticalSpeed& c : block.critical) core.push_back(critical_line(block, c));
        for (const SpinMode& r : block.modes) overdamped_rows += r.mode.kind == "overdamped";
    });
    CHECK(core.size() == 5);
    const auto critical = read_csv(args.critical);
    REQUIRE(critical.size() == core.size());
    std::ifstream lines(args.critical);
    std::string line;
    std::getline(lines, line);  // the header
    for (const std::string& expected : core) {
        REQUIRE(std::getline(lines, line));
        CHECK(line == expected);
    }
    // Printed: one line per critical speed, none at rest, each as the CSV has it.
    const std::string text = out.str();
    CHECK(text.find("Omega = 0 ") == std::string::npos);
    std::size_t printed = 0;
    for (std::size_t at = text.find("P at Omega = "); at != std::string::npos; at = text.find("P at Omega = ", at + 1))
        ++printed;
    CHECK(printed == core.size());
    for (const auto& c : critical)
        CHECK(text.find(c.at("label") + std::string(13 - c.at("label").size(), ' ') + " meets   " + c.at("harmonic") +
                        "P at Omega = ") != std::string::npos);
    // The modes CSV's overdamped rows: frequency 0, damping ratio 1, as the core's.
    int csv_overdamped = 0;
    for (const auto& r : read_csv(args.output))
        if (r.at("kind") == "overdamped") {
            ++csv_overdamped;
            CHECK(r.at("rad_s") == "0");
            CHECK(r.at("damping_ratio") == "1");
            CHECK(std::stod(r.at("growth")) < 0.0);
        }
    CHECK(csv_overdamped == overdamped_rows);
    CHECK(csv_overdamped > 0);
}

namespace {

/// What a hubbeam command line did: its exit code (128 + the signal that ended it, if one did) and its stderr.
struct Ended {
    int code;
    std::string stderr_text;
};

/// Runs the hubbeam program with args in folder, its standard output the writing end of a pipe whose reader has
/// gone (a `| head` that has stopped reading) or the file stdout_file (/dev/full), SIGPIPE's action the default.
Ended run_hubbeam(const std::filesystem::path& folder, const std::vector<std::string>& args,
                  const char* stdout_file = nullptr)
{
    int ends[2];
    REQUIRE(::pipe(ends) == 0);
    ::close(ends[0]);  // the reader gone before the first write
    const std::string errors = (folder / "stderr.txt").string();
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        const int out = stdout_file ? ::open(stdout_file, O_WRONLY) : ends[1];
        const int err = ::open(errors.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        if (out < 0 || err < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0 || ::chdir(folder.c_str()) != 0) ::_exit(99);
        std::signal(SIGPIPE, SIG_DFL);
        std::vector<char*> argv = {const_cast<char*>(HUBBEAM_PROGRAM)};
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(argv[0], argv.data());
        ::_exit(98);
    }
    ::close(ends[1]);
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    std::ifstream in(errors);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    return {WIFSIGNALED(status) ? 128 + WTERMSIG(status) : WEXITSTATUS(status), text};
}

/// The text of a file, empty if there is none.
std::string file_text(const std::filesystem::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST_CASE("a standard output closed by its reader costs no file: modes, run, linearize, kernels", "[modes][cli]")
{
    const TempFolder folder("closed-stdout");
    const std::string cases = HUBBEAM_SOURCE_DIR "/cases/";
    SECTION("modes: a table of 41 rates, far longer than a pipe's buffer, and both CSVs")
    {
        const std::vector<std::string> args = {"modes", cases + "spinup_omega4.toml", "--omega", "0:20:0.5",
                                               "-o", "m.csv", "--critical", "c.csv"};
        const Ended ended = run_hubbeam(folder.path, args);
        INFO(ended.stderr_text);
        CHECK(ended.code == 0);
        CHECK(ended.stderr_text.empty());
        // The files are those of the same command whose output is read to its end.
        const std::string modes = file_text(folder.path / "m.csv"), critical = file_text(folder.path / "c.csv");
        CHECK(std::count(modes.begin(), modes.end(), '\n') == 1 + 41 * 8);
        CHECK(!file_text(folder.path / "m.csv.hubbeam.json").empty());
        const Scene scene = load_scene(cases + "spinup_omega4.toml");
        ModesArgs again;
        again.omega = "0:20:0.5";
        again.output = (folder.path / "again.csv").string();
        again.critical = (folder.path / "again-critical.csv").string();
        std::ostringstream out;
        run_modes(scene, parse_modes_options(again, scene), out);
        CHECK(modes == file_text(again.output));
        CHECK(critical == file_text(again.critical));
        CHECK(std::count(critical.begin(), critical.end(), '\n') > 1);
    }
    SECTION("run")
    {
        const Ended ended = run_hubbeam(folder.path, {"run", cases + "spinup_omega4.toml", "--t-end", "1", "-o", "r.csv"});
        INFO(ended.stderr_text);
        CHECK(ended.code == 0);
        const std::string rows = file_text(folder.path / "r.csv");
        CHECK(std::count(rows.begin(), rows.end(), '\n') == 1 + 101);
    }
    SECTION("linearize")
    {
        const Ended ended = run_hubbeam(folder.path, {"linearize", cases + "torque_tau10.toml", "--omega", "2", "-o", "lin"});
        INFO(ended.stderr_text);
        CHECK(ended.code == 0);
        for (const char* f : {"lin-A.csv", "lin-B.csv", "lin-C.csv", "lin-D.csv", "lin.npz", "lin.hubbeam.json"})
            CHECK(!file_text(folder.path / f).empty());
    }
    SECTION("kernels")
    {
        const Ended ended = run_hubbeam(folder.path, {"kernels", "--ny", "4", "--methods", "amm", "--samples", "3", "-o", "k.csv"});
        INFO(ended.stderr_text);
        CHECK(ended.code == 0);
        CHECK(file_text(folder.path / "k.csv").rfind("method,drive,order,", 0) == 0);
    }
    SECTION("a standard output that fails otherwise (a full disk) is exit 1 and a message, the files whole")
    {
        const Ended ended = run_hubbeam(folder.path,
                                        {"modes", cases + "spinup_omega4.toml", "--omega", "0:20:0.5", "-o", "m.csv"},
                                        "/dev/full");
        CHECK(ended.code == 1);
        CHECK(ended.stderr_text == "hubbeam: standard output could not be written: the printed text is incomplete\n");
        const std::string modes = file_text(folder.path / "m.csv");
        CHECK(std::count(modes.begin(), modes.end(), '\n') == 1 + 41 * 8);
    }
}
