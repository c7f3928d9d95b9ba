"""The Python module against the command line (bit for bit), physics and its own contract: errors, stopped runs,
views without copies, the GIL released while integrating. Needs HUBBEAM (the executable) and SOURCE_DIR."""
import csv
import os
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import numpy as np

import hubbeam
from hubbeam import sweeps

HUBBEAM = os.environ["HUBBEAM"]
SOURCE = os.environ["SOURCE_DIR"]
SPINUP = os.path.join(SOURCE, "cases", "spinup_omega4.toml")


def cli(*args):
    return subprocess.run([HUBBEAM, *args], capture_output=True, text=True)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(v) for v in row] for row in rows[1:]])


def read_csv_named(path):
    """A linearize CSV: its row names, its column names and its values."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return [r[0] for r in rows[1:]], rows[0][1:], np.array([[float(v) for v in r[1:]] for r in rows[1:]])


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

    def test_initial_state_is_a_scene_key_like_any(self):
        # cases/helicopter_blade.toml at rest under gravity along its spin axis: "static" starts it at the cantilever's
        # sag -m g L^4/(8 EI_flap) (FEM holds the quartic's nodal values exactly), whichever way the key is named.
        blade = os.path.join(SOURCE, "cases", "helicopter_blade.toml")
        sag = -8.0 * 9.81 * 6.0 ** 4 / (8.0 * 1e5)
        for keys in ({"state": "static"}, {"initial.state": "static"}):
            r = hubbeam.run(blade, t_end=0.1, **keys)
            self.assertAlmostEqual(r.tip_uz[0] / sag, 1.0, delta=1e-9)
            self.assertIn("\ninitial     static equilibrium at theta = 0 rad (Newton, residual ", r.summary_text)
        r = hubbeam.run(blade, t_end=0.1)
        self.assertEqual(r.tip_uz[0], 0.0)
        self.assertNotIn("\ninitial ", r.summary_text)
        with self.assertRaisesRegex(ValueError, "state: expected one of \"rest\", \"static\", \"steady\""):
            hubbeam.run(blade, state="moving")

    def test_a_rotor_has_each_blades_columns_and_the_hubs(self):
        # cases/three_blade_rotor.toml: three blades on a support. The module's rows are the command line's, bit for
        # bit, with each blade's tip columns by number and the hub's translation and support force.
        rotor = os.path.join(SOURCE, "cases", "three_blade_rotor.toml")
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "rotor.csv")
            p = cli("run", rotor, "--t-end", "2", "-o", out)
            self.assertEqual(p.returncode, 0, p.stderr)
            header, rows = read_csv(out)
        r = hubbeam.run(rotor, t_end=2)
        self.assertEqual(list(r.columns), header)
        self.assertTrue(np.array_equal(r.data, rows))
        for name in ("tip_uy_1", "tip_uy_2", "tip_uy_3", "tip_uz_1", "tip_uz_3", "hub_x", "hub_y", "hub_fx", "hub_fy"):
            self.assertIn(name, r.columns)
        self.assertNotIn("tip_uy", r.columns)
        # The blades differ: blade 2 carries the tip mass.
        uy = {b: r.data[:, list(r.columns).index(f"tip_uy_{b}")] for b in (1, 2)}
        self.assertGreater(abs(uy[1] - uy[2]).max(), 1e-4)

    def test_root_loads_equal_the_command_lines_bit_for_bit(self):
        # cases/three_blade_rotor.toml with each blade's root loads asked for (--loads root, loads="root"): the same
        # columns and values, bit for bit; not asked for, none of them.
        rotor = os.path.join(SOURCE, "cases", "three_blade_rotor.toml")
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "rotor.csv")
            p = cli("run", rotor, "--t-end", "1", "--loads", "root", "-o", out)
            self.assertEqual(p.returncode, 0, p.stderr)
            header, rows = read_csv(out)
        r = hubbeam.run(rotor, t_end=1, loads="root")
        self.assertEqual(list(r.columns), header)
        self.assertTrue(np.array_equal(r.data, rows))
        for b in (1, 2, 3):
            for name in ("root_edge_moment", "root_flap_moment", "root_shear_edge", "root_shear_flap",
                         "root_axial_force"):
                self.assertIn(f"{name}_{b}", r.columns)
        self.assertFalse(any(c.startswith("root_") for c in hubbeam.run(rotor, t_end=0.1).columns))

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

    def test_bad_input_raises_the_command_lines_message_against_the_keyword(self):
        # The command line's message, with the keyword the Python user wrote where the command line names its option.
        for args, keys, keyword in [(["--method", "fem", "--ny", "3"], {"method": "fem", "ny": 3}, "ny"),
                                    (["--rtol", "4"], {"rtol": 4}, "rtol"),
                                    (["--stepper", "nope"], {"stepper": "nope"}, "stepper"),
                                    (["--stepper", "nope"], {"solver.stepper": "nope"}, "solver.stepper")]:
            p = cli("run", SPINUP, *args, "-o", os.devnull)
            self.assertEqual(p.returncode, 2)
            with self.assertRaises(ValueError) as caught:
                hubbeam.run(SPINUP, **keys)
            option = args[-2]
            self.assertTrue(p.stderr.startswith(option + ": "), p.stderr)
            self.assertEqual(str(caught.exception), keyword + ": " + p.stderr.strip()[len(option) + 2:])
        with self.assertRaises(ValueError) as caught:
            hubbeam.run(SPINUP, lenght=8)
        self.assertIn("lenght", str(caught.exception))
        with self.assertRaises(FileNotFoundError):  # as open() says it (test_a_missing_scene_file_is_filenotfounderror)
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


def interrupted_after(test, body, grace=0.3):
    """Runs body (Python source after `import hubbeam, numpy as np, sys, threading, time`) in a child that prints
    "started" before its long call, sends it SIGINT once started and grace seconds have passed, and returns the
    seconds from the signal to the child's line "KeyboardInterrupt at TIME" and the child's output."""
    script = "import hubbeam, numpy as np, sys, threading, time\n" + body
    child = subprocess.Popen([sys.executable, "-c", script, SPINUP], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    test.assertEqual(child.stdout.readline().strip(), "started")
    time.sleep(grace)
    sent = time.time()
    child.send_signal(signal.SIGINT)
    out, err = child.communicate(timeout=60)
    test.assertNotIn("completed", out)
    lines = [line for line in out.splitlines() if line.startswith("KeyboardInterrupt at ")]
    test.assertEqual(len(lines), 1, out + err)
    return float(lines[0].split()[-1]) - sent, out + err


# The child's long call, wrapped so that it reports when KeyboardInterrupt reaches it.
CAUGHT = ("try:\n    {call}\n    print('completed')\nexcept KeyboardInterrupt:\n"
          "    print('KeyboardInterrupt at %.6f' % time.time(), flush=True)\n")


class InterruptTest(unittest.TestCase):
    """Ctrl-C acts within a second wherever hubbeam computes, and an interpreter may exit while a daemon thread runs
    hubbeam (docs/python.md, "Interrupts and threads")."""

    def test_ctrl_c_stops_a_long_run_within_a_second(self):
        # A run of about 25 s: it stops at its next check (0.1 s apart) and raises KeyboardInterrupt.
        call = "print('started', flush=True); hubbeam.run(sys.argv[1], nx=0, t_end=1e6, dt_out=1.0, max_steps=1e12)"
        seconds, out = interrupted_after(self, CAUGHT.format(call=call))
        self.assertLess(seconds, 1.0, out)

    def test_ctrl_c_stops_modes_on_a_long_grid_within_a_second(self):
        # 40000 spin rates take several seconds; the rates are computed with checks between them.
        call = "print('started', flush=True); hubbeam.modes(sys.argv[1], np.linspace(0.0, 4.0, 40000))"
        seconds, out = interrupted_after(self, CAUGHT.format(call=call))
        self.assertLess(seconds, 1.0, out)

    def test_ctrl_c_stops_runs_in_worker_threads_within_a_second(self):
        # The main thread waits for two worker threads that each run for about 25 s. Ctrl-C reaches the main thread
        # only; the interpreter then exits, and waits for its (non-daemon) threads: their runs stop and raise too.
        body = ("def work():\n"
                "    try:\n"
                "        hubbeam.run(sys.argv[1], nx=0, t_end=1e6, dt_out=1.0, max_steps=1e12)\n"
                "        sys.stdout.write('completed\\n')\n"
                "    except KeyboardInterrupt:\n"
                "        sys.stdout.write('worker KeyboardInterrupt at %.6f\\n' % time.time())\n"
                "workers = [threading.Thread(target=work) for _ in range(2)]\n"
                "for w in workers: w.start()\n"
                # Not join(): Python 3.11 takes a thread whose join() Ctrl-C interrupted for ended, and does not
                # wait for it at exit.
                + CAUGHT.format(call="print('started', flush=True)\n    while any(w.is_alive() for w in workers): "
                                     "time.sleep(0.01)") +
                "raise KeyboardInterrupt\n")
        seconds, out = interrupted_after(self, body)
        self.assertLess(seconds, 1.0, out)
        ended = [float(line.split()[-1]) for line in out.splitlines() if line.startswith("worker KeyboardInterrupt")]
        self.assertEqual(len(ended), 2, out)
        main = float([line for line in out.splitlines() if line.startswith("KeyboardInterrupt at")][0].split()[-1])
        self.assertLess(max(ended) - main, 1.0, out)

    def test_a_normal_exit_waits_for_the_runs_of_its_threads(self):
        # Without Ctrl-C the interpreter waits for its (non-daemon) threads, as Python does: their runs complete.
        script = ("import hubbeam, sys, threading\n"
                  "def work():\n"
                  "    r = hubbeam.run(sys.argv[1], nx=0, t_end=2e4, dt_out=1.0, max_steps=1e12)\n"
                  "    sys.stdout.write('completed %s %g\\n' % (r.completed, r.t[-1]))\n"
                  "threading.Thread(target=work).start()\n")
        p = subprocess.run([sys.executable, "-c", script, SPINUP], capture_output=True, text=True, timeout=120)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(p.stdout, "completed True 20000\n")

    def test_exiting_while_a_daemon_thread_computes_does_not_abort(self):
        # Python ends a daemon thread that asks for the GIL during finalization by pthread_exit, whose unwinding
        # through C++ aborts: each of these exits while a daemon thread is deep in the core, several times over.
        long_run = "hubbeam.run(sys.argv[1], nx=0, t_end=1e6, dt_out=1.0, max_steps=1e12{})"
        for work in (long_run.format(""),
                     long_run.format(", torque=lambda t, s: -s['theta_dot']"),  # the GIL taken at every evaluation
                     # Python code in the law drops the GIL: the thread may be ended inside the law's call
                     long_run.format(", torque=lambda t, s: -s['theta_dot'] + 0.0 * sum(range(2000))"),
                     "hubbeam.modes(sys.argv[1], np.linspace(0.0, 4.0, 40000))"):
            script = ("import hubbeam, numpy as np, sys, threading, time\n"
                      f"threading.Thread(target=lambda: {work}, daemon=True).start()\n"
                      "time.sleep(0.2 + 0.1 * int(sys.argv[2]))\n")
            for attempt in range(4):
                with self.subTest(work=work, attempt=attempt):
                    p = subprocess.run([sys.executable, "-c", script, SPINUP, str(attempt)], capture_output=True,
                                       text=True, timeout=60)
                    self.assertEqual(p.returncode, 0, p.stderr)


class MessagesTest(unittest.TestCase):
    def test_control_and_format_characters_show_as_escapes(self):
        # ESC would recolour the terminal, U+202E reverse what follows: a message shows both as escapes, whether
        # Python (an unknown keyword, a dict scene's table) or the core (a bad value) built it.
        shady = "x\x1b[31m\u202e"
        for call in (lambda: hubbeam.run(SPINUP, **{shady: 1}),
                     lambda: hubbeam.run(SPINUP, stepper=shady),
                     lambda: hubbeam.run({shady: 1}),
                     lambda: hubbeam.modes(SPINUP, shady),
                     lambda: sweeps.load_sweep({"scene": SPINUP, "keep": [shady]})):
            with self.assertRaises(ValueError) as caught:
                call()
            text = str(caught.exception)
            self.assertIn("x\\x1b[31m\\u202e", text)
            self.assertNotIn("\x1b", text)
            self.assertNotIn("\u202e", text)
        self.assertEqual(hubbeam.printable("a\x00b\nc\u2066\U000e0001"), "a\\x00b\\x0ac\\u2066\\U000e0001")

    def test_a_leaf_name_that_two_tables_share_must_name_its_table(self):
        with self.assertRaises(ValueError) as caught:
            hubbeam.run(SPINUP, inertia=40.0)
        self.assertIn("hub.inertia and tip.inertia", str(caught.exception))

    def test_a_nul_character_is_refused(self):
        with self.assertRaises(ValueError) as caught:
            hubbeam.run(SPINUP, **{"output.file": "a\u0000b.csv"})
        self.assertIn("NUL", str(caught.exception))

    def test_a_misspelt_keyword_gets_the_nearest_key(self):
        # A leaf name or a dotted name one or two letters off: the message names the key meant; a word far from
        # every key gets no guess.
        for call, meant in ((lambda: hubbeam.run(SPINUP, lenght=8.0), "length"),
                            (lambda: hubbeam.modes(SPINUP, 0.0, **{"discretisation.ny": 4}), "discretization.ny"),
                            (lambda: hubbeam.effective_scene(SPINUP, omgea0=2.0), "omega0"),
                            (lambda: hubbeam.run(SPINUP, sensitivites=["E"]), "sensitivities")):
            with self.assertRaises(ValueError) as caught:
                call()
            self.assertRegex(str(caught.exception), rf": expected a scene key \(docs/scene.md; hubbeam.scene_keys\(\)\), "
                                                    rf"got an unknown keyword \(did you mean {re.escape(meant)}\?\)$")
        with self.assertRaises(ValueError) as caught:
            hubbeam.run(SPINUP, zzzzzz=1)
        self.assertTrue(str(caught.exception).endswith("got an unknown keyword"), str(caught.exception))

    def test_a_missing_scene_file_is_filenotfounderror(self):
        # As open() says it, for every function that reads a scene; a file that is there but bad stays a ValueError.
        with tempfile.TemporaryDirectory() as d:
            missing = os.path.join(d, "nope.toml")
            for call in (lambda: hubbeam.run(missing), lambda: hubbeam.modes(missing), lambda: hubbeam.linearize(missing, 1.0),
                         lambda: hubbeam.effective_scene(missing), lambda: hubbeam.scene_files(missing)):
                with self.assertRaises(FileNotFoundError) as caught:
                    call()
                self.assertEqual(str(caught.exception), f"[Errno 2] {missing}: no such scene file: '{missing}'")
            bad = os.path.join(d, "bad.toml")
            with open(bad, "w") as f:
                f.write("[beam\n")
            with self.assertRaises(ValueError):
                hubbeam.run(bad)


class NumpyInputTest(unittest.TestCase):
    """numpy's numbers and arrays go wherever Python's do; a string is no number."""

    def test_numpy_scalars_are_the_numbers_they_hold(self):
        plain = hubbeam.run(SPINUP, ny=4, nx=2, t_end=0.5, rtol=1e-9, max_steps=100000)
        for keys in ({"ny": np.int64(4), "nx": np.int32(2), "t_end": np.float64(0.5), "rtol": np.float64(1e-9),
                      "max_steps": np.int64(100000)},
                     {"ny": np.array(4), "nx": np.uint8(2), "t_end": np.float32(0.5), "rtol": 1e-9,
                      "max_steps": np.float64(1e5)},
                     {"discretization.ny": np.int16(4), "nx": 2, "t_end": 0.5, "rtol": np.array(1e-9),
                      "max_steps": 100000}):
            with self.subTest(keys=keys):
                self.assertTrue(np.array_equal(hubbeam.run(SPINUP, **keys).data, plain.data))
        scene = {"beam": {"length": np.float64(8.0), "density": 2.7667e3, "area": 7.2968e-5,
                          "second_moment": 8.2189e-9, "youngs_modulus": np.float64(6.8952e10)},
                 "hub": {"radius": np.float32(0.0)},
                 "motion": {"kind": np.str_("spin-up"), "omega0": np.int64(4), "duration": 15.0},
                 "discretization": {"method": "amm", "ny": np.int64(4), "nx": 4},
                 "model": {"order": "first"}, "solver": {"rtol": 1e-8, "atol": 1e-10},
                 "output": {"t_end": 2.0, "dt_out": 0.01}}
        self.assertTrue(np.array_equal(hubbeam.run(scene).data, hubbeam.run(SPINUP, t_end=2).data))

    def test_numpy_arrays_are_lists(self):
        torque = os.path.join(SOURCE, "cases", "torque_tau10.toml")
        self.assertEqual(hubbeam.linearize(torque, np.float64(2.0), nx=np.int64(0))["A"].tolist(),
                         hubbeam.linearize(torque, 2.0, nx=0)["A"].tolist())
        by_list = hubbeam.modes(SPINUP, [0.0, 2.0], harmonics=[1, 2], nx=0)
        by_array = hubbeam.modes(SPINUP, np.array([0.0, 2.0], dtype=np.float32), harmonics=np.array([1, 2]),
                                 nx=np.int64(0))
        self.assertEqual(by_array["rad_s"].tolist(), by_list["rad_s"].tolist())
        step = os.path.join(SOURCE, "cases", "controlled_step.toml")
        r = hubbeam.run(step, t_end=0.2, sensitivities=np.array(["kp", "E"]))
        self.assertEqual(r.columns, hubbeam.run(step, t_end=0.2, sensitivities=["kp", "E"]).columns)
        self.assertIn("d_tip_uy/d_E", r.columns)

    def test_a_string_is_no_number_and_the_message_names_the_keyword(self):
        for keys, keyword in (({"ny": "4"}, "ny"), ({"t_end": "1"}, "t_end"), ({"ny": 4.0}, "ny"),
                              ({"rtol": np.str_("1e-8")}, "rtol"), ({"discretization.nx": "2"}, "discretization.nx"),
                              ({"ny": np.bool_(True)}, "ny"), ({"method": 3}, "method")):
            with self.subTest(keys=keys):
                with self.assertRaises(ValueError) as caught:
                    hubbeam.run(SPINUP, **keys)
                self.assertTrue(str(caught.exception).startswith(keyword + ": expected "), str(caught.exception))
                self.assertNotIn("--", str(caught.exception))


class PandasTest(unittest.TestCase):
    def test_to_pandas_has_the_columns_and_their_units(self):
        import pandas as pd

        r = hubbeam.run(SPINUP, t_end=1)
        df = r.to_pandas()
        self.assertIsInstance(df, pd.DataFrame)
        self.assertEqual(list(df.columns), list(r.columns))
        self.assertTrue(np.array_equal(df.to_numpy(), r.data))
        self.assertEqual(df.attrs["units"]["tip_uy"], "m")
        self.assertEqual(df.attrs["units"]["t"], "s")
        self.assertEqual(df.attrs["units"]["theta_dot"], "rad/s")
        self.assertEqual(set(df.attrs["units"]), set(r.columns))  # every column has its unit
        self.assertEqual(df.attrs["summary"]["variant"], r.variant)

    def test_without_pandas_to_pandas_says_what_to_install(self):
        script = ("import sys; sys.modules['pandas'] = None\n"
                  "import hubbeam\n"
                  "r = hubbeam.run(sys.argv[1], t_end=0.1)\n"
                  "try:\n    r.to_pandas()\nexcept ImportError as e:\n    print(e)\n")
        out = subprocess.run([sys.executable, "-c", script, SPINUP], capture_output=True, text=True, timeout=60)
        self.assertIn("python3-pandas", out.stdout, out.stderr)


class ImportTest(unittest.TestCase):
    def test_a_python_without_numpy_is_told_how(self):
        # -S: no site-packages, as a python3 of its own (pyenv, conda) without Debian's numpy and dask would be.
        out = subprocess.run([sys.executable, "-S", "-c", "import hubbeam"], capture_output=True, text=True,
                             timeout=60)
        self.assertNotEqual(out.returncode, 0)
        last = out.stderr.strip().splitlines()[-1]
        self.assertIn("venv --system-site-packages", last)
        self.assertIn(sys.version.split()[0], last)

    def test_the_documented_virtual_environment_imports_it(self):
        # docs/python.md: a venv over the system's Python and its packages, hubbeam on PYTHONPATH.
        with tempfile.TemporaryDirectory() as d:
            venv = os.path.join(d, "venv")
            subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", venv], check=True,
                           timeout=60)
            out = subprocess.run([os.path.join(venv, "bin", "python"), "-c",
                                  "import sys, hubbeam; print(sys.prefix, hubbeam.run(sys.argv[1], t_end=0.1).completed)",
                                  SPINUP], capture_output=True, text=True, timeout=60)
            self.assertEqual(out.returncode, 0, out.stderr)
            self.assertEqual(out.stdout.split(), [venv, "True"])


class DocsTest(unittest.TestCase):
    def test_the_modes_example_of_docs_python_runs(self):
        # docs/python.md "Modes and linearized models", run as a user would from the source folder.
        with open(os.path.join(SOURCE, "docs", "python.md")) as f:
            page = f.read()
        start = page.index("```python\n", page.index("## Modes and linearized models")) + 10
        example = page[start:page.index("```", start)]
        out = subprocess.run([sys.executable, "-c", example], capture_output=True, text=True, cwd=SOURCE, timeout=120)
        self.assertEqual(out.returncode, 0, out.stderr)
        first = out.stdout.splitlines()[0]
        # The first bending mode at rest: the cantilever's 1.8751^2 sqrt(EI/(m L^4)) / (2 pi) = 0.46327 Hz.
        self.assertTrue(first.startswith("bending 1 [0.4633"), first)


class TorqueLawTest(unittest.TestCase):
    """hubbeam.run(..., torque=f): a hub driven by a Python callable of (t, state)."""
    STEP = os.path.join(SOURCE, "cases", "controlled_step.toml")

    def test_a_controlled_scene_has_its_columns_as_the_command_line_writes_them(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "step.csv")
            p = cli("run", self.STEP, "--t-end", "3", "-o", out)
            self.assertEqual(p.returncode, 0, p.stderr)
            header, rows = read_csv(out)
            r = hubbeam.run(self.STEP, t_end=3)
            self.assertEqual(list(r.columns), header)
            self.assertEqual(header[-3:], ["tau", "theta_ref", "work"])
            self.assertTrue(np.array_equal(r.data, rows))

    def test_a_law_in_python_equals_the_same_law_in_the_scene(self):
        # The scene's own PD law with its saturation, written in Python: the same rows to the tolerance.
        kp, kd, tau_max, angle = 64.45, 90.2, 10.0, 0.5
        seen = []

        def law(t, state):
            seen.append(sorted(state))
            return float(np.clip(-kp * (state["theta"] - angle) - kd * state["theta_dot"], -tau_max, tau_max))

        ref = hubbeam.run(self.STEP, t_end=5)
        r = hubbeam.run(self.STEP, t_end=5, torque=law)
        self.assertTrue(r.completed, r.failure)
        self.assertEqual(list(r.columns), list(ref.columns[:10]) + ["tau", "work"])
        self.assertEqual(seen[0], ["theta", "theta_dot", "tip_uy", "tip_uy_dot"])
        self.assertLess(abs(r.theta - ref.theta).max(), 1e-7)
        self.assertLess(abs(r.tau - ref.tau).max(), 1e-5)
        self.assertLessEqual(abs(r.tau).max(), tau_max)

    def test_the_tip_values_are_the_rows_and_an_exception_in_the_law_is_raised(self):
        tips = {}

        def law(t, state):
            tips[t] = (state["tip_uy"], state["theta"])
            return 1.0 if t < 1.0 else 0.0

        r = hubbeam.run(SPINUP, t_end=2, torque=law, error_check="off")  # no re-runs: the last call at t is the row's
        self.assertTrue(r.completed, r.failure)
        for t, uy, theta in zip(r.t, r.tip_uy, r.theta):
            if t in tips:  # the row's own torque: the state it saw is the row's (u_y(L) summed another way)
                self.assertEqual(tips[t][1], theta)
                self.assertAlmostEqual(tips[t][0], uy, delta=1e-12 * abs(uy) + 1e-300)

        def broken(t, state):
            if t > 0.5:
                raise ZeroDivisionError("law failed")
            return 0.0

        with self.assertRaisesRegex(ZeroDivisionError, "law failed"):
            hubbeam.run(SPINUP, t_end=1, torque=broken)
        with self.assertRaisesRegex(ValueError, "torque: expected a callable"):
            hubbeam.run(SPINUP, t_end=1, torque=3.0)

    def test_the_law_must_return_a_real_number(self):
        # Python's and numpy's real numbers are torques; anything else raises a TypeError naming the law and what
        # it returned, not a conversion's message.
        for tau in (1, 1.0, np.float32(1.0), np.float64(1.0), np.int64(1)):
            r = hubbeam.run(SPINUP, t_end=0.5, torque=lambda t, s, tau=tau: tau)
            self.assertTrue(r.completed, r.failure)
            self.assertEqual(r.tau[-1], 1.0)
        for tau, shown in ((None, "None (NoneType)"), ("1.0", "'1.0' (str)"), ([1.0], "[1.0] (list)"),
                           (1j, "1j (complex)"), (np.complex128(1.0), "(complex128)"), (True, "True (bool)"),
                           (np.array([1.0]), "(ndarray)")):
            def spin_law(t, state, tau=tau):
                return tau
            with self.subTest(tau=tau):
                with self.assertRaises(TypeError) as caught:
                    hubbeam.run(SPINUP, t_end=0.5, torque=spin_law)
                text = str(caught.exception)
                self.assertTrue(text.startswith("torque law "), text)
                self.assertIn("spin_law", text)
                self.assertIn(shown, text)
                self.assertIn("expected a real number", text)

    def test_an_exception_in_the_law_is_raised_as_itself(self):
        class LawError(Exception):
            pass

        raised = LawError("sensor lost")

        def law(t, state):
            if t > 0.2:
                raise raised
            return 0.0

        with self.assertRaises(LawError) as caught:
            hubbeam.run(SPINUP, t_end=1, torque=law)
        self.assertIs(caught.exception, raised)


class ModalDampingTest(unittest.TestCase):
    """[damping] flap_ratios, edge_ratios (docs/model.md section 11.5) reach Python's modes and runs as the command
    line's: the named modes have the ratios given, the others none, and a run counts the energy they dissipate."""

    def test_named_modes_have_their_ratios_and_a_run_its_dissipated_energy(self):
        # An array key from Python is its numbers separated by commas, as rotor.pitch_offsets (docs/scene.md).
        m = hubbeam.modes(SPINUP, 0.0, nx=0, ny=4, method="fem", edge_ratios="0.02, 0.05")
        self.assertEqual(list(m["kind"]), ["bending"] * 4)
        np.testing.assert_allclose(m["damping_ratio"], [0.02, 0.05, 0.0, 0.0], rtol=0, atol=1e-10)
        r = hubbeam.run(SPINUP, t_end=1.0, nx=0, ny=4, method="fem", edge_ratios="0.02, 0.05")
        self.assertIn("dissipated", r.columns)
        self.assertGreater(r["dissipated"][-1], 0.0)
        with self.assertRaisesRegex(ValueError, "^edge_ratios: expected an array of numbers >= 0"):
            hubbeam.modes(SPINUP, 0.0, nx=0, ny=4, method="fem", edge_ratios="0.02, -0.05")


class VersionTest(unittest.TestCase):
    def test_the_version_is_the_projects(self):
        import re

        with open(os.path.join(SOURCE, "CMakeLists.txt")) as f:
            project = re.search(r"project\(hubbeam VERSION (\S+)", f.read()).group(1)
        self.assertEqual(hubbeam.__version__, project)


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

    def test_damping_ratios_are_rayleighs(self):
        # Rayleigh damping gives each mode at rest zeta = alpha / (2 omega) + beta omega / 2 (docs/model.md section 11).
        alpha, beta = 0.05, 1e-3
        m = hubbeam.modes(SPINUP, 0.0, nx=0, **{"damping.mass_proportional": alpha,
                                                "damping.stiffness_proportional": beta})
        for omega, zeta in zip(m["undamped_rad_s"], m["damping_ratio"]):
            self.assertAlmostEqual(zeta, alpha / (2 * omega) + beta * omega / 2, places=9)

    def test_a_spin_under_its_weight_gives_the_command_lines_floquet_modes(self):
        # The wind turbine's blade spinning under its weight in a vertical plane has no steady state: hubbeam.modes
        # takes the periodic motion's Floquet modes (docs/model.md section 10.1), those hubbeam modes writes; gravity
        # is a small perturbation of this blade, its first flap and edge modes within 1 % of the weightless blade's.
        blade = os.path.join(SOURCE, "cases", "wind_turbine_blade.toml")
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "modes.csv")
            p = cli("modes", blade, "--omega", "1.2", "--harmonics", "none", "-o", out)
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertTrue(p.stdout.startswith("analysis    Floquet over one revolution"), p.stdout)
            with open(out, newline="") as f:
                rows = list(csv.DictReader(f))
        m = hubbeam.modes(blade, 1.2, harmonics=None)
        self.assertEqual(list(m["label"]), [r["label"] for r in rows])
        np.testing.assert_array_equal(m["rad_s"], [float(r["rad_s"]) for r in rows])
        np.testing.assert_array_equal(m["damping_ratio"], [float(r["damping_ratio"]) for r in rows])
        weightless = hubbeam.modes(blade, 1.2, harmonics=None, **{"gravity.g": 0.0})
        for kind in ("flap", "edge"):
            ratio = m["rad_s"][m["kind"] == kind][0] / weightless["rad_s"][weightless["kind"] == kind][0]
            self.assertAlmostEqual(ratio, 1.0, delta=0.01, msg=kind)

    def test_bad_spin_rates_raise_valueerror(self):
        torque = os.path.join(SOURCE, "cases", "torque_tau10.toml")
        for call in (lambda: hubbeam.modes(SPINUP, None), lambda: hubbeam.modes(SPINUP, "3"),
                     lambda: hubbeam.modes(SPINUP, [1.0, "2"]), lambda: hubbeam.modes(SPINUP, True),
                     lambda: hubbeam.modes(SPINUP, []), lambda: hubbeam.modes(SPINUP, -1.0),
                     lambda: hubbeam.modes(SPINUP, 1e300, nx=4),
                     lambda: hubbeam.linearize(torque, None), lambda: hubbeam.linearize(torque, "3"),
                     lambda: hubbeam.linearize(torque, [1.0]), lambda: hubbeam.linearize(torque, float("nan")),
                     lambda: hubbeam.linearize(torque, 1e300)):
            with self.assertRaises(ValueError) as caught:
                call()
            self.assertTrue(str(caught.exception).startswith("omega: expected"), str(caught.exception))
        self.assertEqual(len(hubbeam.modes(SPINUP, np.int64(2), nx=0)["omega"]), 4)  # numpy's numbers are rates

    def test_critical_speeds_are_the_command_lines(self):
        # The critical speeds of hubbeam.modes are those hubbeam modes --critical writes, for the harmonics asked.
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "critical.csv")
            p = cli("modes", SPINUP, "--nx", "0", "--omega", "0:6:1", "--harmonics", "1,2", "--critical", out, "-q")
            self.assertEqual(p.returncode, 0, p.stderr)
            with open(out, newline="") as f:
                rows = list(csv.DictReader(f))
        c = hubbeam.modes(SPINUP, np.arange(0.0, 6.5, 1.0), harmonics=[1, 2], nx=0)["critical"]
        self.assertGreater(len(rows), 0)
        self.assertEqual(list(c["label"]), [r["label"] for r in rows])
        self.assertEqual(list(c["harmonic"]), [int(r["harmonic"]) for r in rows])
        for column in ("omega", "rad_s", "hz"):
            self.assertEqual(list(c[column]), [float(r[column]) for r in rows], column)
        for bad in (0, [1, 1001], [1.5], "2", True, [[1]], [], "None"):
            with self.assertRaises(ValueError) as caught:
                hubbeam.modes(SPINUP, 0.0, harmonics=bad, nx=0)
            self.assertTrue(str(caught.exception).startswith("harmonics: expected"), str(caught.exception))
        # None searches no critical speed: the same modes, and no crossing though the rates pass 1P and 2P.
        for none in (None, "none"):
            n = hubbeam.modes(SPINUP, np.arange(0.0, 6.5, 1.0), harmonics=none, nx=0)
            self.assertEqual(len(n["critical"]["omega"]), 0)
            np.testing.assert_array_equal(n["rad_s"], hubbeam.modes(SPINUP, np.arange(0.0, 6.5, 1.0), nx=0)["rad_s"])

    def test_modes_is_the_command_lines_table_column_for_column(self):
        # hubbeam.modes and hubbeam modes -o / --critical give one table: each CSV column but the variant's is a key
        # of the result holding the same values (round-trip exact), and the result has no other columns. A damped
        # scene, so that growth, undamped_rad_s and damping_ratio are not zero, to 6 rad/s past 1P, 2P and 3P.
        scene = os.path.join(SOURCE, "cases", "damped_appendage.toml")
        with tempfile.TemporaryDirectory() as d:
            paths = {"modes": os.path.join(d, "modes.csv"), "critical": os.path.join(d, "critical.csv")}
            p = cli("modes", scene, "--omega", "0:6:0.5", "-o", paths["modes"], "--critical", paths["critical"], "-q")
            self.assertEqual(p.returncode, 0, p.stderr)
            tables = {}
            for name, path in paths.items():
                with open(path, newline="") as f:
                    reader = csv.DictReader(f)
                    tables[name] = (reader.fieldnames, list(reader))
        m = hubbeam.modes(scene, np.arange(0.0, 6.25, 0.5))
        variant = ["method", "ny", "nx", "nz", "nt", "order", "drive"]
        for name, result in (("modes", m), ("critical", m["critical"])):
            header, rows = tables[name]
            self.assertGreater(len(rows), 2, name)
            self.assertEqual(header[:len(variant)], variant, name)
            own = header[len(variant):]
            self.assertEqual(sorted(own), sorted(k for k in result if k not in ("variant", "critical", "scene_file")), name)
            for column in own:
                if result[column].dtype.kind == "U":
                    self.assertEqual(list(result[column]), [r[column] for r in rows], column)
                else:
                    np.testing.assert_array_equal(result[column], [float(r[column]) for r in rows], column)
            for r in rows:
                self.assertTrue(m["variant"].startswith(f"{r['method']}_nx{r['nx']}_ny{r['ny']}_{r['drive']}_{r['order']}"))
        self.assertTrue(np.all(m["growth"] < 0.0))  # the damping's decay

    def test_a_controlled_scene_gives_the_closed_loop_as_the_command_line_does(self):
        # The command line's modes CSV and linearize CSVs of a scene with [control] are the closed loop: the
        # controller's stiffness turns the free hub's rigid rotation into a mode of kind "hub".
        scene = os.path.join(SOURCE, "cases", "controlled_step.toml")
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "modes.csv")
            self.assertEqual(cli("modes", scene, "--omega", "0,1", "-o", out, "-q").returncode, 0)
            with open(out, newline="") as f:
                rows = list(csv.DictReader(f))
            prefix = os.path.join(d, "lin")
            self.assertEqual(cli("linearize", scene, "--omega", "1", "-o", prefix).returncode, 0)
            matrices = {name: read_csv_named(f"{prefix}-{name}.csv") for name in "ABCD"}
            open_loop = {name: read_csv_named(f"{prefix}-open-{name}.csv") for name in "ABCD"}
        m = hubbeam.modes(scene, [0.0, 1.0])
        self.assertEqual(list(m["kind"]), [r["kind"] for r in rows])
        self.assertIn("hub", list(m["kind"]))
        self.assertEqual(list(m["mode"]), [int(r["mode"]) for r in rows])
        self.assertEqual(list(m["label"]), [r["label"] for r in rows])
        for column in ("omega", "rad_s", "hz", "dimensionless", "growth", "undamped_rad_s", "damping_ratio", "mac"):
            np.testing.assert_array_equal(m[column], [float(r[column]) for r in rows], column)  # round-trip exact
        lin = hubbeam.linearize(scene, 1.0)
        for name, (rows_, columns, values) in matrices.items():
            np.testing.assert_array_equal(lin[name], values, name)
        self.assertEqual(lin["inputs"], matrices["B"][1])
        self.assertEqual(lin["states"], matrices["A"][1])
        for name, (rows_, columns, values) in open_loop.items():
            np.testing.assert_array_equal(lin["open"][name], values, "open " + name)
        self.assertEqual(lin["open"]["inputs"], open_loop["B"][1])

    def test_linearize_shapes_and_names(self):
        lin = hubbeam.linearize(os.path.join(SOURCE, "cases", "torque_tau10.toml"), 2.0, nx=0)
        self.assertEqual(lin["A"].shape, (10, 10))
        self.assertEqual(lin["inputs"], ["tau"])
        self.assertEqual(lin["outputs"], ["tip_uy", "theta"])


