"""Figures from Python (docs/python.md, "Figures"): what Result.plot and plot_campbell draw, read back from the
figure's own lines and labels (never its bytes), and the package's import without matplotlib. Needs SOURCE_DIR."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402

import hubbeam  # noqa: E402

SOURCE = os.environ["SOURCE_DIR"]
SPINUP = os.path.join(SOURCE, "cases", "spinup_omega4.toml")


def legend_texts(ax):
    legend = ax.get_legend()
    return [t.get_text() for t in legend.get_texts()], legend.get_title().get_text()


class RunFigures(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.r = hubbeam.run(SPINUP, t_end=3, nx=0)

    def test_tip_draws_tip_uy_against_time_named_by_the_scene(self):
        fig = self.r.plot()
        (ax,) = fig.axes
        (line,) = ax.get_lines()
        self.assertTrue(np.array_equal(line.get_xdata(), self.r.t))
        self.assertTrue(np.array_equal(line.get_ydata(), self.r.tip_uy))
        self.assertEqual((ax.get_xlabel(), ax.get_ylabel()), ("t (s)", "tip_uy (m)"))
        texts, _ = legend_texts(ax)
        self.assertEqual(texts, [f"spinup_omega4, {self.r.variant}"])

    def test_one_panel_per_unit(self):
        fig = self.r.plot("hub")
        self.assertEqual([a.get_ylabel() for a in fig.axes], ["theta (rad)", "theta_dot (rad/s)"])
        self.assertTrue(np.array_equal(fig.axes[1].get_lines()[0].get_ydata(), self.r.theta_dot))
        fig = self.r.plot("energies")
        (ax,) = fig.axes
        self.assertEqual(ax.get_ylabel(), "kinetic, potential, jacobi (J)")
        drawn = {line.get_label().split(",")[0]: line.get_ydata() for line in ax.get_lines()}
        self.assertEqual(set(drawn), {"kinetic", "potential", "jacobi"})
        self.assertTrue(np.array_equal(drawn["potential"], self.r.potential))

    def test_runs_compared_in_one_axes(self):
        other = hubbeam.run(SPINUP, t_end=3, nx=0, method="fem", ny=6)
        fig = self.r.plot(label="AMM")
        other.plot(ax=fig.axes[0], label="FEM")
        texts, _ = legend_texts(fig.axes[0])
        self.assertEqual(texts, ["AMM", "FEM"])
        self.assertTrue(np.array_equal(fig.axes[0].get_lines()[1].get_ydata(), other.tip_uy))

    def test_a_blade_draws_its_flap_and_twist(self):
        blade = hubbeam.run(os.path.join(SOURCE, "cases", "wind_turbine_blade.toml"), t_end=0.5)
        fig = blade.plot("tip")
        self.assertEqual([a.get_ylabel() for a in fig.axes], ["tip_uy, tip_uz (m)", "tip_phi (rad)"])
        self.assertTrue(np.array_equal(fig.axes[0].get_lines()[1].get_ydata(), blade.tip_uz))

    def test_bad_columns_are_refused(self):
        with self.assertRaisesRegex(ValueError, "what: expected one of tip, axial, hub, energies or columns"):
            self.r.plot("tau")  # no driven hub: no tau column
        with self.assertRaisesRegex(ValueError, "ax: expected 2 Axes"):
            self.r.plot("hub", ax=self.r.plot().axes[0])

    def test_loaded_run_draws_the_same_figure(self):
        with tempfile.TemporaryDirectory() as d:
            back = hubbeam.load(self.r.save(os.path.join(d, "r.npy")))
        a, b = self.r.plot("energies"), back.plot("energies")
        for la, lb in zip(a.axes[0].get_lines(), b.axes[0].get_lines(), strict=True):
            self.assertEqual(la.get_label(), lb.get_label())
            self.assertTrue(np.array_equal(la.get_xydata(), lb.get_xydata()))


class Campbell(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.m = hubbeam.modes(SPINUP, np.arange(0, 12.1, 1.0), method="bim", ny=8, nx=0)

    def test_tracked_lines_excitation_lines_and_critical_speeds(self):
        m = self.m
        fig = hubbeam.plot_campbell(m)
        (ax,) = fig.axes
        lines = {line.get_label(): line for line in ax.get_lines()}
        for k in range(1, 5):
            pick = m["label"] == f"bending {k}"
            self.assertTrue(np.array_equal(lines[f"bending {k}"].get_xdata(), m["omega"][pick]))
            self.assertTrue(np.array_equal(lines[f"bending {k}"].get_ydata(), m["hz"][pick]))
        self.assertNotIn("bending 5", lines)  # count=4 per kind
        # n x Omega in Hz: at 12 rad/s, 12 n / (2 pi).
        for n in (1, 2, 3):
            self.assertAlmostEqual(lines[f"{n} x Omega"].get_ydata()[-1], 12.0 * n / (2 * np.pi), places=12)
        crit = lines["critical speeds"]
        c = m["critical"]
        shown = np.isin(c["label"], [f"bending {k}" for k in range(1, 5)])
        self.assertTrue(np.array_equal(crit.get_xdata(), c["omega"][shown]))
        # Each marker sits on its excitation line: hz = n Omega / (2 pi), an independent check of the crossings.
        self.assertTrue(np.allclose(crit.get_ydata(), c["harmonic"][shown] * c["omega"][shown] / (2 * np.pi),
                                    rtol=1e-6))
        self.assertEqual((ax.get_xlabel(), ax.get_ylabel()), ("spin rate Omega (rad/s)", "frequency (Hz)"))
        _, title = legend_texts(ax)
        self.assertEqual(title, f"spinup_omega4\n{m['variant']}")

    def test_kinds_and_harmonics_chosen(self):
        fig = hubbeam.plot_campbell(self.m, count=2, harmonics=[5])
        labels = [line.get_label() for line in fig.axes[0].get_lines()]
        self.assertEqual(labels[:3], ["bending 1", "bending 2", "5 x Omega"])


class CampbellOfADampedBlade(unittest.TestCase):
    """A damped blade's modes (cases/helicopter_blade.toml): overdamped modes have frequency 0, which the diagram
    never draws nor lets meet an excitation line; a tabulated blade's long variant name; the lines told apart."""

    @classmethod
    def setUpClass(cls):
        cls.m = hubbeam.modes(os.path.join(SOURCE, "cases", "helicopter_blade.toml"), np.arange(0.0, 30.1, 5.0),
                              source="assembled")

    def test_an_overdamped_mode_is_not_drawn_and_meets_no_line(self):
        m = self.m
        self.assertTrue((m["hz"] == 0).any(), "the damped blade has overdamped modes (else this test shows nothing)")
        fig = hubbeam.plot_campbell(m, kinds="all", count=64)
        lines = {line.get_label(): line for line in fig.axes[0].get_lines()}
        drawn = [(label, line) for label, line in lines.items() if " x Omega" not in label and label != "critical speeds"]
        self.assertTrue(drawn)
        for label, line in drawn:
            self.assertTrue((np.asarray(line.get_ydata()) > 0).all(), label)
            pick = (m["label"] == label) & (m["hz"] > 0)
            self.assertTrue(np.array_equal(line.get_xdata(), m["omega"][pick]), label)
        c = m["critical"]
        if "critical speeds" in lines:
            self.assertTrue((np.asarray(lines["critical speeds"].get_ydata()) > 0).all())
            self.assertEqual(len(lines["critical speeds"].get_xdata()), int((np.asarray(c["hz"]) > 0).sum()))

    def test_the_excitation_lines_are_dashed_apart(self):
        fig = hubbeam.plot_campbell(self.m, harmonics=[1, 2, 3, 4])
        styles = [(line.get_linestyle(), tuple(line._dash_pattern[1] or ())) for line in fig.axes[0].get_lines()
                  if line.get_label().endswith(" x Omega")]
        self.assertEqual(len(styles), 4)
        self.assertEqual(len(set(styles)), 4, styles)

    def test_a_long_variant_name_is_cut_and_the_axes_stay_in_the_figure(self):
        blade = os.path.join(SOURCE, "cases", "blade_from_file.toml")
        # The blade's variant name, with its fields and terms, runs past the legend's 48 characters.
        m = hubbeam.modes(blade, [0.0, 1.0, 2.0], source="assembled", g=0.0)  # no weight: steady
        r = hubbeam.run(blade, t_end=0.1, source="assembled")
        self.assertGreater(len(r.variant), 60)
        for fig, text in ((hubbeam.plot_campbell(m), lambda ax: legend_texts(ax)[1]),
                          (r.plot(), lambda ax: legend_texts(ax)[0][0])):
            ax = fig.axes[0]
            shown = text(ax)
            self.assertLessEqual(max(len(part) for part in shown.split("\n")), 80, shown)  # column, scene, 48
            self.assertIn("\u2026", shown)
            fig.canvas.draw()
            box = ax.get_position()
            self.assertGreater(box.width, 0.45, "the legend pushed the axes aside")
            self.assertTrue(0.0 <= box.x0 and box.x1 <= 1.0)

    def test_a_result_is_no_modes_table(self):
        r = hubbeam.run(SPINUP, t_end=0.1, nx=0)
        with self.assertRaisesRegex(ValueError, r"^m: expected the modes of hubbeam.modes\(scene, omega=\[...\]\) "
                                                r"\(a dict with omega, hz, label, kind and critical\), got a run's Result"):
            hubbeam.plot_campbell(r)
        with self.assertRaisesRegex(ValueError, r"got a list$"):
            hubbeam.plot_campbell([1, 2])


class NotebookDisplay(unittest.TestCase):
    def test_in_a_notebook_each_figure_is_one_image(self):
        # Cells run by nbconvert: a figure returned by the cell's last line, kept in a name, or drawn by a line that
        # ends in a semicolon, shows as one image, never two; a figure of the user's that a plot draws into as well.
        try:
            import nbconvert  # noqa: F401
            import ipykernel  # noqa: F401
        except ImportError as e:
            self.fail(f"the notebooks run with nbconvert and ipykernel: apt-get install jupyter-nbconvert "
                      f"python3-ipykernel ({e})")
        cells = ["import hubbeam, matplotlib.pyplot as plt",
                 f"r = hubbeam.run({SPINUP!r}, t_end=0.1, nx=0)\nm = hubbeam.modes({SPINUP!r}, [0.0, 1.0], nx=0)",
                 "r.plot()", "fig = r.plot('hub')", "r.plot('energies');", "hubbeam.plot_campbell(m)",
                 "fig, ax = plt.subplots()\nr.plot(ax=ax);"]
        nb = {"cells": [{"cell_type": "code", "execution_count": None, "metadata": {}, "outputs": [],
                         "source": c} for c in cells],
              "metadata": {"kernelspec": {"name": "python3", "display_name": "Python 3", "language": "python"}},
              "nbformat": 4, "nbformat_minor": 5}
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "once.ipynb")
            with open(path, "w") as f:
                json.dump(nb, f)
            done = subprocess.run([sys.executable, "-m", "nbconvert", "--to", "notebook", "--execute", "--output-dir",
                                   d, "--output", "out.ipynb", path], capture_output=True, text=True,
                                  env=dict(os.environ, PYDEVD_DISABLE_FILE_VALIDATION="1"), timeout=300)
            self.assertEqual(done.returncode, 0, done.stderr[-3000:])
            with open(os.path.join(d, "out.ipynb")) as f:
                out = json.load(f)["cells"]
        for cell in out[2:]:
            images = [o for o in cell["outputs"] if "image/png" in o.get("data", {})]
            self.assertEqual(len(images), 1, cell["source"])

    def test_outside_a_notebook_the_figure_is_matplotlibs_own_in_pyplot(self):
        # plt.show() shows it: a figure of pyplot's, of matplotlib's Figure class.
        import matplotlib.pyplot as plt
        from matplotlib.figure import Figure
        fig = hubbeam.run(SPINUP, t_end=0.1, nx=0).plot()
        self.assertIs(type(fig), Figure)
        self.assertIn(fig.number, plt.get_fignums())
        plt.close(fig)


