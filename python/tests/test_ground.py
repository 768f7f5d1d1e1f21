"""Records (PEER .AT2, plain text) and pulses: the values read and evaluated through Python."""
import math

import numpy as np
import pytest

import rocking


def parse_at2(path):
    """An independent reading of a PEER AT2 file: 4 header lines, then values in g."""
    lines = path.read_text().splitlines()
    header = lines[3].replace(",", " ").split()
    npts = int(header[header.index("NPTS=") + 1])
    dt = float(header[header.index("DT=") + 1])
    values = [float(x) for line in lines[4:] for x in line.split()]
    assert len(values) == npts
    return dt, np.array(values)


def test_the_bundled_record(root):
    path = root / "examples" / "records" / "synthetic.AT2"
    record = rocking.read_record(path)
    dt, g_values = parse_at2(path)
    assert record.name == "synthetic" and record.dt == dt and len(record) == len(g_values)
    np.testing.assert_allclose(record.samples, 9.81 * g_values, rtol=1e-15, atol=0)
    assert record.pga == pytest.approx(0.3 * 9.81, rel=1e-6)  # "PGA 0.3 g" in its header
    assert record.duration == pytest.approx((len(g_values) - 1) * dt)
    np.testing.assert_allclose(record.t, np.arange(len(g_values)) * dt, rtol=1e-15)
    # a_g(t): the samples at the sample times, linear in between, zero outside.
    t = record.t[:50]
    np.testing.assert_allclose(record.acceleration(t), record.samples[:50], rtol=1e-12, atol=1e-15)
    mid = 0.5 * (t[10] + t[11])
    assert record.acceleration(mid) == pytest.approx(0.5 * (record.samples[10] + record.samples[11]))
    assert record.acceleration(-1.0) == 0.0 and record.acceleration(1e6) == 0.0
    assert isinstance(record.acceleration(0.5), float)
    assert record.acceleration(np.zeros((2, 3))).shape == (2, 3)
    scaled = record.scaled_to_pga(4.0)
    assert scaled.pga == pytest.approx(4.0, rel=1e-12) and record.pga != scaled.pga
    np.testing.assert_allclose(record.scaled(2.0).samples, 2.0 * record.samples)


def test_plain_text_records(tmp_path):
    one = tmp_path / "one.txt"
    one.write_text("# a comment\n0.0\n0.1\n-0.2\n")
    r = rocking.read_record(one, dt=0.02, units="g")
    np.testing.assert_allclose(r.samples, [0.0, 0.981, -1.962])
    assert r.dt == 0.02 and r.name == "one"
    two = tmp_path / "two.csv"
    two.write_text("0.00, 1.0\n0.01, 2.0\n0.02, 3.0\n")
    r = rocking.read_record(two)
    assert r.dt == pytest.approx(0.01) and r.samples.tolist() == [1.0, 2.0, 3.0]
    r = rocking.read_record(str(two), units="cm/s2")
    np.testing.assert_allclose(r.samples, [0.01, 0.02, 0.03])
    with pytest.raises(rocking.RockingError) as info:
        rocking.read_record(one)  # one column needs dt
    assert "dt" in str(info.value)


def test_record_from_samples():
    samples = np.array([0.0, 1.0, -2.0, 0.5])
    r = rocking.Record(samples, 0.1, name="mine")
    samples[1] = 7.0  # the record keeps its own copy
    assert r.samples.tolist() == [0.0, 1.0, -2.0, 0.5] and r.pga == 2.0 and r.name == "mine"
    assert "mine" in repr(r)


def test_a_record_without_samples_is_refused():
    """An empty file is refused by read_record; Record([], dt) was accepted and ran a simulation
    under no ground motion at all, silently."""
    for empty in ([], np.zeros(0), ()):
        with pytest.raises(rocking.RockingError, match="samples: no sample"):
            rocking.Record(empty, 0.01)


def test_the_ground_motion_at_a_nan_time_is_nan(root):
    """A NaN time gave 0.0 (no comparison with a NaN holds, so it fell "outside" the motion), a
    number out of no time; infinities are before the start or after the end: zero."""
    record = rocking.read_record(root / "examples/records/synthetic.AT2")
    for motion in [record, rocking.half_sine(2.0, 0.5), rocking.ricker(2.0, 1.5)]:
        assert math.isnan(motion.acceleration(math.nan))
        a = motion.acceleration(np.array([math.nan, math.inf, -math.inf, 0.25]))
        assert math.isnan(a[0]) and a[1] == a[2] == 0.0 and a[3] == motion.acceleration(0.25)


