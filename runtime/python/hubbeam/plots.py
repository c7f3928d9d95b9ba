"""Figures of runs and modes with matplotlib (docs/python.md, "Figures"): Result.plot() and plot_campbell(m).

matplotlib is imported only when a figure is asked for, so that the package imports without it.
"""
from __future__ import annotations

import math
import os
from typing import Any, Mapping, Sequence

import numpy as np

# What Result.plot(what) draws for each named kind; a column a run does not have is left out (tip_uz and tip_phi
# exist for a blade only, tau and work with a driven hub).
KINDS = {
    "tip": ("tip_uy", "tip_uz", "tip_phi"),
    "axial": ("tip_ux1", "tip_ux"),
    "hub": ("theta", "theta_dot", "tau"),
    "energies": ("kinetic", "potential", "jacobi", "work", "dissipated"),
}

# The mode kinds a Campbell diagram draws by default: the beam's bending and twist, not its axial modes (hundreds
# of times higher) nor the hub's.
CAMPBELL_KINDS = ("bending", "edge", "flap", "twist")


def pyplot():
    """matplotlib.pyplot, or ImportError saying what to install."""
    try:
        import matplotlib.pyplot as plt
    except ImportError:
        raise ImportError("hubbeam: figures need matplotlib: install python3-matplotlib (Debian) or matplotlib in this "
                          "environment; the numbers are in .data and to_pandas() without it") from None
    return plt


# The longest variant name a legend or a Campbell diagram's title shows whole: a blade's with every term runs past 60
# characters, which would push the axes out of the figure; a longer one is cut with an ellipsis (the whole name is r.variant).
LEGEND_NAME_CHARS = 48


def short_name(name: str, cap: int = LEGEND_NAME_CHARS) -> str:
    """name as a legend shows it: whole up to cap characters, else its first cap - 1 and an ellipsis."""
    return name if len(name) <= cap else name[:cap - 1] + "\u2026"


def _subplots(plt, *args, **options):
    """plt.subplots, but in a notebook (an IPython kernel with matplotlib's inline backend) of a Figure subclass that
    IPython shows once: pyplot shows every figure at the end of the cell that drew it, and a cell that returns the
    figure (`r.plot()` as its last line) would show it a second time as its result. The subclass's image is drawn
    by matplotlib's own formatter, which first takes the figure out of pyplot's list: shown as the cell's result,
    it is then not shown again at the cell's end; kept (`fig = r.plot()`) or drawn by a line ending in a
    semicolon, pyplot shows it, once."""
    figure_class = _shown_once()
    out = plt.subplots(*args, **options, **({"FigureClass": figure_class} if figure_class else {}))
    if figure_class is not None:
        _shown_once()  # the inline backend registers its image formats with its first figure: now
    return out


_SHOWN_ONCE: Any = None


def _shown_once():
    """The Figure subclass of _subplots, drawn by matplotlib's formatter for each image format IPython has for
    Figure, after closing it in pyplot (checked at each figure: the formats are registered with the first figure,
    and may be chosen again with %config InlineBackend.figure_formats); None outside a notebook's inline backend."""
    global _SHOWN_ONCE
    import sys

    import matplotlib

    ipython = sys.modules.get("IPython")
    shell = ipython.get_ipython() if ipython is not None and hasattr(ipython, "get_ipython") else None
    if shell is None or "inline" not in matplotlib.get_backend():
        return None
    from matplotlib.figure import Figure

    if _SHOWN_ONCE is None:
        # Named Figure: a cell's result reads "<Figure size 750x440 with 1 Axes>" in text, as matplotlib's own.
        _SHOWN_ONCE = type("Figure", (Figure,), {
            "__doc__": "A figure of hubbeam's in a notebook: shown once, as a cell's result or by pyplot.",
            "__module__": __name__})
    for formatter in shell.display_formatter.formatters.values():
        printers = getattr(formatter, "type_printers", {})
        draw = printers.get(Figure)
        if draw is None or getattr(printers.get(_SHOWN_ONCE), "__wrapped__", None) is draw:
            continue

        def closing(fig, draw=draw):
            pyplot().close(fig)  # out of pyplot's list: the cell's end does not show it again
            return draw(fig)

        closing.__wrapped__ = draw
        formatter.for_type(_SHOWN_ONCE, closing)
    return _SHOWN_ONCE


