"""brdffit.load() on every format the library reads, each checked against
the file parsed or written here with numpy: the five real Cornell .brdf
files (pbrt-v2), a MERL table written by the test, tidy CSV (by hand, and
Dataset.to_csv's round trip), ASTM E1392; and the errors -- a missing
path is a LoadError, a malformed file a ParseError carrying the library's
file, line and problem -- and bad arrays are clear errors before C sees
them."""

import os
import re

import numpy as np
import pytest

import brdffit
from conftest import CORNELL_FILES


def numbers_of(path):
    """Every number of a pbrt file ('#' comments to the end of the line)."""
    with open(path) as f:
        text = re.sub(r"#[^\n]*", " ", f.read())
    return np.array(text.split(), dtype=float)


def test_the_five_cornell_files_load_as_their_numbers(cornell_dir):
    for stem in CORNELL_FILES:
        path = os.path.join(cornell_dir, stem + ".brdf")
        ds = brdffit.load(path)
        x = numbers_of(path)
        w = int(x[0])
        records = x[1 + w:].reshape(-1, 4 + w)
        assert len(ds) == 1 and len(records) == 1439  # SOURCES.md
        m = ds[0]
        assert (m.format, m.source, m.number) == ("pbrt", path, 1)
        np.testing.assert_array_equal(m.wavelengths, x[1:1 + w])
        np.testing.assert_array_equal(m.wavelengths,
                                      np.arange(400.0, 701.0, 10.0))
        assert m.channels == tuple("%d" % v for v in x[1:1 + w])
        np.testing.assert_array_equal(m.angles, records[:, :4])
        np.testing.assert_array_equal(m.values, records[:, 4:])
        assert m.valid.all()
    # Names: the file's description, else the file name (pbrt.c).
    assert brdffit.load(os.path.join(cornell_dir, "cayman.brdf"))[0].name \
        == "Cayman Metallic, High-gloss Paint"
    assert brdffit.load(os.path.join(cornell_dir,
                                     "acryl_blue.brdf"))[0].name \
        == "acryl_blue"


# MERL .binary (SPEC §8): 90 x 90 x 180 cells of (theta_h, theta_d,
# phi_d), channel-planar R, G, B, value = raw * scale.
MERL_DIMS = (90, 90, 180)
MERL_SCALE = np.array([1.0, 1.15, 1.66]) / 1500.0


def merl_cell(angles):
    """The cell (i, j, k) of configurations (n, 4) (measurement frame),
    from Rusinkiewicz's half and difference angles computed here."""
    ti, pi_, to, po = angles.T

    def direction(t, p):
        return np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p),
                         np.cos(t)], axis=1)
    wi, wo = direction(ti, pi_), direction(to, po)
    h = wi + wo
    h /= np.linalg.norm(h, axis=1)[:, None]
    th, ph = np.arccos(np.clip(h[:, 2], -1, 1)), np.arctan2(h[:, 1], h[:, 0])
    # d: wi rotated by -phi_h about z, then by -theta_h about y.
    x = np.cos(ph) * wi[:, 0] + np.sin(ph) * wi[:, 1]
    y = -np.sin(ph) * wi[:, 0] + np.cos(ph) * wi[:, 1]
    z = wi[:, 2]
    dx, dz = np.cos(th) * x - np.sin(th) * z, np.sin(th) * x + np.cos(th) * z
    td, pd = np.arccos(np.clip(dz, -1, 1)), np.arctan2(y, dx)
    pd = np.where(pd < 0, pd + np.pi, pd)
    coords = np.stack([np.sqrt(th / (np.pi / 2)) * 90, td / (np.pi / 2) * 90,
                       pd / np.pi * 180], axis=1)
    cell = np.clip(np.floor(coords), 0, np.array(MERL_DIMS) - 1)
    return cell.astype(int), coords


