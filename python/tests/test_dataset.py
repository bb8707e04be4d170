"""brdffit.load() and Dataset: CURET read through the library against the
files parsed here with numpy, datasets built from arrays (round trips,
shared configuration sets), and clear errors for bad input."""

import csv
import os

import numpy as np
import pytest

import brdffit


def test_curet_loads_every_sample_as_the_files_give_it(curet, curet_dir):
    rows = np.loadtxt(os.path.join(curet_dir, "abrdf.dat"))
    rows = rows[np.argsort(rows[:, 0])]
    table = np.loadtxt(os.path.join(curet_dir, "table.txt"))
    with open(os.path.join(curet_dir, "samples.tsv")) as f:
        names = {int(r["sample"]): r["name"]
                 for r in csv.DictReader(f, delimiter="\t")}
    assert len(curet) == len(rows) == 61
    # table.txt is "index theta_v phi_v theta_i phi_i" (SPEC §1.3); the
    # dataset stores theta_i, phi_i, theta_o = theta_v, phi_o = phi_v.
    angles = table[:, [3, 4, 1, 2]]
    for m, row in zip(curet, rows):
        assert m.number == int(row[0])
        assert m.name == names[m.number]
        assert m.format == "curet"
        assert m.channels == ("mean",)
        assert m.config_set == curet[0].config_set
        np.testing.assert_array_equal(m.values[:, 0], row[1:])
        np.testing.assert_array_equal(m.angles, angles)
        assert m.valid.all()
    assert curet.find(5).name == "Leather"
    assert curet["Leather"] is curet.find(5) is curet[4]
    assert curet.material(5) is curet[4]


def test_material_arrays_are_read_only_copies(curet):
    m = curet.find(5)
    with pytest.raises(ValueError):
        m.values[0, 0] = 1.0
    with pytest.raises(ValueError):
        m.angles[0, 0] = 1.0


def test_a_dataset_from_arrays_keeps_every_value_bit_for_bit():
    rng = np.random.default_rng(7)
    angles = np.column_stack([rng.uniform(0, 1.5, 40),
                              rng.uniform(-np.pi, np.pi, 40),
                              rng.uniform(0, 1.5, 40),
                              rng.uniform(-np.pi, np.pi, 40)])
    values = rng.normal(0.2, 0.1, (3, 40, 2))  # negatives kept (SPEC §2)
    valid = np.ones(values.shape, dtype=bool)
    valid[1, 5, 0] = False
    values[1, 5, 0] = np.nan  # an invalid value may be anything
    ds = brdffit.Dataset.from_arrays(angles, values, names=["a", "b", "c"],
                                     channels=["R", "G"], valid=valid,
                                     wavelengths=[610.0, 550.0])
    assert len(ds) == 3
    for i, m in enumerate(ds):
        assert (m.name, m.number, m.format) == ("abc"[i], i + 1, "memory")
        assert m.channels == ("R", "G")
        np.testing.assert_array_equal(m.wavelengths, [610.0, 550.0])
        np.testing.assert_array_equal(m.angles, angles)
        np.testing.assert_array_equal(m.valid, valid[i])
        np.testing.assert_array_equal(m.values[valid[i]], values[i][valid[i]])
        assert m.config_set == ds[0].config_set  # equal angles: one set
    assert ds[1].channel_index("g") == 1
    with pytest.raises(brdffit.NotFoundError, match="no channel 'B'"):
        ds[1].channel_index("B")


def test_materials_with_other_angles_get_their_own_configuration_set():
    a = np.array([[0.1, 0.0, 0.2, 3.0], [0.3, 0.0, 0.4, 3.0]])
    ds = brdffit.Dataset()
    m1 = ds.add_material("one", a, [1.0, 2.0], number=7)
    m2 = ds.add_material("two", a[::-1], [1.0, 2.0])
    m3 = ds.add_material("three", a.copy(), [[1.0], [2.0]])
    assert (m1.number, m2.number, m3.number) == (7, 2, 3)
    assert m1.config_set == m3.config_set != m2.config_set
    assert ds.find(7) is m1


@pytest.mark.parametrize("kwargs, error, text", [
    (dict(angles=[[0.1, 0.0, 1.7, 0.0]]), brdffit.InvalidArgumentError,
     r"row 0 .* zenith angles must lie in \[0, pi/2\]"),
    (dict(angles=[[0.1, 0.0, 0.2]]), ValueError, r"expected shape \(n, 4\)"),
    (dict(angles=[["a", "b", "c", "d"]]), TypeError,
     "angles: expected real numbers"),
    (dict(values=[1.0, 2.0]), ValueError, r"values: expected shape \(1,\)"),
    (dict(values=[np.inf]), brdffit.InvalidArgumentError,
     "a valid value must be finite"),
    (dict(valid=[1]), TypeError, "valid: expected a bool array"),
    (dict(number=-2), brdffit.InvalidArgumentError, "integer >= 0"),
    (dict(number=1), brdffit.InvalidArgumentError,
     "material number 1 is already taken"),
    (dict(channels=["R", "G"]), brdffit.InvalidArgumentError,
     "expected 1 non-empty names"),
])
def test_add_material_rejects_bad_input_clearly(kwargs, error, text):
    ds = brdffit.Dataset()
    ds.add_material("first", [[0.1, 0.0, 0.2, 0.0]], [1.0])
    args = dict(name="x", angles=[[0.1, 0.0, 0.2, 0.0]], values=[1.0])
    args.update(kwargs)
    with pytest.raises(error, match=text):
        ds.add_material(**args)
    assert len(ds) == 1  # nothing half-added


def test_lookups_fail_clearly(curet):
    with pytest.raises(brdffit.NotFoundError, match="no material numbered 99"):
        curet.find(99)
    with pytest.raises(brdffit.NotFoundError, match="no material named"):
        curet["Nothing"]
    with pytest.raises(IndexError, match="out of range"):
        curet[61]
    assert curet[-1].number == 61


def test_a_missing_file_is_a_load_error_naming_it(tmp_path):
    # A folder is read as CURET: its table.txt is missing here.
    with pytest.raises(brdffit.LoadError) as e:
        brdffit.load(tmp_path)
    assert isinstance(e.value, OSError)
    assert e.value.file == str(tmp_path / "table.txt")
    assert str(e.value).startswith(e.value.file + ": ")
    assert e.value.code_name == "BF_EIO"


def test_a_malformed_curet_table_names_file_and_line(tmp_path):
    # A small CURET-layout folder of our own (the real files are read in
    # place, never copied): line 3 has four numbers instead of five.
    (tmp_path / "table.txt").write_text(
        "1 0.5 0.1 0.2 0.3\n2 0.6 0.1 0.2 0.3\n3 0.5 0.1 0.2\n")
    (tmp_path / "abrdf.dat").write_text("1 0.1 0.2 0.3\n")
    with pytest.raises(brdffit.ParseError) as e:
        brdffit.load(tmp_path)
    assert e.value.file.endswith("table.txt") and e.value.line == 3
    assert str(e.value).startswith(e.value.file + ":3: ")
    assert e.value.code_name == "BF_EPARSE"


def test_an_unknown_format_name_is_not_found():
    with pytest.raises(brdffit.NotFoundError, match="unknown format 'tiff'"):
        brdffit.load("x", format="tiff")