def scene_name(scene_file: str) -> str:
    """A scene's name for a legend: its file's name without .toml, or the dict scene's placeholder."""
    return os.path.splitext(os.path.basename(scene_file))[0] if scene_file and not scene_file.startswith("<") \
        else (scene_file or "scene")


def _columns(result, what: Any) -> list[str]:
    """The columns a plot draws: a kind's (KINDS) that the run has, or the names given, each checked."""
    if isinstance(what, str) and what in KINDS:
        names = [c for c in KINDS[what] if c in result.columns]
    elif isinstance(what, str):
        names = [what]
    else:
        names = list(what)
    if not names:
        raise ValueError(f"what: expected one of {', '.join(KINDS)} or column names, got {what!r}")
    for c in names:
        if c not in result.columns or c == "t":
            raise ValueError(f"what: expected one of {', '.join(KINDS)} or columns of the run "
                             f"({', '.join(result.columns[1:])}), got {c!r}")
    return names


def plot_result(result, what: Any = "tip", *, ax: Any = None, label: str | None = None):
    """Draws columns of a run against time, one panel per unit; returns the figure. what: "tip" (tip_uy, and
    tip_uz and tip_phi for a blade), "axial", "hub" (theta, theta_dot, tau), "energies", a column's name or a list
    of them. ax: an Axes (or one per panel) to draw into, to compare runs in one figure; label: the legend's name
    of this run (default: the scene's name and the variant)."""
    from . import unit_of

    plt = pyplot()
    names = _columns(result, what)
    groups: dict[str, list[str]] = {}
    for c in names:
        groups.setdefault(unit_of(c), []).append(c)
    if ax is None:
        fig, axes = _subplots(plt, len(groups), 1, sharex=True, squeeze=False,
                              figsize=(7.5, 2.2 + 2.0 * len(groups)), layout="constrained")
        axes = list(axes[:, 0])
    else:
        axes = list(np.atleast_1d(ax))
        if len(axes) != len(groups):
            raise ValueError(f"ax: expected {len(groups)} Axes (one per unit: {', '.join(groups)}), got {len(axes)}")
        fig = axes[0].figure
    name = label if label is not None else f"{scene_name(result.scene_file)}, {short_name(result.variant)}"
    for a, (unit, columns) in zip(axes, groups.items()):
        for c in columns:
            a.plot(result.t, result[c], label=name if len(columns) == 1 else f"{c}, {name}")
        a.set_ylabel(f"{', '.join(columns)} ({unit})" if unit else ", ".join(columns))
        a.grid(True, alpha=0.3)
        a.legend(fontsize="small")
    axes[-1].set_xlabel("t (s)")
    return fig


# The shades of each mode family, darkest first, as `hubbeam plot campbell` draws them: flap blue, edge and a planar
# beam's (in-plane) bending green, twist purple, axial orange, the hub's pink, any other kind brown; none of them the
# greys of the per-rev lines nor the red of the critical speeds and the instabilities.
FAMILY_SHADES = {
    "flap": ("#08306b", "#08519c", "#2171b5", "#4292c6", "#6baed6"),
    "edge": ("#00441b", "#006d2c", "#238b45", "#41ab5d", "#74c476"),
    "bending": ("#00441b", "#006d2c", "#238b45", "#41ab5d", "#74c476"),
    "twist": ("#3f007d", "#54278f", "#6a51a3", "#807dba", "#9e9ac8"),
    "axial": ("#7f2704", "#a63603", "#d94801", "#f16913", "#fd8d3c"),
    "hub": ("#49006a", "#7a0177", "#ae017e", "#dd3497", "#f768a1"),
}
OTHER_SHADES = ("#543005", "#8c510a", "#bf812d", "#a6761d", "#dfc27d")

