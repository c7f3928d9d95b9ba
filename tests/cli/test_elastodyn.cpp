// hubbeam modes --elastodyn end to end: the file read as ElastoDyn reads its BLADE MODE SHAPES section, a uniform
// blade's flap 1 polynomial against the fit of the clamped-free beam's closed-form first mode, and what is printed.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <hubbeam/mode_shapes.hpp>
#include <hubbeam/scene.hpp>
#include "modes.hpp"
#include "temp_folder.hpp"

using namespace hubbeam;

TEST_CASE("modes --elastodyn writes ElastoDyn's 15 mode shape lines, flap 1 the clamped-free beam's fit",
          "[modes][elastodyn]")
{
    TempFolder folder("elastodyn");
    const Scene scene = load_scene(HUBBEAM_SOURCE_DIR "/tests/scenes/uniform_blade.toml");
    ModesArgs args;
    args.omega = "0,5";  // the first rate's shapes
    args.elastodyn = (folder.path / "blade_modes.dat").string();
    args.quiet = true;
    std::ostringstream out;
    run_modes(scene, parse_modes_options(args, scene), out);

    std::ifstream in(args.elastodyn);
    std::string line;
    REQUIRE(std::getline(in, line));
    CHECK(line.rfind("---------------------- BLADE MODE SHAPES ----", 0) == 0);
    // "   0.0622   BldFl1Sh(2) - Flap mode 1, coeff of x^2": the value first, then the name ElastoDyn reads.
    const std::regex layout(R"(^ *(\S+)   (BldFl1Sh|BldFl2Sh|BldEdgSh)\(([2-6])\) - .*, coeff of x\^([2-6])$)");
    const char* names[] = {"BldFl1Sh", "BldFl2Sh", "BldEdgSh"};
    std::vector<std::vector<double>> c(3);
    int lines = 0;
    while (std::getline(in, line)) {
        INFO(line);
        std::smatch m;
        REQUIRE(std::regex_match(line, m, layout));
        const int group = lines / 5, power = lines % 5 + 2;
        CHECK(m[2] == names[group]);
        CHECK(std::stoi(m[3]) == power);
        CHECK(std::stoi(m[4]) == power);
        c[static_cast<std::size_t>(group)].push_back(std::stod(m[1]));
        ++lines;
    }
    CHECK(lines == 15);
    for (const auto& group : c) {
        double sum = 0.0;
        for (const double v : group) sum += v;
        CHECK(std::abs(sum - 1.0) < 1e-6);
    }

    // The closed form's fit on the same 201 equally spaced samples.
    const double bl = 1.8751040687119611664;
    const double sigma = (std::cosh(bl) + std::cos(bl)) / (std::sinh(bl) + std::sin(bl));
    std::vector<double> xi, phi;
    for (int i = 0; i <= 200; ++i) {
        const double x = i / 200.0;
        xi.push_back(x);
        phi.push_back(std::cosh(bl * x) - std::cos(bl * x) - sigma * (std::sinh(bl * x) - std::sin(bl * x)));
    }
    const PolynomialFit exact = fit_mode_shape(xi, phi);
    // The scene's AMM basis holds the clamped-free modes: its flap 1 is the closed form but for round-off (below
    // 1e-9 of the tip, test_mode_shapes.cpp). The fit is linear in the samples, so a coefficient moves by at most
    // ||A^+|| sqrt(201) 1e-9, A the constrained fit's matrix (columns xi^k - xi^6, k = 2..5).
    Eigen::MatrixXd A(201, 4);
    for (int i = 0; i <= 200; ++i)
        for (int k = 2; k <= 5; ++k) A(i, k - 2) = std::pow(xi[static_cast<std::size_t>(i)], k) - std::pow(xi[static_cast<std::size_t>(i)], 6);
    const double amplification = 1.0 / Eigen::JacobiSVD<Eigen::MatrixXd>(A).singularValues().minCoeff();
    const double tolerance = 2.0 * amplification * std::sqrt(201.0) * 1e-9;  // twice: c_6 sums the other four's
    INFO("tolerance " << tolerance);
    CHECK(tolerance < 1e-3);
    for (std::size_t k = 0; k < 5; ++k) CHECK(std::abs(c[0][k] - exact.coefficients[k]) < tolerance);
    // Printed: the file, the rate used, and each mode's frequency and fit residual; flap 1's are the closed form's,
    // 1.8751^2 sqrt(EI_flap / (m L^4)) and the residual of its fit, to the printed digits.
    const std::string printed = out.str();
    CHECK(printed.find("elastodyn: " + args.elastodyn) != std::string::npos);
    CHECK(printed.find("at Omega = 0 rad/s, the first spin rate") != std::string::npos);
    const Parameters& p = scene.parameters;
    char expected[200];
    std::snprintf(expected, sizeof expected, "  BldFl1Sh  flap 1  %11.6g Hz  fit residual %.3g of the tip deflection\n",
                  bl * bl * std::sqrt(p.E * p.I_flap / (p.rho * p.S * std::pow(p.L, 4))) / (2.0 * M_PI), exact.residual);
    INFO(printed);
    CHECK(printed.find(expected) != std::string::npos);
    // and the metadata beside it, as every output has
    CHECK(std::ifstream(args.elastodyn + ".hubbeam.json").good());
}
