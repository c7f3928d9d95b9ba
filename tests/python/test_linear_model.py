"""hubbeam linearize's .npz (docs/cli.md, "hubbeam linearize"): read by numpy and by an independent zip reader, the
same matrices as the CSVs, and a model that predicts a small-amplitude nonlinear run, with damping and a
controller. Needs HUBBEAM and SOURCE_DIR."""
import csv
import os
import subprocess
import tempfile
import unittest
import zipfile

import numpy as np
import scipy.linalg
import scipy.signal

import hubbeam

HUBBEAM = os.environ["HUBBEAM"]
SOURCE = os.environ["SOURCE_DIR"]
CONTROLLED = os.path.join(SOURCE, "cases", "controlled_step.toml")


def linearize(scene, prefix, *options):
    done = subprocess.run([HUBBEAM, "linearize", scene, "--omega", "0", "-o", prefix, *options],
                          capture_output=True, text=True)
    if done.returncode != 0:
        raise AssertionError(done.stderr)
    return np.load(prefix + ".npz")


class Archive(unittest.TestCase):
    def test_numpy_zip_and_csv_agree(self):
        with tempfile.TemporaryDirectory() as d:
            prefix = os.path.join(d, "lin")
            m = linearize(CONTROLLED, prefix)
            with zipfile.ZipFile(prefix + ".npz") as z:
                self.assertIsNone(z.testzip())  # every entry's CRC-32 holds
                self.assertEqual(sorted(z.namelist()), sorted(k + ".npy" for k in
                                                              ("A", "B", "C", "D", "states", "inputs", "outputs")))
            for name in "ABCD":
                with open(f"{prefix}-{name}.csv", newline="") as f:
                    rows = list(csv.reader(f))
                np.testing.assert_array_equal(m[name], np.array([[float(v) for v in r[1:]] for r in rows[1:]]))
                if name in "AB":
                    self.assertEqual(list(m["states"]), [r[0] for r in rows[1:]])
            self.assertEqual(list(m["outputs"]), ["tip_uy", "theta"])
            system = scipy.signal.StateSpace(m["A"], m["B"], m["C"], m["D"])  # the one line a user writes
            self.assertEqual(system.A.shape[0], len(m["states"]))
            self.assertTrue(os.path.exists(prefix + "-open.npz"))


class StepResponse(unittest.TestCase):
    def check(self, keys, options):
        """The controlled hub stepping to a small angle: the closed loop's free response from theta = -angle (a
        step of the reference is a start that far from the new equilibrium) against the nonlinear run."""
        angle = 1e-4
        with tempfile.TemporaryDirectory() as d:
            scene = os.path.join(d, "small.toml")
            with open(CONTROLLED) as f:
                text = f.read().replace("angle = 0.5 ", f"angle = {angle} ").replace("tau_max = 10.0", "tau_max = 1e9")
            with open(scene, "w") as f:
                f.write(text + keys)
            m = linearize(scene, os.path.join(d, "lin"), *options)
            r = hubbeam.run(scene, t_end=10.0, rtol=1e-11, atol=1e-14, stepper="rk8pd")
        x0 = np.zeros(len(m["states"]))
        x0[list(m["states"]).index("theta")] = -angle
        expected = np.array([m["C"] @ scipy.linalg.expm(m["A"] * t) @ x0 for t in r.t])
        for i, out in enumerate(m["outputs"]):
            got = r.tip_uy if out == "tip_uy" else r.theta - angle
            with self.subTest(output=out):
                # the nonlinear terms are of second order in the angle: measured 4e-10 of the response; the model
                # without its damping is 4e-2 off
                self.assertLess(np.abs(got - expected[:, i]).max(), 1e-6 * np.abs(expected[:, i]).max())
                self.assertGreater(np.abs(expected[:, i]).max(), 0.0)

    def test_controlled(self):
        self.check("", [])

    def test_controlled_and_damped(self):
        self.check("\n[damping]\nmass_proportional = 0.05\nstiffness_proportional = 0.002\n", [])


if __name__ == "__main__":
    unittest.main()


class MultiBlade(unittest.TestCase):
    """A rotor of 3 identical blades in multi-blade coordinates (docs/model.md section 13.2): the module's model is the
    command line's, bit for bit; frame= takes the blades' frames or refuses, naming why."""
    BALANCED = os.path.join(SOURCE, "cases", "ground_resonance_balanced.toml")
    UNEVEN = os.path.join(SOURCE, "cases", "ground_resonance.toml")

    def test_linearize_as_the_command_line(self):
        with tempfile.TemporaryDirectory() as d:
            prefix = os.path.join(d, "rotor")
            done = subprocess.run([HUBBEAM, "linearize", self.BALANCED, "--omega", "10", "-o", prefix],
                                  capture_output=True, text=True)
            self.assertEqual(done.returncode, 0, done.stderr)
            m = np.load(prefix + ".npz")
            lin = hubbeam.linearize(self.BALANCED, 10.0)
            for name in "ABCD":
                np.testing.assert_array_equal(lin[name], m[name])
            self.assertEqual(lin["states"], list(m["states"]))
            self.assertIn("B1_cos1", lin["states"])
            self.assertEqual(lin["outputs"][:4], ["tip_uy_coll", "tip_uy_cos1", "tip_uy_sin1", "theta"])

    def test_frames(self):
        fixed = hubbeam.modes(self.BALANCED, [11.0], harmonics=None)
        self.assertIn("FW hub", set(fixed["kind"]))
        self.assertGreater(fixed["growth"].max(), 0.4)  # ground resonance
        rotating = hubbeam.modes(self.BALANCED, [0.0], harmonics=None, frame="rotating")
        self.assertFalse(any(k.startswith(("FW", "BW", "collective")) for k in rotating["kind"]))
        with self.assertRaisesRegex(ValueError, "^frame: multi-blade coordinates need identical blades, and blade 2"):
            hubbeam.modes(self.UNEVEN, [0.0], frame="fixed")
        with self.assertRaisesRegex(ValueError, "^frame: expected"):
            hubbeam.modes(self.BALANCED, [0.0], frame="inertial")
        with self.assertRaisesRegex(ValueError, "periodic"):
            hubbeam.linearize(self.BALANCED, 10.0, frame="rotating")
