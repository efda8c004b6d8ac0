"""Plots of pmech results with matplotlib: time histories from energy.csv and probes.csv, and snapshots
of a frame's particles coloured by a field, with axes in metres and the field's unit on the colour bar.

    import pmech, pmech.plot
    run = pmech.Run("slope.out")
    ax = pmech.plot.history(run.probes, "A.vy")
    ax = pmech.plot.snapshot(run.frame(-1), "plastic_strain")
"""
import numpy as np


def _axes(ax):
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt
    return plt.figure().add_subplot()


def history(table, *columns, ax=None, xcolumn="time", xlabel="t [s]", ylabel=None):
    """Lines of columns of a structured array (Run.energy, Run.probes) against time."""
    ax = _axes(ax)
    for c in columns:
        ax.plot(table[xcolumn], table[c], label=c)
    ax.set_xlabel(xlabel)
    if ylabel:
        ax.set_ylabel(ylabel)
    if len(columns) > 1:
        ax.legend()
    ax.grid(True, alpha=0.3)
    return ax


def snapshot(frame, field, ax=None, vmin=None, vmax=None, cmap="viridis", size=None, axisymmetric=False):
    """The particles of a Frame as squares of their current size (from volume ... half_size and F when
    the frame has them) coloured by ``field`` (see Frame.field), equal axes in metres, a colour bar with
    the field's name and unit; returns the axes."""
    import matplotlib.pyplot as plt
    ax = _axes(ax)
    values, unit = frame.field(field)
    x, y = frame.points[:, 0], frame.points[:, 1]
    if size is None:
        # marker area in points^2 from the particle's drawn width against the axes' width in points
        half = frame.arrays.get("half_size")
        span = max(np.ptp(x), np.ptp(y), 1e-12)
        width_pt = ax.figure.get_figwidth() * 72 * 0.75
        h = np.mean(half[:, 0]) if half is not None and len(half) else span / max(np.sqrt(len(x)), 1)
        size = max((2 * h / span * width_pt) ** 2, 1.0)
    sc = ax.scatter(x, y, c=values, s=size, marker="s", linewidths=0, cmap=cmap, vmin=vmin, vmax=vmax)
    ax.set_aspect("equal")
    ax.set_xlabel("r [m]" if axisymmetric else "x [m]")
    ax.set_ylabel("z [m]" if axisymmetric else "y [m]")
    ax.set_title("t = %.4g s" % frame.time)
    label = "%s [%s]" % (field, unit) if unit else field
    plt.colorbar(sc, ax=ax, label=label, orientation="horizontal", pad=0.15)
    return ax
