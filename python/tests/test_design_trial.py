"""A structural engineer's trial of the design workflow through the package: files that cannot
be read are named, and a list of records is read whole before the first spectrum."""
import pytest

import rocking


@pytest.mark.parametrize(
    "call",
    [
        lambda f: rocking.oas(f, levels=2, sizes=2),
        lambda f: rocking.tp(f),
        lambda f: rocking.read_record(f),
        lambda f: rocking.simulate(f),
        lambda f: rocking.t1(f, levels=2, sizes=2),
    ],
)
def test_a_missing_file_is_named(call, tmp_path):
    # FileNotFoundError said "No such file or directory (os error 2)", without the file.
    missing = tmp_path / "FF-44.AT2"
    with pytest.raises(FileNotFoundError) as e:
        call(missing)
    assert e.value.filename == str(missing)
    assert e.value.errno == 2
    assert "FF-44.AT2" in str(e.value)


def test_a_folder_given_as_a_record_is_named(tmp_path):
    with pytest.raises(IsADirectoryError) as e:
        rocking.oas(tmp_path, levels=2, sizes=2)
    assert e.value.filename == str(tmp_path)


def test_t1_reads_every_record_before_the_first_spectrum(root, tmp_path):
    # The spectra of the records before a missing one were computed first (seconds to minutes
    # each) and then thrown away.
    done = []
    with pytest.raises(FileNotFoundError) as e:
        rocking.t1(
            [root / "examples/records/synthetic.AT2", tmp_path / "missing.AT2"],
            levels=8,
            sizes=24,
            threads=1,
            progress=lambda k, n: done.append(k),
        )
    assert e.value.filename == str(tmp_path / "missing.AT2")
    assert done == []


def test_a_fractile_given_twice_is_refused(root):
    o = rocking.oas(root / "examples/records/synthetic.AT2", levels=4, sizes=6, threads=1)
    for fractiles, says in [([0.5, 0.5], "0.5 is given twice"), ([], "at least one")]:
        with pytest.raises(rocking.RockingError, match="fractile") as e:
            rocking.suite([o], fractiles=fractiles)
        assert says in str(e.value)


def test_beta_is_labelled_with_its_unit(root):
    mpl = pytest.importorskip("matplotlib")
    mpl.use("Agg")
    import matplotlib.pyplot as plt

    o = rocking.oas(root / "examples/records/synthetic.AT2", levels=16, sizes=40, threads=1)
    for against in ["p", "f", "size"]:
        _, ax = plt.subplots()
        o.plot(against=against, ax=ax)
        labels = [l.get_label() for l in ax.get_lines() if "beta" in l.get_label()]
        assert labels and all(l.endswith(" s") for l in labels), labels
    plt.close("all")


def test_blocks_rocking_as_one_are_one_line(root):
    mpl = pytest.importorskip("matplotlib")
    mpl.use("Agg")
    import matplotlib.pyplot as plt

    for scene, labels in [
        ("three_block_sine_pulse", ["blocks 0, 1, 2 (as one)"]),
        ("column_synthetic_record", ["block 0", "block 1", "block 2"]),
    ]:
        r = rocking.simulate(root / f"examples/scenes/{scene}.json")
        _, ax = plt.subplots()
        rocking.plot.simulation(r, ax=ax, events=False)
        assert [l.get_label() for l in ax.get_lines()] == labels, scene
    plt.close("all")


def test_empty_design_arrays_keep_their_types():
    # `governing` of empty inputs came back as a float64 array; `safe` was already bool.
    for r in [
        rocking.design_width(height=[], pga=3.0, t1=0.25),
        rocking.design_check(width=[], height=[], pga=3.0, t1=0.25),
    ]:
        assert r["governing"].shape == (0,)
        assert r["governing"].dtype.kind == "U"
    c = rocking.design_check(width=[], height=[], pga=3.0, t1=0.25)
    assert c["safe"].dtype == bool
    w = rocking.design_width(height=[10.0, 20.0], pga=3.0, t1=0.25)
    assert list(w["governing"]) == ["impulse", "impulse"]
