"""Figures from Python (docs/python.md, "Figures"): what Result.plot and plot_campbell draw, read back from the
figure's own lines and labels (never its bytes), and the package's import without matplotlib. Needs SOURCE_DIR."""
import json
import os
import re
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


def texts_outside(fig):
    """The texts of fig (titles, axis labels, annotations, legends) whose drawn extent leaves the figure: a label or
    a key cut off."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    texts = list(fig.texts)
    for a in fig.axes:
        texts += [a.title, a.xaxis.label, a.yaxis.label, *a.texts]
        if a.get_legend() is not None:
            texts += [*a.get_legend().get_texts(), a.get_legend().get_title()]
    box = fig.bbox
    outside = []
    for t in texts:
        if not t.get_visible() or not t.get_text():
            continue
        e = t.get_window_extent(renderer)
        if not (e.x0 >= box.x0 - 0.5 and e.x1 <= box.x1 + 0.5 and e.y0 >= box.y0 - 0.5 and e.y1 <= box.y1 + 0.5):
            outside.append(t.get_text())
    return outside


def per_rev_lines(ax):
    return {line.get_label(): line for line in ax.get_lines() if re.fullmatch(r"\d+P", line.get_label())}


class Campbell(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.m = hubbeam.modes(SPINUP, np.arange(0, 12.1, 1.0), method="bim", ny=8, nx=0)

    def test_tracked_lines_excitation_lines_and_critical_speeds(self):
        m = self.m
        fig = hubbeam.plot_campbell(m, harmonics=[1, 2, 3], max_frequency=1000.0)
        ax, below = fig.axes
        lines = {line.get_label(): line for line in ax.get_lines()}
        damping = {line.get_label(): line for line in below.get_lines()}
        for k in range(1, 5):
            pick = m["label"] == f"bending {k}"
            self.assertTrue(np.array_equal(lines[f"bending {k}"].get_xdata(), m["omega"][pick]))
            self.assertTrue(np.array_equal(lines[f"bending {k}"].get_ydata(), m["hz"][pick]))
            self.assertTrue(np.array_equal(damping[f"bending {k}"].get_ydata(), 100 * m["damping_ratio"][pick]))
        self.assertNotIn("bending 5", lines)  # count=4 per kind
        # n P in Hz: at 12 rad/s, 12 n / (2 pi).
        for n in (1, 2, 3):
            self.assertAlmostEqual(lines[f"{n}P"].get_ydata()[-1], 12.0 * n / (2 * np.pi), places=12)
        crit = lines["critical speeds"]
        c = m["critical"]
        shown = np.isin(c["label"], [f"bending {k}" for k in range(1, 5)])
        self.assertTrue(np.array_equal(crit.get_xdata(), c["omega"][shown]))
        # Each marker sits on its excitation line: hz = n Omega / (2 pi), an independent check of the crossings.
        self.assertTrue(np.allclose(crit.get_ydata(), c["harmonic"][shown] * c["omega"][shown] / (2 * np.pi),
                                    rtol=1e-6))
        self.assertEqual((below.get_xlabel(), ax.get_ylabel()), ("spin rate Omega (rad/s)", "frequency (Hz)"))
        self.assertEqual(ax.get_title(), f"spinup_omega4, {hubbeam.plots.short_name(m['variant'])}")
        self.assertEqual(texts_outside(fig), [])

    def test_kinds_and_harmonics_chosen(self):
        fig = hubbeam.plot_campbell(self.m, count=2, harmonics=[5])
        labels = [line.get_label() for line in fig.axes[0].get_lines()]
        self.assertEqual(labels[:3], ["bending 1", "bending 2", "5P"])


class CampbellOfARotorInGroundResonance(unittest.TestCase):
    """A rotor on a soft support (cases/ground_resonance_balanced.toml) through its ground-resonance band: the mode that
    grows there is the hub's whirl, not of the kinds drawn by default; it is drawn all the same, by Python and by the
    command line alike, so that no choice of kinds hides an instability."""

    HUBBEAM = os.environ.get("HUBBEAM", "")
    SCENE = os.path.join(SOURCE, "cases", "ground_resonance_balanced.toml")

    @classmethod
    def setUpClass(cls):
        # From 0.5 rad/s, so that the line that grows in the band is tracked from rest as the hub's whirl, above the
        # four lowest of its kind that the diagram draws by default.
        cls.m = hubbeam.modes(cls.SCENE, np.arange(0.5, 20.1, 0.5))
        cls.growing = set(cls.m["label"][(cls.m["growth"] > 0) & (cls.m["hz"] > 0)])

    def test_python_draws_every_growing_line(self):
        self.assertTrue(self.growing, "the band holds an unstable mode (else this test shows nothing)")
        fig = hubbeam.plot_campbell(self.m)
        drawn = {line.get_label() for line in fig.axes[0].get_lines()}
        self.assertLessEqual(self.growing, drawn)

    def test_the_command_line_draws_every_growing_line(self):
        with tempfile.TemporaryDirectory() as d:
            table = os.path.join(d, "modes.csv")
            subprocess.run([self.HUBBEAM, "modes", self.SCENE, "--omega", "0.5:20:0.5", "-o", table], check=True,
                           capture_output=True)
            done = subprocess.run([self.HUBBEAM, "plot", "campbell", table, "-o", os.path.join(d, "c")],
                                  capture_output=True, text=True)
            self.assertEqual(done.returncode, 0, done.stderr)
            with open(os.path.join(d, "c.gp")) as f:
                script = f.read()
        for label in self.growing:
            self.assertIn(f"{label} (unstable)", script)


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
        fig = hubbeam.plot_campbell(m, kinds="all", count=64, harmonics=[1, 2, 3], max_frequency=1e6)
        lines = {line.get_label(): line for line in fig.axes[0].get_lines()}
        drawn = [(label, line) for label, line in lines.items()
                 if not re.fullmatch(r"\d+P", label) and label not in ("critical speeds", "unstable")]
        self.assertTrue(drawn)
        for label, line in drawn:
            self.assertTrue((np.asarray(line.get_ydata()) > 0).all(), label)
            pick = (m["label"] == label) & (m["hz"] > 0)
            self.assertTrue(np.array_equal(line.get_xdata(), m["omega"][pick]), label)
        c = m["critical"]
        if "critical speeds" in lines:
            self.assertTrue((np.asarray(lines["critical speeds"].get_ydata()) > 0).all())
            self.assertEqual(len(lines["critical speeds"].get_xdata()), int((np.asarray(c["hz"]) > 0).sum()))
        # every mode named at its end, none of the names cut off however many
        self.assertEqual(texts_outside(fig), [])

    def test_the_per_rev_lines_are_named_and_the_blades_multiples_heavier(self):
        fig = hubbeam.plot_campbell(self.m, harmonics=[1, 2, 3, 4], blades=2)
        ax = fig.axes[0]
        widths = {label: line.get_linewidth() for label, line in per_rev_lines(ax).items()}
        self.assertEqual(set(widths), {"1P", "2P", "3P", "4P"})
        self.assertGreater(widths["2P"], widths["1P"])
        self.assertEqual(widths["2P"], widths["4P"])
        self.assertEqual(widths["1P"], widths["3P"])
        names = [t.get_text() for t in ax.texts]
        for k in range(1, 5):
            self.assertEqual(names.count(f"{k}P"), 1)
        self.assertIn("2P and its multiples (2 blades)", [t.get_text() for t in fig.axes[1].get_legend().get_texts()])

    def test_a_long_variant_name_is_cut_and_the_axes_stay_in_the_figure(self):
        blade = os.path.join(SOURCE, "cases", "blade_from_file.toml")
        # The blade's variant name, with its fields and terms, runs past the legend's 48 characters.
        m = hubbeam.modes(blade, [0.0, 1.0, 2.0], source="assembled", g=0.0)  # no weight: steady
        r = hubbeam.run(blade, t_end=0.1, source="assembled")
        self.assertGreater(len(r.variant), 60)
        for fig, text in ((hubbeam.plot_campbell(m), lambda ax: ax.get_title()),
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
                                                r"\(a dict with omega, hz, label, kind and critical\) or a modes CSV's "
                                                r"path, got a run's Result"):
            hubbeam.plot_campbell(r)
        with self.assertRaisesRegex(ValueError, r"got a list$"):
            hubbeam.plot_campbell([1, 2])


class CampbellOfASyntheticRotor(unittest.TestCase):
    """The table of tests/tools/test_plot.cpp's rotor, from its CSV: two flap modes (the second unstable at the
    highest rate), an edge mode in backward and forward whirl, a flap mode at 40 Hz above the cutoff; at 0, 1, 2 and
    3 revolutions per second."""

    REVS = 2 * np.pi * np.arange(4.0)

    @staticmethod
    def flap1(w):
        return 1.0 + 0.1 * w

    @staticmethod
    def flap2(w):
        return 5.0 + 0.05 * w

    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.TemporaryDirectory()
        cls.path = os.path.join(cls.dir.name, "rotor-modes.csv")
        rows = ["method,ny,nx,order,drive,omega,mode,kind,rad_s,hz,dimensionless,growth,undamped_rad_s,"
                "damping_ratio,label,mac"]
        for w in cls.REVS:
            last = w == cls.REVS[-1]
            for n, (label, hz, growth, zeta) in enumerate([
                    ("flap 1", cls.flap1(w), -0.1, 0.02), ("BW edge 1", 3.0 - 0.05 * w, -0.1, 0.01),
                    ("FW edge 1", 3.0 + 0.05 * w, -0.1, 0.01),
                    ("flap 2", cls.flap2(w), 0.2 if last else -0.1, -0.005 if last else 0.01),
                    ("flap 3", 40.0, -0.1, 0.01)], start=1):
                rows.append(f"amm,8,0,first,prescribed,{w!r},{n},{label.split()[-2]},{2 * np.pi * hz!r},{hz!r},1,"
                            f"{growth!r},{2 * np.pi * hz!r},{zeta!r},{label},1")
        # and at the highest rate a divergence: a real root that grows (0 Hz, damping ratio -1)
        rows.append(f"amm,8,0,first,prescribed,{cls.REVS[-1]!r},6,overdamped,0,0,0,0.3,0.3,-1,overdamped 1,1")
        with open(cls.path, "w") as f:
            f.write("\n".join(rows) + "\n")

    @classmethod
    def tearDownClass(cls):
        cls.dir.cleanup()

    def draw(self, **options):
        options = {"spin_unit": "rpm", "blades": 3, "operating_range": (150.0, 180.0), **options}
        fig = hubbeam.plot_campbell(self.path, **options)
        ax, below = fig.axes
        return fig, ax, below, {line.get_label(): line for line in ax.get_lines()}

    def test_two_panels_every_label_inside_the_figure(self):
        fig, ax, below, _ = self.draw()
        self.assertEqual(len(fig.axes), 2)
        self.assertEqual(below.get_ylabel(), "damping ratio (%)")
        self.assertEqual(ax.get_title(), "rotor, amm, Ny = 8")
        self.assertEqual(texts_outside(fig), [])
        # the modes named at their ends, none in a legend box over the axes
        names = [t.get_text() for t in ax.texts]
        for name in ("flap 1", "flap 2 (unstable)", "BW edge 1", "FW edge 1"):
            self.assertEqual(names.count(name), 1, name)
        self.assertIsNone(ax.get_legend())

    def test_rpm_per_rev_lines_and_cutoff(self):
        fig, ax, below, lines = self.draw()
        w_max = self.REVS[-1]
        rpm = self.REVS * 60 / (2 * np.pi)
        self.assertTrue(np.allclose(lines["flap 1"].get_xdata(), [0, 60, 120, 180], rtol=0, atol=1e-12))
        self.assertTrue(np.allclose(lines["flap 1"].get_ydata(), self.flap1(self.REVS)))
        self.assertAlmostEqual(ax.get_xlim()[1], 180.0, places=9)
        self.assertEqual(below.get_xlabel(), "spin rate Omega (rpm)")
        # 1P to 6P by default, each f = k Omega / 2 pi, the multiples of 3 blades heavier
        per_rev = per_rev_lines(ax)
        self.assertEqual(sorted(per_rev, key=lambda k: int(k[:-1])), [f"{k}P" for k in range(1, 7)])
        for k in range(1, 7):
            line = per_rev[f"{k}P"]
            self.assertAlmostEqual(line.get_xdata()[-1], rpm[-1], places=9)
            self.assertAlmostEqual(line.get_ydata()[-1], k * w_max / (2 * np.pi), places=9)
            self.assertEqual(line.get_linewidth() > 2, k % 3 == 0, k)
        # the cutoff 1.1 x 6P at the highest rate: flap 3 (40 Hz) left out
        self.assertAlmostEqual(ax.get_ylim()[1], 1.1 * 6 * w_max / (2 * np.pi), places=9)
        self.assertNotIn("flap 3", lines)
        self.assertNotIn("flap 3", [t.get_text() for t in ax.texts])
        # flap 1 meets 1P where 1 + 0.1 omega = omega / 2 pi: marked, in rpm
        meets = 1.0 / (1.0 / (2 * np.pi) - 0.1)
        crit = lines["critical speeds"]
        self.assertTrue(np.any(np.isclose(crit.get_xdata(), meets * 60 / (2 * np.pi), rtol=1e-12)
                               & np.isclose(crit.get_ydata(), meets / (2 * np.pi), rtol=1e-12)))
        # a lower cutoff: only the lines with a point at or below 4 Hz (flap 2 starts at 5 Hz)
        _, ax4, _, lines4 = self.draw(max_frequency=4.0)
        self.assertEqual([k for k in lines4 if k.endswith(" 1") or k.endswith(" 2")], ["flap 1", "BW edge 1", "FW edge 1"])
        self.assertEqual(ax4.get_ylim()[1], 4.0)
        # rad/s: the rates as the table has them
        _, _, below_rad, lines_rad = self.draw(spin_unit="rad/s", operating_range=None)
        self.assertTrue(np.allclose(lines_rad["flap 1"].get_xdata(), self.REVS))
        self.assertEqual(below_rad.get_xlabel(), "spin rate Omega (rad/s)")

    def test_unstable_marked_damping_below_whirl_dashed(self):
        fig, ax, below, lines = self.draw()
        rpm_max = 180.0
        marks = [line for line in ax.get_lines() if line.get_label() == "unstable"]
        self.assertEqual(len(marks), 2)  # flap 2's, and the divergence's at 0 Hz
        self.assertTrue(np.allclose(marks[0].get_xdata(), [rpm_max]))
        self.assertTrue(np.allclose(marks[0].get_ydata(), [self.flap2(self.REVS[-1])]))
        self.assertTrue(np.allclose(marks[1].get_xdata(), [rpm_max]))
        self.assertTrue(np.array_equal(marks[1].get_ydata(), [0.0]))
        for mark in marks:
            self.assertEqual(mark.get_marker(), "x")
        damping = {line.get_label(): line for line in below.get_lines()}
        self.assertTrue(np.allclose(damping["flap 2"].get_ydata(), [1.0, 1.0, 1.0, -0.5]))
        self.assertTrue(np.allclose(damping["unstable"].get_ydata(), [-0.5]))
        self.assertEqual(lines["BW edge 1"].get_linestyle(), "--")
        self.assertEqual(lines["FW edge 1"].get_linestyle(), ":")
        self.assertEqual(lines["flap 1"].get_linestyle(), "-")
        self.assertEqual(lines["BW edge 1"].get_color(), lines["FW edge 1"].get_color())
        self.assertNotEqual(lines["flap 1"].get_color(), lines["flap 2"].get_color())
        key = [t.get_text() for t in below.get_legend().get_texts()]
        for entry in ("critical speeds", "unstable", "3P and its multiples (3 blades)", "backward whirl (BW)",
                      "forward whirl (FW)", "operating range"):
            self.assertIn(entry, key)
        # the operating range shaded in both panels, from 150 to 180 rpm
        for a in (ax, below):
            spans = [p for p in a.patches if p.get_label() == "operating range"]
            self.assertEqual(len(spans), 1)
            x = a.transData.inverted().transform(spans[0].get_verts())[:, 0]  # its corners, in data x
            self.assertTrue(np.allclose((x.min(), x.max()), (150.0, 180.0), rtol=0, atol=1e-9))

    def test_bad_options_are_refused(self):
        with self.assertRaisesRegex(ValueError, r"^spin_unit: expected 'rad/s' or 'rpm', got 'hz'$"):
            hubbeam.plot_campbell(self.path, spin_unit="hz")
        with self.assertRaisesRegex(ValueError, r"^operating_range: expected \(lo, hi\), two spin rates >= 0 in the "
                                                r"spin_unit \(rad/s\) with lo < hi, got \(180, 150\)$"):
            hubbeam.plot_campbell(self.path, operating_range=(180, 150))
        with self.assertRaisesRegex(ValueError, r"^blades: expected an integer >= 1, got 0$"):
            hubbeam.plot_campbell(self.path, blades=0)
        with self.assertRaisesRegex(ValueError, r"^max_frequency: expected a frequency > 0 \(Hz\), got -1$"):
            hubbeam.plot_campbell(self.path, max_frequency=-1)
        with self.assertRaisesRegex(ValueError, r"^max_frequency: expected a frequency at or above the lowest mode "
                                                r"drawn \(1 Hz\), got 0.5$"):
            hubbeam.plot_campbell(self.path, max_frequency=0.5)


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