# A rotor's whirl, the word a mode's kind or label may begin with ("BW edge 1"), and its line: backward whirl dashed,
# forward whirl dotted, collective (and a blade's own mode, which names none) solid.
WHIRL_STYLES = {"BW": "--", "FW": ":", "collective": "-", "": "-"}

# The per-rev lines drawn by default: 1P to this (or to NP for a rotor of more blades).
DEFAULT_PER_REV = 6

# The colours of the per-rev lines (the rotor's N-per-rev multiples darker and heavier), the critical speeds, the
# instabilities and the operating range.
PER_REV_COLOUR, PER_REV_BLADES_COLOUR = "0.6", "0.2"
CRITICAL_COLOUR, UNSTABLE_COLOUR, RANGE_COLOUR = "red", "#b2182b", "#fde9b0"


def mode_name(text: str) -> tuple[str, str, int]:
    """A mode's kind or label read word by word: its whirl (BW, FW, collective or ""), its family ("flap", ...) and
    its number (the label's last word; 0 where there is none)."""
    words = str(text).split()
    whirl = words.pop(0) if words and words[0] in WHIRL_STYLES and words[0] else ""
    family = words[0] if words else ""
    number = int(words[-1]) if len(words) > 1 and words[-1].isdigit() else 0
    return whirl, family, number


def family_colour(family: str, number: int) -> str:
    """Mode `number` of a family: the family's hue, darker the lower the mode (shades cycle past 5)."""
    shades = FAMILY_SHADES.get(family, OTHER_SHADES)
    return shades[(max(number, 1) - 1) % len(shades)]


def spread_labels(heights: Sequence[float], gap: float, top: float) -> list[float]:
    """Heights (in data units) of labels at a panel's right edge moved apart so that no two are closer than gap,
    inside [0, top] where they fit; in the order given."""
    order = sorted(range(len(heights)), key=lambda i: heights[i])
    y = [min(max(float(heights[i]), 0.0), top) for i in order]
    for i in range(1, len(y)):
        y[i] = max(y[i], y[i - 1] + gap)
    if y and y[-1] > top:
        y[-1] = top
        for i in range(len(y) - 2, -1, -1):
            y[i] = min(y[i], y[i + 1] - gap)
    out = [0.0] * len(y)
    for rank, i in enumerate(order):
        out[i] = y[rank]
    return out


def campbell_cutoff(highest_per_rev: int, omega_max: float, lowest_top: float) -> float:
    """The frequency (Hz) above which a Campbell diagram leaves its modes out when max_frequency is not given: 1.1 n
    Omega_max / 2 pi (a little above the highest per-rev line at the highest rate), raised to 1.1 times the lowest
    mode's highest frequency so that at least one is drawn; inf without per-rev lines or at rest alone (as
    `hubbeam plot campbell`)."""
    if highest_per_rev <= 0 or not omega_max > 0:
        return math.inf
    return 1.1 * max(highest_per_rev * omega_max / (2 * math.pi), lowest_top)


# The columns plot_campbell reads from a modes CSV (hubbeam modes -o), as numbers or as text.
_CSV_NUMBERS = ("omega", "hz", "damping_ratio", "growth")
_CSV_VARIANT = ("method", "ny", "nx", "nz", "nt", "order", "drive")


def modes_from_csv(path: Any) -> dict:
    """A modes CSV of one variant (hubbeam modes -o FILE) as the arrays of hubbeam.modes: omega, hz, damping_ratio,
    growth, kind, label (the kind and mode number in a file without tracking), variant and scene_file (the file's
    stem without -modes); no critical speeds. ValueError for a file of several variants or without the columns."""
    import csv

    from . import printable

    shown = printable(os.fspath(path))
    with open(path, newline="", encoding="utf-8-sig") as f:
        rows = list(csv.DictReader(f))
    needed = _CSV_NUMBERS + ("kind", "mode")
    if not rows or any(c not in rows[0] for c in needed):
        raise ValueError(f"{shown}: expected a modes CSV (hubbeam modes -o) with the columns {', '.join(needed)} "
                         f"and rows, got {'no rows' if not rows else 'a header without ' + ', '.join(c for c in needed if c not in rows[0])}")
    variants = {tuple(r.get(c, "") for c in _CSV_VARIANT) for r in rows}
    if len(variants) > 1:
        raise ValueError(f"{shown}: expected the modes of one variant (plot_campbell draws one), got {len(variants)}: "
                         f"write each with its own hubbeam modes -o, or draw them together with hubbeam plot campbell")
    m = {c: np.array([float(r[c]) for r in rows]) for c in _CSV_NUMBERS}
    m["kind"] = np.array([r["kind"] for r in rows])
    m["label"] = np.array([r["label"] if r.get("label") else f"{r['kind']} mode {r['mode']}" for r in rows])
    (variant,) = variants
    m["variant"] = f"{variant[0]}, Ny = {variant[1]}"  # as the command line's figure names one variant
    stem = os.path.splitext(os.path.basename(os.fspath(path)))[0]
    m["scene_file"] = stem[:-len("-modes")] if stem.endswith("-modes") else stem
    return m


def _crossings(omega, hz, n: int):
    """Where the straight segments between a line's points (by increasing rate) cross f = n omega / 2 pi: arrays of
    (omega, Hz), as `hubbeam plot campbell` marks them."""
    gap = hz - n * omega / (2 * np.pi)
    at = []
    for i in range(len(omega) - 1):
        ga, gb = gap[i], gap[i + 1]
        if ga == 0:
            at.append(omega[i])
        elif ga * gb < 0:
            at.append(omega[i] + (omega[i + 1] - omega[i]) * ga / (ga - gb))
    w = np.array(at, dtype=float)
    return w, n * w / (2 * np.pi)


def _campbell_arguments(m: Any, spin_unit: str, blades: Any, operating_range: Any, max_frequency: Any):
    """plot_campbell's arguments checked, each refusal naming its argument: the modes as a dict (read from a CSV's
    path), the blade count (0 where not given) and the operating range (lo, hi), or None."""
    from . import printable

    if isinstance(m, (str, os.PathLike)):
        m = modes_from_csv(m)
    if not isinstance(m, Mapping) or not all(k in m for k in ("omega", "hz", "label", "kind")):
        got = "a run's Result (draw it with r.plot(); a Campbell diagram needs hubbeam.modes(scene, omega=...))" \
            if hasattr(m, "columns") and hasattr(m, "data") else f"a {type(m).__name__}"
        raise ValueError(f"m: expected the modes of hubbeam.modes(scene, omega=[...]) (a dict with omega, hz, label, "
                         f"kind and critical) or a modes CSV's path, got {got}")
    if spin_unit not in ("rad/s", "rpm"):
        raise ValueError(f"spin_unit: expected 'rad/s' or 'rpm', got {printable(repr(spin_unit), 80)}")
    if blades is not None and (isinstance(blades, bool) or not isinstance(blades, (int, np.integer)) or blades < 1):
        raise ValueError(f"blades: expected an integer >= 1, got {printable(repr(blades), 80)}")
    span = None
    if operating_range is not None:
        try:
            lo, hi = (float(v) for v in operating_range)
        except (TypeError, ValueError):
            lo = hi = math.nan
        if not (0 <= lo < hi < math.inf):
            raise ValueError(f"operating_range: expected (lo, hi), two spin rates >= 0 in the spin_unit "
                             f"({spin_unit}) with lo < hi, got {printable(repr(operating_range), 80)}")
        span = (lo, hi)
    if max_frequency is not None and not (isinstance(max_frequency, (int, float, np.number))
                                          and 0 < max_frequency < math.inf):
        raise ValueError(f"max_frequency: expected a frequency > 0 (Hz), got {printable(repr(max_frequency), 80)}")
    return m, int(blades or 0), span


def _campbell_axes(plt, ax: Any):
    """The figure, the frequencies' axes and the damping ratios' below them (None where ax is one Axes)."""
    if ax is None:
        fig, (ax, axz) = _subplots(plt, 2, 1, sharex=True, figsize=(9.0, 6.5), layout="constrained",
                                   gridspec_kw={"height_ratios": (2.6, 1.0)})
        return fig, ax, axz
    axes = list(np.atleast_1d(ax))
    if len(axes) not in (1, 2):
        raise ValueError(f"ax: expected an Axes (the frequencies alone) or two (and the damping ratios below), "
                         f"got {len(axes)}")
    return axes[0].figure, axes[0], (axes[1] if len(axes) == 2 else None)