def test_a_merl_table_is_looked_up_cell_by_cell(tmp_path):
    # raw value of channel c at cell (i, j, k): its flat index + 1, times
    # c + 1; cells with k % 7 == 0 are marked invalid (negative).
    n_cells = np.prod(MERL_DIMS)
    flat = np.arange(n_cells, dtype=np.float64).reshape(MERL_DIMS)
    raw = np.stack([(flat + 1.0) * (c + 1) for c in range(3)])
    raw[:, :, :, ::7] *= -1.0
    path = tmp_path / "synthetic.binary"
    with open(path, "wb") as f:
        f.write(np.array(MERL_DIMS, dtype="<i4").tobytes())
        f.write(raw.astype("<f8").tobytes())
    rng = np.random.default_rng(11)
    at = np.column_stack([rng.uniform(0, 1.5, 400),
                          rng.uniform(-np.pi, np.pi, 400),
                          rng.uniform(0, 1.5, 400),
                          rng.uniform(-np.pi, np.pi, 400)])
    cell, coords = merl_cell(at)
    # Leave out configurations within 1e-9 of a cell border (where the
    # rounding of this computation and the library's may differ).
    clear = (np.abs(coords - np.round(coords)) > 1e-9).all(axis=1)
    at, cell = at[clear], cell[clear]
    m = brdffit.load(path, at=at)[0]
    assert m.format == "merl" and m.channels == ("R", "G", "B")
    np.testing.assert_array_equal(m.angles, at)
    i, j, k = cell.T
    # Invalid cells keep their negative values, as read (never clamped).
    np.testing.assert_array_equal(m.values, raw[:, i, j, k].T * MERL_SCALE)
    np.testing.assert_array_equal(m.valid, np.repeat((k % 7 != 0)[:, None],
                                                     3, axis=1))
    with pytest.raises(brdffit.InvalidArgumentError):  # neither at nor all
        brdffit.load(path)
    # A truncated table: the reader names the file and the size.
    short = tmp_path / "short.binary"
    short.write_bytes(path.read_bytes()[:1000])
    with pytest.raises(brdffit.ParseError) as e:
        brdffit.load(short, at=at)
    assert e.value.file == str(short) and str(e.value).startswith(str(short))


CSV_TEXT = """# measured by hand
material,theta_i,phi_i,theta_o,phi_o,R,G
felt,10,0,20,180,0.031,0.029
"paint, blue",10,0,20,180,0.51,0.66
felt,30,0,40,90,0.025,
"paint, blue",30,0,40,90,0.5,0.6
"""


def test_a_tidy_csv_loads_in_degrees_with_empty_fields_invalid(tmp_path):
    path = tmp_path / "hand.csv"
    path.write_text(CSV_TEXT)
    ds = brdffit.load(path)
    assert [m.name for m in ds] == ["felt", "paint, blue"]
    felt, paint = ds
    assert felt.format == "csv" and felt.channels == ("R", "G")
    assert felt.config_set == paint.config_set  # the same configurations
    np.testing.assert_allclose(felt.angles, np.radians(
        [[10, 0, 20, 180], [30, 0, 40, 90]]), rtol=1e-15)
    np.testing.assert_array_equal(felt.valid, [[True, True], [True, False]])
    np.testing.assert_array_equal(felt.values[felt.valid],
                                  [0.031, 0.029, 0.025])
    np.testing.assert_array_equal(paint.values, [[0.51, 0.66], [0.5, 0.6]])


def test_to_csv_reads_back_bit_for_bit(tmp_path):
    rng = np.random.default_rng(3)
    angles = np.column_stack([rng.uniform(0, np.pi / 2, 30),
                              rng.uniform(-np.pi, np.pi, 30),
                              rng.uniform(0, np.pi / 2, 30),
                              rng.uniform(-np.pi, np.pi, 30)])
    values = rng.normal(0.3, 0.2, (2, 30, 3))  # negatives kept (SPEC §2)
    valid = rng.uniform(size=values.shape) > 0.1
    ds = brdffit.Dataset.from_arrays(angles, values, names=["a", "b, c"],
                                     channels=["R", "G", "550"],
                                     wavelengths=[np.nan, np.nan, 550.0],
                                     valid=valid)
    ds.to_csv(tmp_path / "out.csv")
    back = brdffit.load(tmp_path / "out.csv")
    assert back[0].format == "csv" and len(back) == 2
    for m, b in zip(ds, back):
        assert (b.name, b.channels) == (m.name, m.channels)
        np.testing.assert_array_equal(b.wavelengths, m.wavelengths)
        np.testing.assert_array_equal(b.angles, m.angles)
        np.testing.assert_array_equal(b.valid, m.valid)
        np.testing.assert_array_equal(b.values[b.valid], m.values[m.valid])
    text = ds.to_csv()
    assert text == (tmp_path / "out.csv").read_text()
    assert text.splitlines()[0] == ("material,theta_i,phi_i,theta_o,phi_o,"
                                    "R,G,550nm")
    two = brdffit.Dataset()
    two.add_material("x", angles, values[0])
    two.add_material("x", angles, values[1])  # one name twice
    with pytest.raises(brdffit.InvalidArgumentError, match="two under one"):
        two.to_csv()


