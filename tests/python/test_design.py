"""Sensitivities from Python and the gradients of summary quantities built on them (docs/sensitivities.md): against
central differences of whole runs, and the optimization example's claim that exact gradients need fewer runs.
Needs SOURCE_DIR."""
import importlib.util
import os
import unittest

import numpy as np

import hubbeam

SOURCE = os.environ["SOURCE_DIR"]
CONTROLLED = os.path.join(SOURCE, "cases", "controlled_step.toml")
CONVERGED = dict(t_end=6.0, stepper="rk8pd", rtol=1e-12, atol=1e-14)


def moved(name, value):
    return {hubbeam.PARAMETER_KEYS[name]: value}


class Sensitivities(unittest.TestCase):
    def test_columns_and_values_against_differences(self):
        r = hubbeam.run(CONTROLLED, sensitivities=["kp", "E"], **CONVERGED)
        self.assertIn("d_tip_uy/d_kp", r.columns)
        self.assertIn("d_theta_dot/d_E", r.columns)
        for name, value in (("kp", 64.45), ("E", 6.8952e10)):
            h = 1e-4 * value
            up = hubbeam.run(CONTROLLED, **CONVERGED, **moved(name, value + h))
            down = hubbeam.run(CONTROLLED, **CONVERGED, **moved(name, value - h))
            for out in ("theta", "tip_uy"):
                fd = (getattr(up, out) - getattr(down, out)) / (2 * h)
                with self.subTest(parameter=name, output=out):
                    self.assertLess(np.abs(r[f"d_{out}/d_{name}"] - fd).max() / np.abs(fd).max(), 1e-5)

    def test_bad_names_are_refused(self):
        with self.assertRaisesRegex(ValueError, "sensitivities: expected parameter symbols"):
            hubbeam.run(CONTROLLED, sensitivities=["young"], t_end=0.1)
        with self.assertRaisesRegex(ValueError, r"\[control\]"):
            hubbeam.run(os.path.join(SOURCE, "cases", "spinup_omega4.toml"), sensitivities=["kp"], t_end=0.1)


class Gradients(unittest.TestCase):
    def check_measure(self, measure, **keys):
        names = ["kp", "kd"]
        x = np.array([60.0, 95.0])
        f = hubbeam.Objective(CONTROLLED, names, measure, **CONVERGED, **keys)
        value, gradient = f(x)
        for i, name in enumerate(names):
            h = 1e-4 * x[i]
            e = np.zeros(2)
            e[i] = h
            fd = (f.value(x + e) - f.value(x - e)) / (2 * h)
            with self.subTest(parameter=name):
                self.assertLess(abs(gradient[i] - fd), 1e-5 * abs(fd))
        self.assertGreater(value, 0.0)

    def test_max_deflection(self):
        # the largest deflection comes while the torque is at its limit, where the gains do not act: a higher limit
        self.check_measure(lambda r, n: hubbeam.max_deflection(r, n), **{"control.tau_max": 100.0})

    def test_residual_vibration(self):
        self.check_measure(lambda r, n: hubbeam.residual_vibration(r, n, after=3.0))

    def test_final_error(self):
        self.check_measure(lambda r, n: hubbeam.final_error(r, n, "theta", 0.5))

    def test_optimizer_needs_fewer_runs_with_exact_gradients(self):
        path = os.path.join(SOURCE, "examples", "tune_controller", "tune_controller.py")
        spec = importlib.util.spec_from_file_location("tune_controller", path)
        example = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(example)
        exact, exact_runs = example.minimise(jac=True)
        differenced, differenced_runs = example.minimise(jac=False)
        self.assertTrue(exact.success)
        # the same optimum, reached in fewer runs
        np.testing.assert_allclose(exact.x, differenced.x, rtol=1e-3)
        self.assertLess(exact_runs, differenced_runs)


if __name__ == "__main__":
    unittest.main()