class WithoutMatplotlib(unittest.TestCase):
    def test_the_package_imports_and_a_figure_says_what_to_install(self):
        code = ("import sys; sys.modules['matplotlib'] = None; sys.modules['matplotlib.pyplot'] = None\n"
                "import hubbeam\n"
                f"r = hubbeam.run({SPINUP!r}, t_end=0.1, nx=0)\n"
                "try:\n    r.plot()\nexcept ImportError as e:\n    print(e)\n")
        done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("figures need matplotlib: install python3-matplotlib", done.stdout)


if __name__ == "__main__":
    unittest.main()


class Animation(unittest.TestCase):
    """hubbeam plot animate: the beam's points in each frame of the script, against the fields and the run's theta
    turned here by numpy; the GIF's frames counted by PIL."""

    HUBBEAM = os.environ.get("HUBBEAM", "")

    def animate(self, scene, d, times, *, turned=True):
        base = os.path.join(d, "run.csv")
        subprocess.run([self.HUBBEAM, "run", scene, "--t-end", str(max(times)), "--fields-at",
                        ",".join(map(str, times)), "--fields-points", "9", "-o", base], check=True,
                       capture_output=True)
        fields = os.path.join(d, "run-fields.csv")
        files = [fields, base] if turned else [fields]
        done = subprocess.run([self.HUBBEAM, "plot", "animate", *files, "-o", os.path.join(d, "anim")],
                              capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(os.path.join(d, "anim.gp")) as f:
            script = f.read()
        blocks = script.split("$beam << EOD\n")[1].split("EOD\n")[0].strip("\n").split("\n\n\n")
        drawn = [np.loadtxt(b.splitlines(), ndmin=2) for b in blocks]
        f = np.genfromtxt(fields, delimiter=",", names=True)
        r = np.genfromtxt(base, delimiter=",", names=True)
        return script, drawn, f, r

    def test_plane_frames_are_the_fields_turned_by_theta(self):
        times = [0, 5, 10, 15, 20]
        with tempfile.TemporaryDirectory() as d:
            script, drawn, f, r = self.animate(SPINUP, d, times)
            from PIL import Image
            with Image.open(os.path.join(d, "anim.gif")) as gif:
                self.assertEqual(gif.n_frames, len(times))
        self.assertEqual(len(drawn), len(times))
        for k, t in enumerate(times):
            rows = f[f["t"] == t]
            th = r["theta"][np.argmin(abs(r["t"] - t))]
            along = rows["x"] + rows["ux"]
            x = np.cos(th) * along - np.sin(th) * rows["uy"]
            y = np.sin(th) * along + np.cos(th) * rows["uy"]
            self.assertTrue(np.allclose(drawn[k][:, 0], x, rtol=0, atol=1e-12))
            self.assertTrue(np.allclose(drawn[k][:, 1], y, rtol=0, atol=1e-12))
            self.assertTrue(np.all(drawn[k][:, 2] == 0))
        for label in ("title 'hub'", "title 'tip path'", "title 'beam'", "X (m, inertial frame)"):
            self.assertIn(label, script)
        self.assertIn("plot $hub", script)

    def test_a_blade_is_drawn_in_three_dimensions_with_its_flap(self):
        with tempfile.TemporaryDirectory() as d:
            script, drawn, f, _ = self.animate(os.path.join(SOURCE, "cases", "helicopter_blade.toml"), d, [0, 1],
                                               turned=False)
        self.assertIn("splot $hub", script)
        self.assertIn("X (m, the hub", script)
        for k, t in enumerate((0, 1)):
            rows = f[f["t"] == t]
            self.assertTrue(np.array_equal(drawn[k][:, 2], rows["uz"]))
            self.assertTrue(np.allclose(drawn[k][:, 0], rows["x"] + rows["ux"], rtol=0, atol=1e-12))
        self.assertLess(drawn[1][-1, 2], -0.01)  # released undeformed at t = 0, the blade droops under its weight

    def test_a_run_csv_is_no_fields_csv(self):
        with tempfile.TemporaryDirectory() as d:
            self.animate(SPINUP, d, [0, 1])
            done = subprocess.run([self.HUBBEAM, "plot", "animate", os.path.join(d, "run.csv"), "-o",
                                   os.path.join(d, "bad")], capture_output=True, text=True)
            self.assertEqual(done.returncode, 2)
            self.assertIn("expected a column x in its header", done.stderr)
            self.assertFalse(os.path.exists(os.path.join(d, "bad.gif")))