class _CampbellLines:
    """The modes' columns and which lines a Campbell diagram draws: the `count` lowest of each kind asked for, every
    line unstable at some rate, those that reach below the frequency cutoff `top`."""

    def __init__(self, m: Mapping, kinds: Sequence[str] | str, count: int, harmonics: list[int],
                 max_frequency: float | None):
        from . import printable

        self.omega, self.hz, self.labels, kind = (np.asarray(m[k]) for k in ("omega", "hz", "label", "kind"))
        n = len(self.omega)
        self.zeta = np.asarray(m["damping_ratio"], dtype=float) if "damping_ratio" in m else np.zeros(n)
        self.growth = np.asarray(m["growth"], dtype=float) if "growth" in m else np.zeros(n)
        family = np.array([mode_name(k)[1] for k in kind]) if n else np.array([], dtype=str)
        self.oscillates = self.hz > 0  # an overdamped mode's frequency is 0 (NaN compares False too)
        # A divergence: a real root that grows, at 0 Hz; any kind.
        self.divergent = ~self.oscillates & (self.growth > 0)
        keep = self.oscillates & (np.ones(n, bool) if kinds == "all" else np.isin(family, list(kinds)))
        per_kind: dict[str, list[str]] = {}
        for line, k in dict.fromkeys(zip(self.labels[keep], family[keep])):  # first appearance: the lowest first
            per_kind.setdefault(k, []).append(line)
        drawn = [line for lines in per_kind.values() for line in lines[:count]]
        # A line unstable at some rate is drawn whatever its rank, and whatever its kind unless kinds= leaves it out:
        # the default kinds hide no instability.
        unstable = self.oscillates & ((self.growth > 0) | (self.zeta < 0))
        if kinds is not CAMPBELL_KINDS:
            unstable &= keep
        drawn += [line for line in dict.fromkeys(self.labels[unstable]) if line not in drawn]
        keep = self.oscillates & (keep | np.isin(self.labels, drawn))
        # The cutoff: given, or a little above the highest per-rev line at the highest rate.
        self.omega_max = float(self.omega[keep].max()) if keep.any() else 0.0
        lowest = min(drawn, key=lambda line: self.hz[keep & (self.labels == line)][0], default=None)
        lowest_top = float(self.hz[keep & (self.labels == lowest)].max()) if lowest is not None else 0.0
        top = float(max_frequency) if max_frequency is not None else \
            campbell_cutoff(max(harmonics, default=0), self.omega_max, lowest_top)
        self.drawn = [line for line in drawn if (self.hz[keep & (self.labels == line)] <= top).any()]
        if not self.drawn and keep.any():  # a cutoff given below every mode (the default keeps the lowest)
            raise ValueError(f"max_frequency: expected a frequency at or above the lowest mode drawn "
                             f"({float(self.hz[keep].min()):g} Hz), got {printable(repr(max_frequency), 80)}")
        self.keep = keep & np.isin(self.labels, self.drawn)
        self.top = top if math.isfinite(top) else (1.05 * float(self.hz[self.keep].max()) if self.keep.any() else 1.0)

    def line(self, label: str):
        """One drawn line's rates, frequencies, damping ratios and growth rates, by increasing rate."""
        pick = self.keep & (self.labels == label)
        order = np.argsort(self.omega[pick], kind="stable")
        return (self.omega[pick][order], self.hz[pick][order], self.zeta[pick][order], self.growth[pick][order])


