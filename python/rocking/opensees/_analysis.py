"""The transient analysis: OpenSees integrates, the library decides (docs/opensees.md §2), with
event detection and step control, from a CLI scene (blocks, initial angles, excitation)."""
import json
import math
import numbers
import os
from pathlib import Path

import rocking

from ._coupling import Coupling, dof
from ._model import ColumnModel

#: HHT with alpha = 0.9: one-step (so the velocities written at an impact are all it needs; the
#: multistep TRBDF2 keeps the pre-impact history and gains energy), and dissipative at the contact
#: springs' frequency (omega dt ~ 1) while the rocking (omega dt ~ 5e-4) is untouched.
#: Average-acceleration Newmark keeps the contact ringing. Override with ROCKING_INTEGRATOR,
#: e.g. "Newmark,0.5,0.25".
DEFAULT_INTEGRATOR = ("HHT", 0.9)

#: A corner of a closed interface has lifted (an opening) when its gap exceeds this (m): ten times
#: the static compression of the default contact springs, above their ringing.
LIFT = 1e-6

#: Landing tolerance on the contact of an arriving corner (m).
LAND = 1e-12


def integrator():
    spec = os.environ.get("ROCKING_INTEGRATOR")
    if not spec:
        return DEFAULT_INTEGRATOR
    name, *params = spec.split(",")
    return (name, *[float(x) for x in params])


def load_scene(scene):
    """A scene as a dict (the CLI's schema) and the folder its relative record paths start from."""
    if isinstance(scene, dict):
        return scene, Path.cwd()
    path = Path(scene)
    try:
        spec = json.loads(path.read_text(encoding="utf-8-sig"))  # a byte-order mark or none
    except json.JSONDecodeError as e:
        raise rocking._error(f"{path}: not a JSON scene ({e})") from None
    return spec, path.resolve().parent


def check_scene(spec, base):
    """The scene checked by the library's parser (every field, with its messages: a scene run
    for no time), and refused when it is not what this model integrates: a column of blocks on
    the thesis's driver under standard gravity (an arch or a colonnade, drums that slide or fly,
    another gravity were run as something else or failed with a KeyError)."""
    result = rocking.simulate(dict(spec, duration=0.0), base=os.fspath(base))
    if not isinstance(result, rocking.Simulation):
        what = "a closed chain (arch, colonnade)" if isinstance(result, rocking.LoopSimulation) else \
            "the contact scheme (scheme, on_sliding, on_tension: drums that slide or fly)"
        raise rocking._error(f"scene: rocking.opensees models a column of blocks on the thesis's driver, not "
                             f"{what}; run it with rocking.simulate")
    gravity = spec.get("gravity", rocking.GRAVITY)
    if gravity != rocking.GRAVITY:
        raise rocking._error(f"gravity = {gravity}: rocking.opensees models standard gravity ({rocking.GRAVITY} m/s2)")
    for k, b in enumerate(spec["blocks"]):
        w, h, m = b["width"], b["height"], b["mass"]
        inertia = b.get("inertia") or m * (w * w + h * h) / 12.0
        if m - 4.0 * inertia / (h * h) <= 0.0:
            # The three mass points of thesis Appendix C: the centre's would be negative.
            raise rocking._error(f"blocks[{k}]: inertia {inertia:g} kg m2 too large for three mass points on the "
                                 f"block's axis (4 I / h^2 >= mass: a block much wider than tall)")


def _check_run_options(**options):
    """The options of :func:`run`, each finite and positive (``duration``, ``max_events`` and
    ``settle`` >= 0), or None for the default."""
    for name, v in options.items():
        if v is None:
            continue
        at_least_zero = name in ("duration", "max_events", "settle")  # settle=0: no settling by energy
        if isinstance(v, bool) or not isinstance(v, numbers.Real):
            raise TypeError(f"{name}: expected a number, got {type(v).__name__}")
        if not math.isfinite(v) or v < 0 or (v == 0 and not at_least_zero):
            raise rocking._error(f"{name} = {v}: must be a finite number {'>= 0' if at_least_zero else 'greater than zero'}")