def test_records_and_pulses_pickle(root):
    """multiprocessing and copy.deepcopy pickle their arguments: `cannot pickle 'rocking.Record'
    object`. Each comes back equal, to the bit."""
    import copy
    import pickle

    record = rocking.read_record(root / "examples/records/synthetic.AT2").scaled_to_pga(4.0)
    motions = [record, rocking.half_sine(2.0, 0.5), rocking.full_sine(-2.467, 0.6), rocking.half_sines(1.0, 0.3, 3),
               rocking.rectangular(1.5, 0.2), rocking.triangular(-1.0, 0.4), rocking.ricker(2.0, 1.5),
               rocking.mavroeidis_papageorgiou(3.0, 1.0, 2.0, 0.5)]
    t = np.linspace(-0.5, 25.0, 5001)
    for m in motions:
        for back in [pickle.loads(pickle.dumps(m)), copy.deepcopy(m)]:
            assert type(back) is type(m) and repr(back) == repr(m)
            assert np.array_equal(back.acceleration(t), m.acceleration(t))
    back = pickle.loads(pickle.dumps(record))
    assert back.name == record.name and back.dt == record.dt and np.array_equal(back.samples, record.samples)
    for m in motions[1:]:
        assert pickle.loads(pickle.dumps(m)).to_dict() == m.to_dict()


def test_a_record_saved_with_a_byte_order_mark(tmp_path):
    """Windows editors and spreadsheets write a UTF-8 byte-order mark first: it was read as part
    of the first number (`\ufeff0` is not a finite number, the mark invisible)."""
    (tmp_path / "bom.txt").write_bytes(b"\xef\xbb\xbf0 0.1\n0.01 0.2\n0.02 -0.3\n")
    (tmp_path / "plain.txt").write_text("0 0.1\n0.01 0.2\n0.02 -0.3\n")
    a, b = rocking.read_record(tmp_path / "bom.txt"), rocking.read_record(tmp_path / "plain.txt")
    assert a.dt == b.dt and a.samples.tolist() == b.samples.tolist() == [0.1, 0.2, -0.3]


def test_pulses():
    hs = rocking.half_sine(3.0, 0.5)
    t = np.linspace(-0.1, 0.6, 71)
    want = np.where((t >= 0) & (t <= 0.5), 3.0 * np.sin(np.pi * t / 0.5), 0.0)
    np.testing.assert_allclose(hs.acceleration(t), want, atol=1e-15)
    assert hs.end_time == 0.5 and hs.amplitude == 3.0 and hs.to_dict() == {"type": "half_sine", "amplitude": 3.0, "duration": 0.5}
    # full_sine takes the WHOLE period, as the CLI's scenes: each lobe lasts duration / 2.
    fs = rocking.full_sine(-2.467, 0.6)
    assert fs.end_time == pytest.approx(0.6)
    assert fs.acceleration(0.15) == pytest.approx(-2.467) and fs.acceleration(0.45) == pytest.approx(2.467)
    assert fs.to_dict() == {"type": "half_sines", "count": 2, "amplitude": -2.467, "duration": 0.3}
    three = rocking.half_sines(1.0, 0.2, 3)
    assert three.end_time == pytest.approx(0.6) and three.acceleration(0.5) == pytest.approx(1.0)
    rect = rocking.rectangular(2.0, 0.3)
    assert rect.acceleration([0.0, 0.29, 0.3]).tolist() == [2.0, 2.0, 0.0]
    tri = rocking.triangular(2.0, 0.4)
    assert tri.acceleration(0.2) == pytest.approx(2.0) and tri.acceleration(0.1) == pytest.approx(1.0)
    ricker = rocking.ricker(5.0, 2.0)
    t0 = 3 * math.sqrt(2) / (math.pi * 2.0)
    assert ricker.acceleration(t0) == pytest.approx(5.0) and ricker.end_time == pytest.approx(2 * t0)
    mp = rocking.mavroeidis_papageorgiou(4.0, 1.0, 2.0, 0.0)
    tt = np.linspace(0, mp.end_time, 20001)
    assert np.abs(mp.acceleration(tt)).max() == pytest.approx(4.0, rel=1e-6)
    assert mp.to_dict()["type"] == "mavroeidis_papageorgiou"
    assert rocking.half_sine(1.0, 1.0).scaled(-2.0).amplitude == -2.0
    assert "half sine" in repr(hs)


def test_an_at2_record_takes_no_step_nor_other_units(root, tmp_path):
    """A PEER .AT2 file is in g with its own step: ``dt`` or ``units`` other than "g" given for
    one were ignored (a record in m/s2 under an .AT2 name read 9.81 times too strong)."""
    at2 = root / "examples/records/synthetic.AT2"
    for kwargs, field in [(dict(units="m/s2"), "units"), (dict(units="cm/s2"), "units"), (dict(dt=0.005), "dt")]:
        with pytest.raises(rocking.RockingError, match=f"{field} = .*AT2") as e:
            rocking.read_record(at2, **kwargs)
        assert e.value.code is None
    g = rocking.read_record(at2, units="g")
    assert g.pga == rocking.read_record(at2).pga and g.dt == 0.01
    # Any case of the extension is an .AT2 (as the reader decides).
    lower = tmp_path / "rec.at2"
    lower.write_bytes(at2.read_bytes())
    with pytest.raises(rocking.RockingError, match="units"):
        rocking.read_record(lower, units="m/s2")