ASTM_TEXT = """SOURCE test
SAMPLE_NAME "blue paint"
NUM_POINTS 3
VARS theta_i,phi_i,theta_s,phi_s,R,G,B
0.1,0,0.2,3.1,0.5,0.25,-0.125
0.2,0,0.3,1.5,0.75,0.5,0.25
0.3,0.5,0.4,-1.5,1,2,3
"""


def test_an_astm_file_loads_as_written(tmp_path):
    path = tmp_path / "paint.astm"
    path.write_text(ASTM_TEXT)
    (m,) = brdffit.load(path)
    assert (m.format, m.name, m.channels) == ("astm", "blue paint",
                                             ("R", "G", "B"))
    np.testing.assert_array_equal(m.angles, [[0.1, 0, 0.2, 3.1],
                                             [0.2, 0, 0.3, 1.5],
                                             [0.3, 0.5, 0.4, -1.5]])
    np.testing.assert_array_equal(m.values, [[0.5, 0.25, -0.125],
                                             [0.75, 0.5, 0.25], [1, 2, 3]])


@pytest.mark.parametrize("name, text, line", [
    ("bad.brdf", "2\n500 600\n0.1 0 0.2 3.0 1 2\n0.1 0 0.2 x 1 2\n", 4),
    ("bad.astm", ASTM_TEXT.replace("0.75,0.5,0.25", "0.75,0.5"), 6),
    ("bad.csv", CSV_TEXT.replace("0.5,0.6", "0.5,0.6x"), 6),
])
def test_a_malformed_file_names_its_file_and_line(tmp_path, name, text,
                                                  line):
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(brdffit.ParseError) as e:
        brdffit.load(path)
    assert e.value.file == str(path) and e.value.line == line
    assert str(e.value).startswith("%s:%d: " % (path, line))
    assert e.value.reason and e.value.reason in str(e.value)


def test_a_missing_path_is_a_load_error(tmp_path):
    path = tmp_path / "nothing.brdf"
    with pytest.raises(brdffit.LoadError) as e:
        brdffit.load(path)
    assert e.value.file == str(path) and e.value.line == 0
    assert str(e.value) == "%s: %s" % (path, e.value.reason)
    assert "No such file" in e.value.reason


def test_bad_arrays_are_clear_errors_never_a_crash(tmp_path):
    a = np.array([[0.1, 0.0, 0.2, 3.0], [0.3, 0.0, 0.4, 1.0]])
    # Non-contiguous and Fortran-ordered arrays are copied, never misread.
    strided = np.zeros((2, 8))
    strided[:, ::2] = a
    for angles in (strided[:, ::2], np.asfortranarray(a)):
        m = brdffit.Dataset.from_arrays(angles, [1.0, 2.0])[0]
        np.testing.assert_array_equal(m.angles, a)
    with pytest.raises(TypeError, match="values: expected real numbers"):
        brdffit.Dataset.from_arrays(a, np.array([1 + 1j, 2]))
    with pytest.raises(TypeError, match="angles: expected real numbers"):
        brdffit.Dataset.from_arrays(a.astype(object), [1.0, 2.0])
    with pytest.raises(ValueError, match=r"values: expected shape \(n,\)"):
        brdffit.Dataset.from_arrays(a, np.zeros((2, 2, 2, 2)))
    with pytest.raises(ValueError, match=r"at: expected shape \(n, 4\)"):
        brdffit.load(tmp_path / "x.binary", at=np.zeros((3, 3)))
    with pytest.raises(TypeError, match="not an array of numbers"):
        brdffit.load(tmp_path / "x.binary", at=[[0, 0, 0, 0], [1]])
