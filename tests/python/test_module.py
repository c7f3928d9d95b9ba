"""The Python module against the command line (bit for bit), physics and its own contract: errors, stopped runs,
views without copies, the GIL released while integrating. Needs HUBBEAM (the executable) and SOURCE_DIR."""
import csv
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import numpy as np

import hubbeam

HUBBEAM = os.environ["HUBBEAM"]
SOURCE = os.environ["SOURCE_DIR"]
SPINUP = os.path.join(SOURCE, "cases", "spinup_omega4.toml")


def cli(*args):
    return subprocess.run([HUBBEAM, *args], capture_output=True, text=True)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(v) for v in row] for row in rows[1:]])


class RunTest(unittest.TestCase):
    def test_rows_equal_the_command_lines_bit_for_bit(self):
        with tempfile.TemporaryDirectory() as d:
            for args, keys in [(["--t-end", "3"], {"t_end": 3}),
                               (["--method", "fem", "--ny", "6", "--t-end", "2"], {"method": "fem", "ny": 6, "t_end": 2.0}),
                               ([], {})]:
                out = os.path.join(d, "cli.csv")
                scene = SPINUP if args or keys else os.path.join(SOURCE, "cases", "torque_tau1.toml")
                p = cli("run", scene, *args, "-o", out)
                self.assertEqual(p.returncode, 0, p.stderr)
                header, rows = read_csv(out)
                r = hubbeam.run(scene, **keys)
                self.assertEqual(list(r.columns), header)
                self.assertEqual(r.data.shape, rows.shape)
                self.assertTrue(np.array_equal(r.data, rows), f"{args}: largest difference {abs(r.data - rows).max()}")
                self.assertIn(r.variant, p.stdout)

    def test_a_dict_scene_is_the_file_scene(self):
        scene = {
            "beam": {"length": 8.0, "density": 2.7667e3, "area": 7.2968e-5, "second_moment": 8.2189e-9,
                     "youngs_modulus": 6.8952e10},
            "hub": {"radius": 0.0},
            "motion": {"kind": "spin-up", "omega0": 4.0, "duration": 15.0},
            "discretization": {"method": "amm", "ny": 4, "nx": 4},
            "model": {"order": "first"},
            "solver": {"rtol": 1e-8, "atol": 1e-10},
            "output": {"t_end": 2.0, "dt_out": 0.01},
        }
        self.assertTrue(np.array_equal(hubbeam.run(scene).data, hubbeam.run(SPINUP, t_end=2).data))

    def test_bad_input_raises_the_command_lines_message(self):
        for args, keys in [(["--method", "fem", "--ny", "3"], {"method": "fem", "ny": 3}),
                           (["--rtol", "4"], {"rtol": 4}),
                           (["--stepper", "nope"], {"stepper": "nope"})]:
            p = cli("run", SPINUP, *args, "-o", os.devnull)
            self.assertEqual(p.returncode, 2)
            with self.assertRaises(ValueError) as caught:
                hubbeam.run(SPINUP, **keys)
            self.assertEqual(str(caught.exception), p.stderr.strip())
        with self.assertRaises(ValueError) as caught:
            hubbeam.run(SPINUP, lenght=8)
        self.assertIn("lenght", str(caught.exception))
        with self.assertRaises(ValueError):
            hubbeam.run(os.path.join(SOURCE, "no_such_scene.toml"))

    def test_a_stopped_run_is_flagged_or_raises(self):
        scene = os.path.join(SOURCE, "tests", "scenes", "zero_order_unstable.toml")
        r = hubbeam.run(scene)
        self.assertFalse(r.completed)
        self.assertIn("unstable", r.failure)
        self.assertGreater(len(r.t), 100)  # the rows up to the stop are kept
        with self.assertRaises(hubbeam.RunStopped) as caught:
            hubbeam.run(scene, check=True)
        self.assertFalse(caught.exception.result.completed)

    def test_columns_are_views_of_one_array(self):
        r = hubbeam.run(SPINUP, t_end=1)
        self.assertEqual(r.data.shape, (101, 10))
        self.assertTrue(np.shares_memory(r.tip_uy, r.data))
        self.assertTrue(np.shares_memory(r.t, r.data))
        self.assertEqual(r.tip_uy[50], r.data[50, 3])

    def test_the_gil_is_released_while_integrating(self):
        # While a long run integrates in a thread, this thread keeps running Python: the longest pause between two
        # of its loop iterations stays far below the integration's own time (holding the GIL, it would be all of it).
        done = threading.Event()
        wall = [0.0]

        def integrate():
            wall[0] = hubbeam.run(SPINUP, stepper="msadams", rtol=1e-12, atol=1e-14, t_end=6).wall_seconds
            done.set()

        worker = threading.Thread(target=integrate)
        last, longest = time.perf_counter(), 0.0
        worker.start()
        while not done.is_set():
            now = time.perf_counter()
            longest, last = max(longest, now - last), now
        worker.join()
        self.assertGreater(wall[0], 0.1)
        self.assertLess(longest, wall[0] / 4)


    def test_ctrl_c_stops_a_long_run_with_keyboardinterrupt(self):
        # A run of about 25 s, interrupted after 1 s: it stops within a fraction of a second and raises.
        script = ("import hubbeam, sys, time\n"
                  "start = time.time()\n"
                  "try:\n"
                  "    hubbeam.run(sys.argv[1], nx=0, t_end=1e6, dt_out=1.0, max_steps=1e12)\n"
                  "    print('completed')\n"
                  "except KeyboardInterrupt:\n"
                  "    print('KeyboardInterrupt after %.1f s' % (time.time() - start))\n")
        child = subprocess.Popen([sys.executable, "-c", script, SPINUP], stdout=subprocess.PIPE, text=True,
                                 preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
        time.sleep(1.0)
        child.send_signal(signal.SIGINT)
        out, _ = child.communicate(timeout=15)
        self.assertIn("KeyboardInterrupt after", out)


class ModesTest(unittest.TestCase):
    def test_the_cantilevers_frequency_at_rest(self):
        # docs/model.md section 7: the first bending frequency, 1.8751^2 sqrt(EI/(m L^4)) = 2.9107 rad/s.
        m = hubbeam.modes(SPINUP, [0.0, 4.0], nx=0)
        self.assertEqual(m["variant"], "amm_nx0_ny4_prescribed_first")
        at_rest = m["rad_s"][(m["omega"] == 0.0) & (m["kind"] == "bending")]
        beta = 1.8751040687119611
        unit = np.sqrt(6.8952e10 * 8.2189e-9 / (2.7667e3 * 7.2968e-5 * 8.0 ** 4))
        self.assertAlmostEqual(at_rest[0] / (beta ** 2 * unit), 1.0, places=9)
        spinning = m["rad_s"][(m["omega"] == 4.0) & (m["kind"] == "bending")]
        self.assertGreater(spinning[0], at_rest[0])  # centrifugal stiffening

    def test_linearize_shapes_and_names(self):
        lin = hubbeam.linearize(os.path.join(SOURCE, "cases", "torque_tau10.toml"), 2.0, nx=0)
        self.assertEqual(lin["A"].shape, (10, 10))
        self.assertEqual(lin["inputs"], ["tau"])
        self.assertEqual(lin["outputs"], ["tip_uy", "theta"])


if __name__ == "__main__":
    unittest.main()