def _draw_campbell_modes(ax: Any, axz: Any, lines: _CampbellLines, scale: float) -> list:
    """Each drawn line in its family's shade and its whirl's dashes, in both panels, its unstable points crossed;
    a divergence crossed at 0 Hz. Returns each line's (name, colour, last frequency) for its label at the end."""
    ends = []
    for label in lines.drawn:
        w, f, z, g = lines.line(label)
        whirl, fam, number = mode_name(label)
        colour = family_colour(fam, number)
        style = dict(color=colour, linestyle=WHIRL_STYLES[whirl], linewidth=1.8, marker=".", markersize=4)
        ax.plot(w * scale, f, label=label, **style)
        unstable = (z < 0) | (g > 0)
        if axz is not None:
            axz.plot(w * scale, 100 * z, label=label, **style)
        if unstable.any():
            ax.plot(w[unstable] * scale, f[unstable], linestyle="none", marker="x", markersize=9, markeredgewidth=2,
                    color=UNSTABLE_COLOUR, label="unstable")
            if axz is not None:
                axz.plot(w[unstable] * scale, 100 * z[unstable], linestyle="none", marker="x", markersize=9,
                         markeredgewidth=2, color=UNSTABLE_COLOUR, label="unstable")
        ends.append((label + (" (unstable)" if unstable.any() else ""), colour, f[-1]))
    # A divergence is an instability too: a cross at 0 Hz, above only (its damping ratio, -1, would squash the lower
    # panel).
    divergent = lines.divergent
    if divergent.any():
        ax.plot(lines.omega[divergent] * scale, np.zeros(int(divergent.sum())), linestyle="none", marker="x",
                markersize=9, markeredgewidth=2, color=UNSTABLE_COLOUR, label="unstable", clip_on=False)
    return ends


def _draw_per_rev(ax: Any, m: Mapping, lines: _CampbellLines, harmonics: list[int], blades: int, scale: float):
    """The per-rev lines and their crossings with the modes (refined ones from hubbeam.modes where it searched that
    harmonic, else where the straight segments between rates cross them), each line named at its end. Returns the
    spin range drawn and whether a crossing was."""
    top, drawn = lines.top, lines.drawn
    w_lo = float(lines.omega[lines.keep].min()) if lines.keep.any() else 0.0
    w = np.array([w_lo, lines.omega_max if lines.omega_max > w_lo else w_lo + 1.0])
    crit = m.get("critical") or {}
    searched = set(int(k) for k in crit.get("harmonic", ()))
    cw, chz = [], []
    if searched:
        c_label, c_n = np.asarray(crit["label"]), np.asarray(crit["harmonic"])
        c_omega, c_hz = np.asarray(crit["omega"], dtype=float), np.asarray(crit["hz"], dtype=float)
        shown = np.isin(c_label, drawn) & np.isin(c_n, harmonics) & (c_hz > 0) & (c_hz <= top)
        cw += list(c_omega[shown])
        chz += list(c_hz[shown])
    for k in harmonics:
        heavy = blades > 1 and k % blades == 0
        ax.plot(w * scale, k * w / (2 * np.pi), color=PER_REV_BLADES_COLOUR if heavy else PER_REV_COLOUR,
                linewidth=2.4 if heavy else 0.9, label=f"{k}P", zorder=1.5)
        f_end = k * w[1] / (2 * np.pi)
        x_end, y_end = (w[1], f_end) if f_end <= top else (top * 2 * np.pi / k, top)
        ax.annotate(f"{k}P", (x_end * scale, y_end), xytext=(-3, -11 if f_end > top else 3),
                    textcoords="offset points", ha="right", fontsize="small", color="0.25")
        if k not in searched:
            for label in drawn:
                omega, hz, _, _ = lines.line(label)
                xw, xf = _crossings(omega, hz, k)
                cw += list(xw[xf <= top])
                chz += list(xf[xf <= top])
    if cw:
        ax.plot(np.array(cw) * scale, chz, linestyle="none", marker="o", markersize=6, color=CRITICAL_COLOUR,
                label="critical speeds", zorder=3)
    return w, bool(cw)