if __name__ == "__main__":
    unittest.main()


class ElastoDynTest(unittest.TestCase):
    UNIFORM = os.path.join(SOURCE, "tests", "scenes", "uniform_blade.toml")

    def test_mode_shapes_are_the_command_lines_file_and_fit_the_closed_form(self):
        # hubbeam.elastodyn_mode_shapes gives the coefficients hubbeam modes --elastodyn writes, each set summing
        # to 1; the uniform blade's flap 1 (AMM: its basis holds the clamped-free mode) is the closed form's fit,
        # here by numpy's least squares with c_6 eliminated (no code of hubbeam's).
        r = hubbeam.elastodyn_mode_shapes(self.UNIFORM, omega=0.0)
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "blade_modes.dat")
            p = cli("modes", self.UNIFORM, "--omega", "0", "--elastodyn", out, "-q")
            self.assertEqual(p.returncode, 0, p.stderr)
            with open(out) as f:
                lines = f.read().splitlines()
        self.assertEqual(lines, r["section"].splitlines())
        self.assertEqual(len(lines), 16)
        for i, name in enumerate(("BldFl1Sh", "BldFl2Sh", "BldEdgSh")):
            written = [float(line.split()[0]) for line in lines[1 + 5 * i:6 + 5 * i]]
            self.assertEqual(written, list(r[name]["coefficients"]), name)
            self.assertAlmostEqual(sum(written), 1.0, delta=1e-12)
        self.assertEqual(r["BldFl1Sh"]["mode"], "flap 1")
        bl = 1.8751040687119611664
        sigma = (np.cosh(bl) + np.cos(bl)) / (np.sinh(bl) + np.sin(bl))
        x = np.linspace(0.0, 1.0, 201)
        phi = np.cosh(bl * x) - np.cos(bl * x) - sigma * (np.sinh(bl * x) - np.sin(bl * x))
        phi /= phi[-1]
        A = np.stack([x ** k - x ** 6 for k in range(2, 6)], axis=1)
        c = np.linalg.lstsq(A, phi - x ** 6, rcond=None)[0]
        exact = np.append(c, 1.0 - c.sum())
        # A coefficient moves by at most ||A^+|| sqrt(201) times the shape's error, below 1e-9 of the tip for AMM.
        tolerance = 2.0 / np.linalg.svd(A, compute_uv=False).min() * np.sqrt(201.0) * 1e-9
        np.testing.assert_allclose(r["BldFl1Sh"]["coefficients"], exact, rtol=0, atol=tolerance)
        self.assertAlmostEqual(r["BldFl1Sh"]["residual"], np.sqrt(np.mean((A @ c + x ** 6 - phi) ** 2)), delta=1e-9)
        np.testing.assert_allclose(r["BldFl1Sh"]["phi"], phi, rtol=0, atol=1e-9)

    def test_a_beam_in_the_plane_has_no_flap_mode_shapes(self):
        with self.assertRaises(ValueError) as caught:
            hubbeam.elastodyn_mode_shapes(SPINUP)
        self.assertIn("discretization.nz > 0", str(caught.exception))
        self.assertEqual(len(hubbeam.elastodyn_mode_shapes(SPINUP, nz=2)["BldEdgSh"]["coefficients"]), 5)


