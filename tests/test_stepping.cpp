// Free stepping (solver.stepping = "free"): rows interpolated between step ends by the quintic Hermite interpolant
// of positions, rates and accelerations, with its error estimated at each step's middle; against polynomials it
// must reproduce, its convergence order, and runs of every stepper against a tight reference.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "integrate.hpp"
#include "runs.hpp"

using namespace hubbeam;
using namespace hubbeam::test;

namespace {

/// y = (p, v) and f = (v, a) at t for p(t) = sin(w t) and p(t) = t^5 - 2 t^3 + t.
struct Sample {
    std::vector<double> y, f;
};
Sample sample(double t, double w)
{
    const double p1 = std::sin(w * t), v1 = w * std::cos(w * t), a1 = -w * w * std::sin(w * t);
    const double p2 = std::pow(t, 5) - 2 * std::pow(t, 3) + t, v2 = 5 * std::pow(t, 4) - 6 * t * t + 1,
                 a2 = 20 * std::pow(t, 3) - 12 * t;
    return {{p1, p2, v1, v2}, {v1, v2, a1, a2}};
}

}  // namespace

TEST_CASE("interpolate_state reproduces quintics and converges as h^6 (positions) and h^5 (rates)", "[stepping]")
{
    const double w = 3.0, t0 = 0.4;
    double previous_p = 0.0, previous_v = 0.0;
    for (const double h : {0.4, 0.2, 0.1, 0.05}) {
        const Sample a = sample(t0, w), b = sample(t0 + h, w);
        double error_p = 0.0, error_v = 0.0;
        for (const double s : {0.1, 0.3, 0.5, 0.77}) {
            const double t = t0 + s * h;
            std::vector<double> y(4);
            interpolate_state(t0, a.y.data(), a.f.data(), t0 + h, b.y.data(), b.f.data(), t, 4, y.data());
            const Sample exact = sample(t, w);
            // The quintic polynomial (second position) exactly, to round-off.
            CHECK(std::abs(y[1] - exact.y[1]) <= 1e-13);
            CHECK(std::abs(y[3] - exact.y[3]) <= 1e-12);
            error_p = std::max(error_p, std::abs(y[0] - exact.y[0]));
            error_v = std::max(error_v, std::abs(y[2] - exact.y[2]));
        }
        if (previous_p > 0.0) {
            INFO("h = " << h << ": position error " << error_p << " (was " << previous_p << "), rate error " << error_v
                        << " (was " << previous_v << ")");
            CHECK(previous_p / error_p > 0.8 * 64.0);
            CHECK(previous_v / error_v > 0.8 * 32.0);
        }
        previous_p = error_p;
        previous_v = error_v;
    }
}

TEST_CASE("interpolation_error estimates the interpolant's error at the step's middle", "[stepping]")
{
    const double w = 3.0, t0 = 0.4;
    for (const double h : {0.2, 0.1, 0.05}) {
        const Sample a = sample(t0, w), b = sample(t0 + h, w);
        std::vector<double> y_mid(4);
        interpolate_state(t0, a.y.data(), a.f.data(), t0 + h, b.y.data(), b.f.data(), t0 + h / 2, 4, y_mid.data());
        // The equations' acceleration at the interpolated state: p'' = -w^2 p (sine) and the quintic's own.
        const Sample exact = sample(t0 + h / 2, w);
        std::vector<double> f_mid = {y_mid[2], y_mid[3], -w * w * y_mid[0], exact.f[3]};
        const double estimate = interpolation_error(t0, a.y.data(), a.f.data(), t0 + h, b.y.data(), b.f.data(),
                                                    y_mid.data(), f_mid.data(), 4, 1.0, 0.0);
        const double actual = std::abs(y_mid[0] - exact.y[0]);
        INFO("h = " << h << ": estimate " << estimate << ", actual " << actual);
        CHECK(estimate > 0.5 * actual);
        CHECK(estimate < 2.0 * actual);
    }
}

TEST_CASE("free stepping: every stepper's interpolated rows are as accurate as a step at every row", "[stepping]")
{
    // The spin-up without axial coordinates, 3 s into the drive; a tight reference with a step at every row.
    Scene reference = paper_scene(Method::amm, 0, 4, spin_up(4.0));
    reference.output.t_end = 3.0;
    reference.solver.stepper = "rk8pd";
    reference.solver.rtol = reference.solver.atol = 1e-14;
    reference.solver.stepping = Stepping::rows;
    const std::vector<Row> exact = run(reference);
    double scale = 0.0;
    for (const Row& r : exact) scale = std::max(scale, std::abs(r.tip_uy));
    const auto error = [&](const std::vector<Row>& rows) {
        REQUIRE(rows.size() == exact.size());
        double e = 0.0;
        for (std::size_t i = 0; i < rows.size(); ++i) {
            CHECK(rows[i].t == exact[i].t);
            e = std::max(e, std::abs(rows[i].tip_uy - exact[i].tip_uy));
        }
        return e;
    };
    for (const std::string& stepper : stepper_names()) {
        const bool low_order = stepper == "rk2" || stepper == "rk2imp" || stepper == "rk1imp";
        Scene s = reference;
        s.solver.stepper = stepper;
        s.solver.rtol = s.solver.atol = low_order ? 1e-6 : 1e-9;
        s.solver.stepping = Stepping::rows;
        const double at_rows = error(run(s));
        s.solver.stepping = Stepping::free;
        const double free = error(run(s));
        INFO(stepper << ": free " << free << " m, a step at every row " << at_rows << " m, scale " << scale << " m");
        CHECK(free <= std::max(2.0 * at_rows, 50.0 * s.solver.rtol * scale));
    }
}
