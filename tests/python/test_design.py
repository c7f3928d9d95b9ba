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


    def test_sensitivities_that_conflict_with_the_scenes_or_a_keys_are_refused(self):
        # sensitivities= and output.sensitivities (in the scene, or as a key) naming other parameters: one of them
        # would be dropped silently, so the run is refused naming both; the same parameters in both are no conflict.
        import tempfile

        with open(CONTROLLED) as f:
            text = f.read()
        with tempfile.TemporaryDirectory() as d:
            scene = os.path.join(d, "with_sensitivities.toml")
            with open(scene, "w") as f:
                f.write(text.replace("[output]", '[output]\nsensitivities = "kd, E"', 1))
            by_key = {"output.sensitivities": "kd,E"}
            for call, where in ((lambda: hubbeam.run(CONTROLLED, sensitivities=["kp"], t_end=0.1, **by_key),
                                 "the keyword output.sensitivities"),
                                (lambda: hubbeam.run(scene, sensitivities="kp", t_end=0.1), scene)):
                with self.assertRaises(ValueError) as caught:
                    call()
                message = str(caught.exception)
                self.assertTrue(message.startswith('sensitivities: got "kp"'), message)
                self.assertIn(where, message)
                self.assertIn('output.sensitivities = "kd,E"', message)
            same = hubbeam.run(scene, sensitivities=["E", "kd"], t_end=0.1)
            self.assertIn("d_tip_uy/d_kd", same.columns)
            self.assertIn("d_tip_uy/d_E", same.columns)
            # An Objective's runs take its names' sensitivities whatever the scene names.
            f = hubbeam.Objective(scene, ["kp"], lambda r, n: hubbeam.final_error(r, n, "theta", 0.5), t_end=0.5)
            value, gradient = f([60.0])
            self.assertEqual(gradient.shape, (1,))

    def test_an_objective_takes_one_value_per_name(self):
        f = hubbeam.Objective(CONTROLLED, ["kp", "kd"], lambda r, n: hubbeam.final_error(r, n, "theta", 0.5),
                              t_end=0.5)
        for x in ([60.0], [60.0, 90.0, 1.0], 60.0):
            with self.subTest(x=x):
                with self.assertRaises(ValueError) as caught:
                    f(x)
                self.assertTrue(str(caught.exception).startswith("x: expected 2 values, one for each of kp, kd"),
                                str(caught.exception))
                with self.assertRaises(ValueError):
                    f.value(x)
        self.assertEqual(f.runs, 0)
        with self.assertRaisesRegex(ValueError, "^sensitivities: expected no such keyword"):
            hubbeam.Objective(CONTROLLED, ["kp"], lambda r, n: (0.0, 0.0), sensitivities=["kd"])


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