class OutOfPlaneTest(unittest.TestCase):
    def test_blade_keys_columns_and_mode_kinds(self):
        # The out-of-plane keys as keywords: the columns tip_uz and tip_phi appear, and modes names flap, edge and
        # twist; flap and lead-lag of a uniform blade obey omega_flap^2 = omega_lag^2 + Omega^2 (docs/model.md 12).
        blade = {"beam": {"length": 1.0, "density": 1.0, "area": 1.0, "second_moment": 1.0, "youngs_modulus": 1.0,
                          "shear_modulus": 1.0, "torsion_constant": 0.5},
                 "motion": {"kind": "spin-up", "omega0": 1.0, "duration": 1.0},
                 "discretization": {"method": "fem", "ny": 4, "nx": 0},
                 "output": {"t_end": 0.5}}
        r = hubbeam.run(blade, nz=4, nt=2, pitch=0.1)
        self.assertEqual(tuple(r.columns[-2:]), ("tip_uz", "tip_phi"))
        self.assertEqual(tuple(hubbeam.run(blade).columns[-1:]), ("jacobi",))
        m = hubbeam.modes(blade, [6.0], nz=4, nt=2)
        kinds = set(m["kind"])
        self.assertEqual(kinds, {"flap", "edge", "twist"})
        flap = np.sort(m["rad_s"][m["kind"] == "flap"])[0]
        edge = np.sort(m["rad_s"][m["kind"] == "edge"])[0]
        self.assertAlmostEqual(flap ** 2, edge ** 2 + 36.0, delta=1e-8 * flap ** 2)
        with self.assertRaises(ValueError) as caught:
            hubbeam.run(blade, nt=2, shear_modulus=0.0)
        self.assertIn("shear_modulus: expected a number > 0 with discretization.nt > 0", str(caught.exception))