def excitation_of(spec, base):
    """The scene's ``excitation`` (a dict, or already a :class:`rocking.Pulse` or
    :class:`rocking.Record`) as a :class:`rocking.Pulse` or :class:`rocking.Record` (None for
    ``{"type": "none"}``), with the CLI's semantics (``full_sine``'s duration is the whole
    period, record paths relative to the scene file, ``scale_to_pga`` in m/s²)."""
    if isinstance(spec, (rocking.Pulse, rocking.Record)):
        return spec  # a dict scene may hold the objects, as rocking.simulate's
    kind = spec.get("type")
    args = {k: v for k, v in spec.items() if k != "type"}
    if kind == "none":
        return None
    if kind == "record":
        path = Path(args["path"])
        # units None: the reader's default, m/s2 for plain text and g for a PEER .AT2 (which
        # refuses any other units).
        record = rocking.read_record(path if path.is_absolute() else base / path, dt=args.get("dt"),
                                     units=args.get("units"))
        return record.scaled_to_pga(args["scale_to_pga"]) if args.get("scale_to_pga") is not None else record
    makers = {"half_sine": rocking.half_sine, "full_sine": rocking.full_sine, "half_sines": rocking.half_sines,
              "rectangular": rocking.rectangular, "triangular": rocking.triangular, "ricker": rocking.ricker,
              "mavroeidis_papageorgiou": rocking.mavroeidis_papageorgiou}
    if kind not in makers:
        raise rocking._error(f"excitation.type: unknown type {kind!r} ({', '.join(['none', 'record', *makers])})")
    return makers[kind](**args)


def ground_motion(ops, excitation, dt, tag=10):
    """The excitation as an OpenSees ``UniformExcitation`` in x: a ``Path`` time series of the
    record's samples, or of the pulse sampled every ``dt`` (linear in between, as the record)."""
    if isinstance(excitation, rocking.Record):
        values, step = excitation.samples, excitation.dt
    else:
        count = int(excitation.end_time / dt) + 2
        step = dt
        values = excitation.acceleration([i * dt for i in range(count)])
    ops.timeSeries("Path", tag, "-dt", step, "-values", *[float(x) for x in values])
    ops.pattern("UniformExcitation", tag, 1, "-accel", tag)


def transient(ops, dt):
    ops.wipeAnalysis()
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-11, 100)
    ops.algorithm("Newton")
    ops.integrator(*integrator())
    ops.analysis("Transient")


def why_it_does_not_stand(model, coupling, status):
    """The error when the static gravity step failed (a RuntimeError, "the static gravity step
    failed", said no more): the column does not stand as tilted, past static tipping at an open
    interface or with a closed interface that must open at once (the library's reaction test on
    OpenSees's own matrices), named under ``initial_angles``; the rigid driver runs such a start
    (``rocking.simulate``)."""
    tipped = [k for k in range(model.n) if model.overturned(k, status[k])]
    if tipped:
        why = f"the column is past static tipping at interface {tipped[0]}"
    else:
        mass, load, _ = coupling.reduced(0.0)
        holds, _, must_open = rocking.check_configuration(mass, load, status)
        why = (f"the closed interface(s) {[int(k) for k in must_open]} must open at once" if not holds else
               "OpenSees found no static equilibrium")
    return rocking._error(f"initial_angles: {why} as tilted, and the analysis starts from the column standing "
                          f"under gravity (its static step failed); rocking.simulate runs such a start")


def settle_gravity(model, tilted):
    """Gravity applied statically, with the rotations of the tilted blocks held (imposed ``sp``
    values in a temporary pattern): the contact springs start pre-compressed instead of ringing
    from a suddenly applied weight (which lifts corners that should stay down)."""
    ops = model.ops
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    for tag, mm in model.mass_nodes:
        ops.load(tag, 0.0, -mm * rocking.GRAVITY, 0.0)
    ops.pattern("Plain", 2, 1)
    angles = model.block_angles()
    for j in tilted:
        ops.sp(model.centres[j], 3, angles[j])
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-12, 50)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    if ops.analyze(1) != 0:
        raise RuntimeError("OpenSees: the static gravity step failed")
    ops.loadConst("-time", 0.0)
    ops.remove("loadPattern", 2)


def event_dict(kind, t, interface, before, after, report=None, **extra):
    e = {"t": t, "kind": kind, "interface": interface, "statuses_before": list(before), "statuses_after": list(after)}
    if report is not None:
        e["report"] = report.to_dict()
    e.update(extra)
    return e


