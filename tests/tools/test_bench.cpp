// hubbeam bench's numbers and figures: each row's errors against references computed here on their own, the
// Pareto front's ties within the converged reference's resolution, the figures' series (only those run, none
// drawn alike, ticks at the grid's Ny); and the modes CSV's dimensionless frequencies against their definition.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "bench.hpp"
#include "modes.hpp"
#include "runs.hpp"

using namespace hubbeam;
namespace fs = std::filesystem;

namespace {

struct ScratchDir {
    fs::path dir = fs::temp_directory_path() / ("hubbeam_test_bench_" + std::to_string(::getpid()));
    ScratchDir() { fs::create_directories(dir); }
    ~ScratchDir() { fs::remove_all(dir); }
};

/// A CSV file as a header and rows of fields, looked up here by column name (a reader of its own).
struct Table {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    explicit Table(const fs::path& path)
    {
        std::ifstream in(path);
        for (std::string line; std::getline(in, line);) {
            std::vector<std::string> f;
            std::stringstream ss(line);
            for (std::string item; std::getline(ss, item, ',');) f.push_back(item);
            (header.empty() ? header : rows.emplace_back()) = f;
        }
    }
    std::size_t column(const std::string& name) const
    {
        const auto it = std::find(header.begin(), header.end(), name);
        REQUIRE(it != header.end());
        return static_cast<std::size_t>(it - header.begin());
    }
};

double max_tip_difference(const std::vector<Row>& a, const std::vector<Row>& b)
{
    REQUIRE(a.size() == b.size());
    double d = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        REQUIRE(a[i].t == Approx(b[i].t).margin(1e-12));
        d = std::max(d, std::abs(a[i].tip_uy - b[i].tip_uy));
    }
    return d;
}

}  // namespace

TEST_CASE("bench: the Pareto front treats errors within the reference's resolution as ties", "[bench]")
{
    // a fast coarse run, one 5 times better, rk8pd at the reference's floor, msadams 7 times slower "better" by
    // 3e-10 m, far below the 5.8e-7 m to which the converged reference itself is known
    const std::vector<WorkPoint> points{
        {0.232, 5.792e-7}, {0.001, 1e-4}, {0.033, 5.795e-7}, {0.010, 2e-5}, {0.5, 1e-7}};
    CHECK(pareto_front(points, 5.8e-7) == std::vector<std::size_t>{1, 3, 2});
    // with a reference resolved to 1e-10 m, the same differences are real
    CHECK(pareto_front(points, 1e-10) == std::vector<std::size_t>{1, 3, 2, 0, 4});
}

TEST_CASE("bench: each row's errors are against the references it names, and the figures draw what ran",
          "[bench]")
{
    ScratchDir scratch;
    Scene scene = load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/spinup_omega4.toml");
    scene.output.t_end = 3.0;
    BenchArgs args;
    args.methods = "amm,bim";
    args.ny = "4,6";
    args.nx = "0";
    args.steppers = "rkck,rk8pd";
    args.rtols = "1e-6";
    args.repeats = "1";
    args.ref_ny = "8";
    args.output = (scratch.dir / "bench.csv").string();
    args.plot = (scratch.dir / "bench").string();
    const BenchOptions options = parse_bench_options(args, scene);
    std::ostringstream out, progress;
    const std::vector<BenchRow> rows = run_bench(scene, options, out, progress, {});
    REQUIRE(rows.size() == 8);

    // The references, computed here: the same variant at rk8pd, rtol 1e-12 with a step at every row (time), and
    // AMM at Ny = 8 (the converged one, as --ref-ny 8 asks).
    const auto tight = [&](const VariantKey& key) {
        Scene s = scene;
        s.variant = key;
        s.solver.stepper = "rk8pd";
        s.solver.rtol = 1e-12;
        s.solver.atol = 1e-14;
        s.solver.stepping = Stepping::rows;
        return test::run(s);
    };
    VariantKey converged_key = scene.key();
    converged_key.method = Method::amm;
    converged_key.ny = 8;
    converged_key.nx = 0;
    const std::vector<Row> converged = tight(converged_key);
    const Table csv(scratch.dir / "bench.csv");
    REQUIRE(csv.rows.size() == rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const BenchRow& r = rows[i];
        INFO(r.key.name() << " " << r.stepper);
        REQUIRE(r.status == "ok");
        Scene s = scene;
        s.variant = r.key;
        s.solver.stepper = r.stepper;
        s.solver.rtol = 1e-6;
        s.solver.atol = 1e-8;
        const std::vector<Row> run = test::run(s);
        const double time_error = max_tip_difference(run, tight(r.key));
        const double disc_error = max_tip_difference(run, converged);
        CHECK(r.time_error == Approx(time_error).epsilon(1e-9).margin(1e-16));
        CHECK(r.disc_error == Approx(disc_error).epsilon(1e-9).margin(1e-16));
        // the CSV holds the same, by column name
        CHECK(std::stod(csv.rows[i][csv.column("time_error")]) == Approx(time_error).epsilon(1e-9).margin(1e-16));
        CHECK(std::stod(csv.rows[i][csv.column("disc_error")]) == Approx(disc_error).epsilon(1e-9).margin(1e-16));
        CHECK(csv.rows[i][csv.column("stepper")] == r.stepper);
    }

    // The figures: a line per method and stepper that ran, no two alike, named after the scene; Ny ticks.
    std::ifstream gp(scratch.dir / "bench.gp");
    const std::string script((std::istreambuf_iterator<char>(gp)), std::istreambuf_iterator<char>());
    for (const char* series : {"title 'amm rkck'", "title 'amm rk8pd'", "title 'bim rkck'", "title 'bim rk8pd'",
                               "title 'amm'", "title 'bim'"})
        CHECK(script.find(series) != std::string::npos);
    CHECK(script.find("fem") == std::string::npos);
    CHECK(script.find("bsim") == std::string::npos);
    CHECK(script.find("set xtics (4, 6)") != std::string::npos);
    CHECK(script.find("Work against precision, spinup_omega4") != std::string::npos);
    std::set<std::string> looks;  // colour and point type of each work-precision line
    std::size_t lines = 0;
    for (std::size_t at = script.find("lw 1.5 lc "); at != std::string::npos; at = script.find("lw 1.5 lc ", at + 1)) {
        const std::size_t end = script.find(" dt ", at);
        looks.insert(script.substr(at, end - at));
        ++lines;
    }
    CHECK(lines == 4);
    CHECK(looks.size() == lines);
    CHECK(fs::file_size(scratch.dir / "bench-work.png") > 0);
}

TEST_CASE("modes CSV: the dimensionless column is omega / sqrt(EI / (rho S L^4))", "[bench]")
{
    ScratchDir scratch;
    const Scene scene = load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/spinup_omega4.toml");
    ModesArgs args;
    args.omega = "0,4";
    args.methods = "amm,fem";
    args.ny = "4";
    args.output = (scratch.dir / "modes.csv").string();
    std::ostringstream out;
    run_modes(scene, parse_modes_options(args, scene), out);
    const Table csv(scratch.dir / "modes.csv");
    // docs/model.md: the frequency unit of the classical dimensionless frequencies, from the scene's beam
    const Parameters& p = scene.parameters;
    const double unit = std::sqrt(p.E * p.I / (p.rho * p.S * std::pow(p.L, 4)));
    const std::size_t rad_s = csv.column("rad_s"), hz = csv.column("hz"), dimensionless = csv.column("dimensionless"),
                      omega = csv.column("omega"), mode = csv.column("mode"), kind = csv.column("kind"),
                      method = csv.column("method");
    REQUIRE(csv.rows.size() > 8);
    int at_rest = 0;
    for (const auto& r : csv.rows) {
        CHECK(std::stod(r[dimensionless]) == Approx(std::stod(r[rad_s]) / unit).epsilon(1e-12));
        CHECK(std::stod(r[hz]) == Approx(std::stod(r[rad_s]) / (2.0 * M_PI)).epsilon(1e-12));
        // the cantilever's first bending frequency, (1.87510407)^2 = 3.51601527 in this unit: AMM's basis is
        // the cantilever's own modes, so it is exact there; FEM's four cubic elements are stiffer, within 1e-3
        if (std::stod(r[omega]) == 0.0 && r[mode] == "1" && r[kind] == "bending") {
            const double lambda = std::stod(r[dimensionless]);
            if (r[method] == "amm") CHECK(lambda == Approx(3.51601527).epsilon(1e-7));
            else CHECK((lambda > 3.51601527 && lambda < 3.51601527 * (1 + 1e-3)));
            ++at_rest;
        }
    }
    CHECK(at_rest == 2);
}