def _campbell_key(holder: Any, lines: _CampbellLines, ends: list, crossings: bool, blades: int,
                  operating_range: Any) -> None:
    """The key of what is not named at a line's end: critical speeds, instabilities, the blades' per-rev lines, the
    whirls' dashes, the operating range."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    key = []
    if crossings:
        key.append(Line2D([], [], linestyle="none", marker="o", color=CRITICAL_COLOUR, label="critical speeds"))
    if lines.divergent.any() or any(text.endswith(" (unstable)") for text, _, _ in ends):
        key.append(Line2D([], [], linestyle="none", marker="x", markersize=9, markeredgewidth=2,
                          color=UNSTABLE_COLOUR, label="unstable"))
    if blades > 1:
        key.append(Line2D([], [], color=PER_REV_BLADES_COLOUR, linewidth=2.4,
                          label=f"{blades}P and its multiples ({blades} blades)"))
    for whirl, text in (("BW", "backward whirl (BW)"), ("FW", "forward whirl (FW)")):
        if any(mode_name(line)[0] == whirl for line in lines.drawn):
            key.append(Line2D([], [], color="0.25", linestyle=WHIRL_STYLES[whirl], label=text))
    if operating_range is not None:
        key.append(Patch(color=RANGE_COLOUR, label="operating range"))
    if key:
        holder.legend(handles=key, fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)


def plot_campbell(m: Any, *, kinds: Sequence[str] | str = CAMPBELL_KINDS, count: int = 4,
                  harmonics: Sequence[int] | None = None, spin_unit: str = "rad/s", blades: int | None = None,
                  operating_range: Sequence[float] | None = None, max_frequency: float | None = None,
                  ax: Any = None, label: str | None = None):
    """A Campbell diagram of hubbeam.modes(...) (or of a modes CSV of one variant, by its path), as
    `hubbeam plot campbell` draws it: above, each tracked mode's frequency (Hz) against the spin rate, in its
    family's shade and its whirl's dashes, named at its line's end; the per-rev lines kP named at theirs and the
    critical speeds where the modes meet them; below, the damping ratios (%), unstable points marked in both panels;
    the operating range shaded. Returns the figure (docs/python.md, "Figures")."""
    m, blades, span = _campbell_arguments(m, spin_unit, blades, operating_range, max_frequency)
    harmonics = [int(n) for n in (range(1, max(DEFAULT_PER_REV, blades) + 1) if harmonics is None else harmonics)]
    plt = pyplot()
    fig, ax, axz = _campbell_axes(plt, ax)
    scale = 60 / (2 * np.pi) if spin_unit == "rpm" else 1.0
    lines = _CampbellLines(m, kinds, count, harmonics, max_frequency)
    ends = _draw_campbell_modes(ax, axz, lines, scale)
    w, crossings = _draw_per_rev(ax, m, lines, harmonics, blades, scale)
    # Each mode named at its line's end, right of the axes, the labels moved apart a line of text.
    for (text, colour, _), y in zip(ends, spread_labels([e[2] for e in ends], 0.045 * lines.top, lines.top)):
        ax.annotate(short_name(text), (1.0, y), xycoords=("axes fraction", "data"), xytext=(4, 0),
                    textcoords="offset points", va="center", color=colour, fontsize="small", annotation_clip=False)
    unit = "rpm" if spin_unit == "rpm" else "rad/s"
    panels = [ax] if axz is None else [ax, axz]
    if span is not None:
        for a in panels:
            a.axvspan(span[0], span[1], color=RANGE_COLOUR, zorder=0, label="operating range")
    ax.set_ylim(0.0, lines.top)
    ax.set_xlim(w[0] * scale, w[1] * scale)
    ax.set_ylabel("frequency (Hz)")
    for a in panels:
        a.grid(True, alpha=0.3)
    panels[-1].set_xlabel(f"spin rate Omega ({unit})")
    name = label if label is not None else f"{scene_name(m.get('scene_file', ''))}, {short_name(str(m.get('variant', '')))}"
    ax.set_title(name, fontsize="medium")
    if axz is not None:
        axz.axhline(0.0, color="black", linewidth=0.8)
        axz.set_ylabel("damping ratio (%)")
    # In the lower panel, whose right edge labels nothing.
    _campbell_key(axz if axz is not None else ax, lines, ends, crossings, blades, span)
    return fig
