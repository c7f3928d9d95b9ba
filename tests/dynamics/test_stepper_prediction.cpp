// The automatic choice's predicted step counts against the steps the steppers take, on the prescribed spin-ups where
// the prediction alone decides (a hub torque measures gauss4 with a pilot run instead): near a tie, a prediction off
// by a factor picks the slower stepper.
#include <catch2/catch.hpp>

#include <string>

#include <hubbeam/make_model.hpp>
#include <hubbeam/simulate.hpp>
#include "dynamics/stiffness.hpp"
#include "runs.hpp"

using namespace hubbeam;

TEST_CASE("gauss4's predicted steps on a spin-up are 0.8 to 2.5 times the steps it takes", "[stiffness][steppers]")
{
    // stiffness.cpp: gauss4's step doubling takes 1 to 1.9 times the steps its accuracy alone needs; the
    // prediction counts twice those (here 1.05 to 1.9 times the steps taken; without the factor 2, 0.52 to 0.94).
    // The four methods, without and with axial coordinates.
    struct Point {
        Method method;
        int nx;
    };
    const Point grid[] = {{Method::amm, 0}, {Method::amm, 4}, {Method::bim, 4}, {Method::bsim, 0},
                          {Method::fem, 4}};
    for (const Point& p : grid) {
        Scene s = test::paper_scene(p.method, p.nx, 4, test::spin_up(4.0));
        s.output.t_end = 30.0;
        s.solver.rtol = 1e-8;
        s.solver.atol = 1e-10;
        s.solver.stepper = "gauss4";
        s.solver.error_check = ErrorCheck::off;
        const RunSummary run = test::completed_run(s).summary;
        const auto model = make_model(s.key(), s.parameters, s.source);
        const StepperCosts predicted = predicted_costs(*model, s.axial, s.solver.rtol, s.output.t_end);
        INFO(to_string(p.method) << " Nx = " << p.nx << ": gauss4 took " << run.steps << " steps, predicted "
                                 << predicted.steps_gauss4);
        CHECK(predicted.steps_gauss4 >= 0.8 * static_cast<double>(run.steps));
        CHECK(predicted.steps_gauss4 <= 2.5 * static_cast<double>(run.steps));
    }
}
