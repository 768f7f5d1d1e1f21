"""rocking.plot: matplotlib stays optional (importing rocking never loads it); where it is
installed (`pip install './python[plot]'`), each plot draws what its result holds."""
import subprocess
import sys

import numpy as np
import pytest

import rocking


def test_import_rocking_without_matplotlib():
    code = "import sys, rocking, rocking.plot; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


@pytest.fixture(scope="module")
def plt():
    mpl = pytest.importorskip("matplotlib", reason="matplotlib not installed (the [plot] extra)")
    mpl.use("Agg")
    import matplotlib.pyplot as plt

    yield plt
    plt.close("all")


def test_simulation_plot(plt, root):
    r = rocking.simulate(root / "examples/scenes/two_block_free_rocking.json")
    ax = r.plot()
    lines = ax.get_lines()
    np.testing.assert_array_equal(lines[0].get_xdata(), r.t)
    np.testing.assert_array_equal(lines[1].get_ydata(), r.block_rotations[:, 1])
    assert len(lines) == 2 + len(r.events)  # a line per block and per event
    assert ax.get_title() == r.title


def test_loop_and_contact_plots(plt, root):
    arch = rocking.simulate(root / "examples/scenes/arch_half_sine.json")
    ax = arch.plot()
    moved = [k for k in range(arch.angles.shape[1]) if arch.angles[:, k].any()]
    lines = ax.get_lines()
    assert len(lines) == len(moved) + len(arch.events)  # a line per joint that moved and per event
    np.testing.assert_array_equal(lines[0].get_ydata(), arch.angles[:, moved[0]])
    assert ax.get_ylabel() == "joint angle [rad]"
    scene = {"blocks": [{"width": 1.0, "height": 1.0, "mass": 2500}] * 3, "friction": 0.5,
             "on_sliding": "slide", "excitation": {"type": "half_sine", "amplitude": 6.0, "duration": 0.5},
             "duration": 1.0, "dt": 0.001}
    drums = rocking.simulate(scene)
    assert isinstance(drums, rocking.ContactSimulation)
    ax = drums.plot(events=False)
    assert len(ax.get_lines()) == 3
    np.testing.assert_array_equal(ax.get_lines()[2].get_ydata(), drums.block_rotations[:, 2])


def _drums(n, amplitude, duration):
    return rocking.simulate({
        "blocks": [{"width": 1.0, "height": 1.0, "mass": 2500}] * n, "friction": 0.5, "impacts": 2,
        "on_sliding": "slide", "on_tension": "fly", "duration": duration, "dt": 0.001,
        "excitation": {"type": "full_sine", "amplitude": amplitude, "duration": 1.0}})


def test_contact_plots_show_drums_slips_and_every_event_kind(plt):
    """A drum column's plot names drums, its slips plot draws the slips in mm, each kind of event
    has a style of its own (slip stops were black solid lines, as an overturning), the
    overturning is marked on both; many events are ticks above the axes (42 000 lines took a
    minute and hid the curves), and ten drums are ten colours with seven in the legend."""
    from rocking import plot

    drum_kinds = ["opening", "impact", "slip_start", "slip_stop", "lift_off", "landing",
                  "scheme_switch", "overturned"]
    styles = [plot.EVENT_STYLE[k] for k in drum_kinds]
    assert len(set(styles)) == len(styles), "two kinds drawn alike"
    d = _drums(3, 8.0, 2.0)
    assert d.overturned and 0 < len(d.events) <= plot.MAX_EVENT_LINES
    _, (a, b) = plt.subplots(2)
    d.plot(ax=a)
    d.plot_slips(ax=b)
    assert a.get_ylabel() == "drum rotation [rad]" and b.get_ylabel() == "joint slip [mm]"
    labels = [h.get_label() for h in a.get_legend().legend_handles]
    assert labels[:3] == ["drum 0", "drum 1", "drum 2"] and "overturned" in labels
    np.testing.assert_array_equal(b.get_lines()[1].get_ydata(), 1e3 * d.slips[:, 1])
    slip_labels = [h.get_label() for h in b.get_legend().legend_handles]
    assert {"slip_start", "slip_stop", "overturned"} <= set(slip_labels), slip_labels

    many = _drums(10, 5.0, 3.0)
    assert len(many.events_of("impact")) > plot.MAX_EVENT_LINES
    ax = many.plot()
    lines = ax.get_lines()
    kinds = {e["kind"] for e in many.events} & {"impact", "lift_off", "landing"}
    assert len(lines) == 10 + len(kinds)
    assert f"impact ({len(many.events_of('impact'))}, ticks above)" in [l.get_label() for l in lines]
    colours = {tuple(l.get_color()) for l in lines[:10]}
    assert len(colours) == 10
    named = [l for l in lines[:10] if not l.get_label().startswith("_")]
    assert len(named) == plot.MAX_NAMED


def test_oas_plots(plt, root):
    o = rocking.oas(root / "examples/records/synthetic.AT2", levels=16, sizes=40)
    for against, x in [("p", o.p), ("f", o.f), ("size", o.size)]:
        _, ax = plt.subplots()
        o.plot(against=against, ax=ax)
        points = ax.get_lines()[0]
        np.testing.assert_array_equal(points.get_xdata(), x[o.unsafe])
        np.testing.assert_array_equal(points.get_ydata(), o.levels[o.unsafe])
        assert len(ax.get_lines()) == 3  # Eq. 21 (20) and Eq. 30 (28) with the points
    # Eq. 21 passes through the most vulnerable point (the definition of t1, Eq. 20)
    _, ax = plt.subplots()
    o.plot(against="p", ax=ax)
    eq21 = ax.get_lines()[1]
    k = int(np.nanargmin(o.f))
    assert np.interp(o.p[k], eq21.get_xdata(), eq21.get_ydata()) == pytest.approx(o.levels[k], rel=1e-2)
    with pytest.raises(ValueError, match="against"):
        o.plot(against="q")


def test_oc_plot(plt):
    o = rocking.oc(ptp=8, levels=6)
    ax = o.plot()
    points, envelope = ax.get_lines()
    assert len(points.get_xdata()) == int(o.unsafe.sum())
    np.testing.assert_array_equal(envelope.get_ydata(), o.envelope)
    assert ax.get_xscale() == "log"


def test_oc_plot_spans_the_whole_grid(plt):
    # The shortest pulses of this grid overturn nothing: the axes must still start at the
    # grid's first p t_p (they were fitted to the unsafe points and began at about 0.2).
    o = rocking.oc(ptp=8, levels=6)
    assert not o.unsafe[0].any()
    ax = o.plot()
    lo, hi = ax.get_xlim()
    assert lo <= o.p_tp.min() and hi >= o.p_tp.max()
    assert ax.get_ylim()[0] <= 1.0 and ax.get_ylim()[1] >= o.levels.max()