def run(scene, dt=None, duration=None, max_events=None, k_contact=None, block_stiffness=2e10, solver=None,
        settle=1e-6):
    """Runs a CLI scene in OpenSees with the library deciding every opening and impact.

    ``scene``: a dict with the CLI's scene schema (``blocks``, ``initial_angles``,
    ``excitation``, ``impacts``, ``duration``, ``dt``, ``solver``, ``title``) or the path of a
    scene file, checked by the library's parser first (:class:`rocking.RockingError` naming the
    field); a closed chain, the contact scheme or another gravity are refused. ``dt``:
    OpenSees's time step (default ``min(scene dt, 1e-4)``: the contact springs need it);
    ``duration``, ``max_events``: stop earlier than the scene. ``k_contact``,
    ``block_stiffness``: see :meth:`ColumnModel.build`. An impact after which the kinetic energy
    is below ``settle`` times the largest seen so far, or that comes within three steps of the
    previous impact at the same interface, closes the column for good there (a ``settled``
    event): the rigid driver's rule (docs/opensees.md §2), which keeps micro-impacts from
    crawling. An interface whose corner went through the contact and back within a step (its
    rate already away from closure) closes at rest: a ``settled`` event with the impact model's
    report at zero rate.

    Ground motions (``UniformExcitation``): the blocks' beam section is fixed (A = 0.01 m²,
    I = 1e-3 m⁴), so heavy, tall blocks are flexible at the default ``block_stiffness``: on the
    bundled half-sine scene (1 × 4 m, 10 t; first mode 3 Hz) the opening comes 26 ms after the
    rigid driver's and the block tips 57 ms earlier; with ``block_stiffness=2e14`` (255 Hz) the
    differences are +0.5 ms and −0.1 ms (docs/opensees.md §5). Choose it so that the first mode
    is well above the excitation's frequencies.

    Openings happen in OpenSees (a corner's contact spring goes slack): at each one the
    library's opening model is asked on OpenSees's own matrices and its choice is recorded
    (``library`` in the event; ``agrees``). Impacts: the step is cut to land on the contact of
    the arriving corner, and the library's impact model decides the configuration and the
    velocities, written back into every node.

    Returns ``{"events": [...], "summary": {...}}``: events with ``t``, ``kind``, ``interface``,
    ``statuses_before``, ``statuses_after`` and ``report`` (as the CLI's events.jsonl), and the
    rates before and after impacts (``rate_before``, ``rate_after``, rad/s). The analysis stops at
    static tipping (an ``overturned`` event: the centre of mass above an open interface beyond its
    pivot, SPEC §5), as the rigid driver does.
    """
    spec, base = load_scene(scene)
    check_scene(spec, base)
    _check_run_options(dt=dt, duration=duration, max_events=max_events, k_contact=k_contact,
                       block_stiffness=block_stiffness, settle=settle)
    if solver not in (None, "auto", "enumerate", "projection"):
        # It reached the impact model at the first event, after the model was built and run.
        raise rocking._error(f"solver = {solver!r}, expected \"auto\", \"enumerate\" or \"projection\"")
    blocks = spec["blocks"]
    width = [b["width"] for b in blocks]
    height = [b["height"] for b in blocks]
    mass = [b["mass"] for b in blocks]
    contact = [b.get("contact_width") or (min(width[k - 1], width[k]) if k else width[0]) for k, b in enumerate(blocks)]
    inertia = [b.get("inertia") or m * (w * w + h * h) / 12.0 for b, w, h, m in zip(blocks, width, height, mass)]
    n = len(blocks)
    angles = spec.get("initial_angles") or [0.0] * n
    if len(angles) != n:
        raise rocking._error(f"initial_angles: {len(angles)} values for {n} blocks")
    excitation = excitation_of(spec.get("excitation", {"type": "none"}), base)
    dt = min(spec["dt"], 1e-4) if dt is None else dt
    duration = spec["duration"] if duration is None else duration
    max_events = 10**9 if max_events is None else max_events
    model = ColumnModel.build(width, height, mass, contact, inertia, k_contact, block_stiffness)
    ops = model.ops
    coupling = Coupling(model, spec.get("impacts", 1), solver or spec.get("solver") or "auto")
    status = [0] * n
    for k, a in enumerate(angles):
        if a:
            model.tilt(k, a)
            status[k] = -1 if a < 0 else 1
    model.retie(status)
    try:
        settle_gravity(model, [k for k, a in enumerate(angles) if a])
    except RuntimeError:
        raise why_it_does_not_stand(model, coupling, status) from None
    if excitation is not None:
        ground_motion(ops, excitation, dt)
    transient(ops, dt)

    def ag(t):
        return excitation.acceleration(t) if excitation is not None else 0.0

    t, events = 0.0, []
    peak = [abs(a) for a in model.block_angles()]
    last_compressed = {}
    largest_kinetic = 0.0
    last_impact = {}
    counts = {"opening": 0, "impact": 0, "settled": 0}
    overturned = None

    def impact(k):
        nonlocal status, largest_kinetic
        before = list(status)
        # The rate on the interface's open DOF: towards closure when it is of the other sign.
        rate = coupling.interface_velocity(status)[dof(k, status, n)]
        if rate * status[k] >= 0.0:
            # Through the contact and back within the step (the springs turned it, a small
            # rocking late in a run): it closes at rest, the library deciding what else moves
            # (the model refuses a rate away from closure).
            status, v0, v1, report = coupling.impact(status, k, ag(t), at_rest=True)
            counts["settled"] += 1
            events.append(event_dict("settled", t, k, before, status, report, rate_before=v0, rate_after=v1))
            model.retie(status)
            return
        status, v0, v1, report = coupling.impact(status, k, ag(t))
        counts["impact"] += 1
        events.append(event_dict("impact", t, k, before, status, report, rate_before=v0, rate_after=v1))
        largest_kinetic = max(largest_kinetic, report.kinetic_before)
        crawling = t - last_impact.get(k, -1.0) < 3 * dt
        last_impact[k] = t
        if (report.kinetic_after < settle * largest_kinetic or crawling) and any(status):
            before = list(status)
            status = [0] * n
            coupling.write_back(status, [0.0] * (2 * n), ag(t))
            counts["settled"] += 1
            events.append(event_dict("settled", t, k, before, status))
        model.retie(status)

    while t < duration - 1e-12 and len(events) < max_events:
        # Land on the next impact: the lifted corner of an open interface coming down onto the
        # part below (its contact spring about to engage). Landing on "rotation = 0" instead lets
        # the arriving spring compress first: an elastic impact begins and its ringing trades
        # energy with the rocking (docs/opensees.md §2).
        h, closing = min(dt, duration - t), None
        for k in range(n):
            if status[k] != 0:
                g, gdot = model.gap(k, status[k])
                if gdot < 0 and g < -gdot * h:
                    h, closing = g / -gdot, k
        if closing is not None and model.gap(closing, status[closing])[0] < LAND:
            impact(closing)
            continue
        h = max(h, 1e-9)
        if ops.analyze(1, h) != 0:
            raise RuntimeError(f"OpenSees failed at t = {t}")
        t += h
        # Went through the contact within the cut step: the impact, now.
        for k in range(n):
            if status[k] != 0 and model.gap(k, status[k])[0] < -LAND:
                impact(k)
        # Openings happen in OpenSees: a corner of a closed interface lifts by more than LIFT; the
        # event time is the last instant that corner was in compression (the onset).
        for k in range(n):
            if status[k] == 0:
                forces = model.bearing_forces(k)
                for c in (0, 1):
                    if forces[c] < 0.0:
                        last_compressed[(k, c)] = t
                lifted = [c for c in (0, 1) if model.gap(k, 1 if c == 1 else -1)[0] > LIFT]
                if lifted:
                    library, report = coupling.opening(status, ag(t))
                    before = list(status)
                    status[k] = -1 if lifted[0] == 0 else 1  # left corner up: about the right one
                    model.retie(status)
                    counts["opening"] += 1
                    events.append(event_dict("opening", last_compressed.get((k, lifted[0]), t), k, before, status, report,
                                             library=library, agrees=library == status))
        peak = [max(p, abs(a)) for p, a in zip(peak, model.block_angles())]
        tipped = [k for k in range(n) if model.overturned(k, status[k])]
        if tipped:
            overturned = tipped[0]
            events.append(event_dict("overturned", t, overturned, status, status))
            break
    summary = {
        "title": spec.get("title"),
        "t_end": t,
        "dt": dt,
        "impacts": spec.get("impacts", 1),
        "events": counts,
        "statuses_end": list(status),
        "overturned": overturned is not None,
        "stop_interface": overturned,
        "peak_block_rotation": peak,
        "opensees": {"integrator": list(integrator()), "k_contact": model.k_contact, "block_stiffness": block_stiffness},
    }
    return {"events": events, "summary": summary}
