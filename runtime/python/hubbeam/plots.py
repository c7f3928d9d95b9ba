"""Figures of runs and modes with matplotlib (docs/python.md, "Figures"): Result.plot() and plot_campbell(m).

matplotlib is imported only when a figure is asked for, so that the package imports without it.
"""
from __future__ import annotations

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


# The longest variant name a legend shows whole: a blade's with every term runs past 60 characters, which would
# push the axes out of the figure; a longer one is cut with an ellipsis (the whole name is r.variant).
LEGEND_NAME_CHARS = 48

# The excitation lines n x Omega drawn apart by their dashes, in order of n (then again, thinner).
HARMONIC_STYLES = ("--", "-.", ":", (0, (5, 2, 1, 2, 1, 2)), (0, (8, 3)), (0, (1, 4)))


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
    from . import UNITS

    plt = pyplot()
    names = _columns(result, what)
    groups: dict[str, list[str]] = {}
    for c in names:
        groups.setdefault(UNITS.get(c, ""), []).append(c)
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


def plot_campbell(m: dict, *, kinds: Sequence[str] | str = CAMPBELL_KINDS, count: int = 4,
                  harmonics: Sequence[int] | None = None, ax: Any = None, label: str | None = None):
    """A Campbell diagram of hubbeam.modes(...): each tracked mode's frequency (Hz) against the spin rate, the
    excitation lines n Omega for the harmonics (default: those the critical speeds were found for, else 1, 2, 3),
    each dashed its own way, and the critical speeds where the modes meet them. An overdamped mode (frequency 0: it
    does not oscillate) is not drawn at that rate and meets no line, as in the command line's diagram. kinds: the
    mode kinds drawn ("all" for every one); count: the lowest tracked modes of each kind drawn; returns the
    figure."""
    if not isinstance(m, Mapping) or not all(k in m for k in ("omega", "hz", "label", "kind", "critical")):
        got = "a run's Result (draw it with r.plot(); a Campbell diagram needs hubbeam.modes(scene, omega=...))" \
            if hasattr(m, "columns") and hasattr(m, "data") else f"a {type(m).__name__}"
        raise ValueError(f"m: expected the modes of hubbeam.modes(scene, omega=[...]) (a dict with omega, hz, label, "
                         f"kind and critical), got {got}")
    plt = pyplot()
    if ax is None:
        fig, ax = _subplots(plt, figsize=(9.0, 5.0), layout="constrained")
    else:
        fig = ax.figure
    omega, hz, labels, kind = (np.asarray(m[k]) for k in ("omega", "hz", "label", "kind"))
    oscillates = hz > 0  # an overdamped mode's frequency is 0 (NaN compares False too)
    keep = oscillates & (np.ones(len(omega), bool) if kinds == "all" else np.isin(kind, list(kinds)))
    per_kind: dict[str, list[str]] = {}
    for line, k in dict.fromkeys(zip(labels[keep], kind[keep])):  # first appearance: the lowest of each kind first
        per_kind.setdefault(k, []).append(line)
    drawn = [line for lines in per_kind.values() for line in lines[:count]]
    keep &= np.isin(labels, drawn)
    for line in drawn:
        pick = keep & (labels == line)
        ax.plot(omega[pick], hz[pick], marker=".", label=line)
    crit = m["critical"]
    shown = np.isin(np.asarray(crit["label"]), labels[keep]) & (np.asarray(crit["hz"], dtype=float) > 0)
    if harmonics is None:
        harmonics = sorted(set(int(n) for n in crit["harmonic"])) or [1, 2, 3]
    w = np.array([omega.min(), omega.max()]) if len(omega) else np.array([0.0, 1.0])
    top = hz[keep].max() if keep.any() else 1.0
    for i, n in enumerate(harmonics):
        ax.plot(w, n * w / (2 * np.pi), linestyle=HARMONIC_STYLES[i % len(HARMONIC_STYLES)],
                color="0.35" if i < len(HARMONIC_STYLES) else "0.6", linewidth=1.0, label=f"{n} x Omega")
    if shown.any():
        ax.plot(np.asarray(crit["omega"])[shown], np.asarray(crit["hz"])[shown], linestyle="none", marker="o",
                markerfacecolor="none", markeredgecolor="red", markersize=9, label="critical speeds")
    ax.set_ylim(0.0, 1.05 * top)
    ax.set_xlabel("spin rate Omega (rad/s)")
    ax.set_ylabel("frequency (Hz)")
    ax.grid(True, alpha=0.3)
    name = label if label is not None else f"{scene_name(m.get('scene_file', ''))}\n{short_name(m['variant'])}"
    ax.legend(title=name, fontsize="small", title_fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig
