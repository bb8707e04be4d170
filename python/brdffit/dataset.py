"""dataset: measured BRDFs in any format the library reads, or built from
numpy arrays (the library's format-neutral bf_dataset).

A dataset holds materials; each has a name, a number (CURET's sample
number, or its 1-based position), its configurations -- angles (n, 4):
theta_i, phi_i, theta_o, phi_o in radians, in the measurement frame of
SPEC §1.5 (CURET's table.txt is stored view first, theta_o = theta_v) --
its channels ("mean", "R", "G", "B", "550", ...) and one BRDF value (sr^-1)
per configuration and channel, each with a valid mark.
"""

import os

import numpy as np

from . import _arrays
from ._errors import InvalidArgumentError, NotFoundError, check, new_error
from ._lib import ffi, lib, text
from ._streams import written_by


def _format_id(name):
    """The bf_format of a format name ("auto", "curet", "pbrt", "astm",
    "merl", "csv"); NotFoundError for another."""
    f = ffi.new("bf_format *")
    if not isinstance(name, str) or lib.bf_format_find(name.lower().encode(),
                                                       f) != 0:
        raise NotFoundError("unknown format %r (auto, curet, pbrt, astm, "
                            "merl, csv)" % (name,), 7)
    return f[0]


class Material:
    """One material of a Dataset (read-only; its arrays are copies).

    Attributes:
        index: position in the dataset (0-based).
        name: material name ("" when the data name none).
        number: material number (CURET's sample number, else its position).
        format: the format it was read from ("curet", ..., "memory").
        source: the file or folder it was read from ("" when none).
        channels: tuple of channel names.
        wavelengths: float64 array, nm per channel (NaN where none).
        angles: (n, 4) float64, theta_i, phi_i, theta_o, phi_o (radians,
            SPEC §1.5).
        values: (n, channels) float64 BRDF values as measured.
        valid: (n, channels) bool, False where the format marks a value
            invalid.
        config_set: id of its configuration list (materials with the same
            id share their configurations).
    """

    def __init__(self, dataset, index):
        ds = dataset._ds
        self.dataset = dataset
        self.index = index
        self.name = text(lib.bf_dataset_name(ds, index)) or ""
        self.number = int(lib.bf_dataset_number(ds, index))
        self.format = text(lib.bf_format_name(lib.bf_dataset_format(ds,
                                                                    index)))
        self.source = text(lib.bf_dataset_source(ds, index)) or ""
        self.config_set = int(lib.bf_dataset_set(ds, index))
        n = int(lib.bf_dataset_nconf(ds, index))
        c = int(lib.bf_dataset_nchannels(ds, index))
        self.channels = tuple(text(lib.bf_dataset_channel(ds, index, j))
                              for j in range(c))
        self.wavelengths = np.array([lib.bf_dataset_wavelength(ds, index, j)
                                     for j in range(c)])
        self.wavelengths.flags.writeable = False
        self.angles = _arrays.copy_doubles(lib.bf_dataset_angles(ds, index),
                                           (n, 4))
        self.values = _arrays.copy_doubles(lib.bf_dataset_values(ds, index),
                                           (n, c))
        valid = lib.bf_dataset_valid(ds, index)
        if valid == ffi.NULL:
            self.valid = np.ones((n, c), dtype=bool)
        else:
            self.valid = np.frombuffer(ffi.buffer(valid, n * c),
                                       dtype=np.uint8).reshape(n, c) != 0
        self.valid.flags.writeable = False

    @property
    def n_configs(self):
        """Number of configurations."""
        return self.angles.shape[0]

    def channel_index(self, channel):
        """The library's index of channel (a name, case-insensitive, or a
        wavelength in nm such as "550"); "mean" is the mean over the
        channels. NotFoundError when the material has no such channel."""
        c = ffi.new("size_t *")
        if lib.bf_dataset_channel_find(self.dataset._ds, self.index,
                                       str(channel).encode(), c) != 0:
            raise NotFoundError("material %d (%s) has no channel %r (it has:"
                                " %s, mean)" % (self.number, self.name,
                                                channel,
                                                ", ".join(self.channels)), 7)
        return int(c[0])

    def __repr__(self):
        return ("Material(%d %r, %s, %d configurations, channels %s)"
                % (self.number, self.name, self.format, self.n_configs,
                   ",".join(self.channels)))


class Dataset:
    """Measured materials (bf_dataset): loaded by brdffit.load(path), or
    built in memory -- Dataset() and add_material(), or
    Dataset.from_arrays().

    len(ds) is the number of materials; ds[i] is the i-th Material (an int
    index, or a name); ds.find(number) looks one up by its number;
    ds.materials lists them all.
    """

    def __init__(self):
        """An empty dataset (format "memory") to add materials to."""
        self._wrap(lib.bf_dataset_alloc())
        if self._ds == ffi.NULL:
            raise MemoryError("Dataset: out of memory")

    def _wrap(self, ptr):
        self._ds = ffi.gc(ptr, lib.bf_dataset_free)
        self._sets = []  # (angles, set id) of the sets added here
        self._materials = []

    @classmethod
    def _adopt(cls, ptr):
        """A Dataset owning the bf_dataset ptr (from a reader)."""
        ds = cls.__new__(cls)
        ds._wrap(ptr)
        return ds

    @classmethod
    def from_arrays(cls, angles, values, names=None, channels=None,
                    valid=None, wavelengths=None):
        """A dataset of materials measured at the same configurations.

        Args:
            angles: (n, 4) theta_i, phi_i, theta_o, phi_o in radians
                (measurement frame, SPEC §1.5).
            values: BRDF values: (n,) one material, one channel; (n, c)
                one material, c channels; (m, n, c) m materials.
            names: a name, or m names (default "material 1", ...).
            channels: c channel names (default "1", "2", ...).
            valid: bool array of values' shape (default all valid).
            wavelengths: c wavelengths in nm, or None.
        Returns a Dataset with m materials numbered 1..m.
        """
        v = _arrays.real("values", values)
        if v.ndim not in (1, 2, 3):
            raise ValueError("values: expected shape (n,), (n, c) or "
                             "(m, n, c), got %s" % (v.shape,))
        ok = None if valid is None else np.asarray(valid)
        if ok is not None and ok.shape != v.shape:
            raise ValueError("valid: expected the shape of values %s, got %s"
                             % (v.shape, ok.shape))
        if v.ndim < 3:
            v = v.reshape((1,) + v.shape)
            ok = None if ok is None else ok.reshape((1,) + ok.shape)
        if names is None:
            names = ["material %d" % (i + 1) for i in range(v.shape[0])]
        elif isinstance(names, str):
            names = [names]
        if len(names) != v.shape[0]:
            raise ValueError("names: %d names for %d materials"
                             % (len(names), v.shape[0]))
        ds = cls()
        for i, name in enumerate(names):
            ds.add_material(name, angles, v[i], channels=channels,
                            valid=None if ok is None else ok[i],
                            wavelengths=wavelengths)
        return ds

    def _config_set(self, angles):
        """The id of a configuration set equal to angles, added if new."""
        for a, set_id in self._sets:
            if a.shape == angles.shape and np.array_equal(a, angles):
                return set_id
        set_id = ffi.new("size_t *")
        bad = ffi.new("size_t *")
        rc = lib.bf_dataset_add_configs(self._ds, len(angles),
                                        _arrays.doubles(angles), set_id, bad)
        if rc == 1:
            raise InvalidArgumentError(
                "angles: row %d (theta_i, phi_i, theta_o, phi_o) = %s: zenith"
                " angles must lie in [0, pi/2] (radians) and azimuths be "
                "finite" % (bad[0], tuple(float(x) for x in angles[bad[0]])),
                1)
        check(rc, context="add_material")
        self._sets.append((angles.copy(), int(set_id[0])))
        return int(set_id[0])

    def add_material(self, name, angles, values, channels=None, number=0,
                     valid=None, wavelengths=None, source=None):
        """Adds a material and returns it (a Material).

        Args:
            name: material name (str), or None.
            angles: (n, 4) theta_i, phi_i, theta_o, phi_o in radians
                (SPEC §1.5); materials given equal angles share one
                configuration set.
            values: (n,) or (n, c) BRDF values (sr^-1), kept as measured
                (negative values included, SPEC §2).
            channels: c channel names (default "1", "2", ...).
            number: material number > 0, or 0 for its 1-based position.
            valid: bool array of values' shape, False marks an invalid
                value (default: all valid); a valid value must be finite.
            wavelengths: c wavelengths in nm, or None.
            source: where the data came from (for messages), or None.
        Raises TypeError/ValueError for bad arrays and
        InvalidArgumentError when the library refuses the material (number
        taken, empty channel name, non-finite valid value).
        """
        a = _arrays.matrix("angles", angles, 4)
        v = _arrays.real("values", values)
        if v.ndim == 1:
            v = v.reshape(-1, 1)
        if v.ndim != 2 or v.shape[0] != a.shape[0] or v.shape[1] == 0:
            raise ValueError("values: expected shape (%d,) or (%d, c) for %d"
                             " configurations, got %s"
                             % (len(a), len(a), len(a), v.shape))
        n_ch = v.shape[1]
        ok = np.ones(v.shape, dtype=bool) if valid is None else \
            np.asarray(valid)
        if ok.dtype != bool:
            raise TypeError("valid: expected a bool array, got dtype %s"
                            % ok.dtype)
        if ok.ndim == 1:
            ok = ok.reshape(-1, 1)
        if ok.shape != v.shape:
            raise ValueError("valid: expected shape %s, got %s"
                             % (v.shape, ok.shape))
        bad = np.argwhere(ok & ~np.isfinite(v))
        if len(bad):
            raise InvalidArgumentError(
                "values: value at (configuration %d, channel %d) is %r; a "
                "valid value must be finite (mark it invalid instead)"
                % (bad[0][0], bad[0][1], float(v[tuple(bad[0])])), 1)
        if not isinstance(number, (int, np.integer)) or number < 0:
            raise InvalidArgumentError("number: expected an integer >= 0, "
                                       "got %r" % (number,), 1)
        if number > 0 and lib.bf_dataset_find(self._ds, int(number)) >= 0:
            raise InvalidArgumentError("number: material number %d is "
                                       "already taken" % number, 1)
        keep = []
        desc = ffi.new("bf_material_desc *")
        if name is not None:
            keep.append(ffi.new("char[]", str(name).encode()))
            desc.name = keep[-1]
        desc.number = int(number)
        desc.format = lib.BF_FORMAT_MEMORY
        if source is not None:
            keep.append(ffi.new("char[]", os.fsencode(source)))
            desc.source = keep[-1]
        desc.set = self._config_set(a)
        desc.n_channels = n_ch
        if channels is not None:
            channels = [str(c) for c in channels]
            if len(channels) != n_ch or not all(channels):
                raise InvalidArgumentError(
                    "channels: expected %d non-empty names, got %r"
                    % (n_ch, channels), 1)
            keep.append([ffi.new("char[]", c.encode()) for c in channels])
            keep.append(ffi.new("const char *[]", keep[-1]))
            desc.channel = keep[-1]
        if wavelengths is not None:
            w = _arrays.real("wavelengths", wavelengths).ravel()
            if w.shape != (n_ch,):
                raise ValueError("wavelengths: expected %d values, got %s"
                                 % (n_ch, w.shape))
            keep.append(w)
            desc.wavelength = _arrays.doubles(w)
        keep.append(v)
        desc.values = _arrays.doubles(v)
        mask = np.ascontiguousarray(ok, dtype=np.uint8)
        keep.append(mask)
        desc.valid = ffi.from_buffer("unsigned char[]", mask)
        index = ffi.new("size_t *")
        check(lib.bf_dataset_add_material(self._ds, desc, index),
              context="add_material")
        return self[int(index[0])]

    @property
    def materials(self):
        """Every Material, in dataset order."""
        return [self[i] for i in range(len(self))]

    def __len__(self):
        return int(lib.bf_dataset_count(self._ds))

    def __getitem__(self, key):
        """ds[i]: the material at index i (negative counts from the end);
        ds["name"]: the material of that name."""
        if isinstance(key, str):
            for i in range(len(self)):
                if text(lib.bf_dataset_name(self._ds, i)) == key:
                    return self[i]
            raise NotFoundError("no material named %r" % key, 7)
        if not isinstance(key, (int, np.integer)):
            raise TypeError("Dataset indices are int or str, not %s"
                            % type(key).__name__)
        n = len(self)
        i = int(key) + n if key < 0 else int(key)
        if not 0 <= i < n:
            raise IndexError("material index %d out of range (%d materials)"
                             % (key, n))
        while len(self._materials) < n:
            self._materials.append(None)
        if self._materials[i] is None:
            self._materials[i] = Material(self, i)
        return self._materials[i]

    def __iter__(self):
        return iter(self.materials)

    def find(self, number):
        """The material numbered number (CURET's sample number);
        NotFoundError when none is."""
        i = lib.bf_dataset_find(self._ds, int(number))
        if i < 0:
            raise NotFoundError("no material numbered %d" % number, 7)
        return self[int(i)]

    def material(self, key):
        """The Material that key names: a Material of this dataset, a
        material number (int) or a name (str)."""
        if isinstance(key, Material):
            if key.dataset is not self:
                raise InvalidArgumentError("material %r belongs to another "
                                           "dataset" % (key,), 1)
            return key
        if isinstance(key, str):
            return self[key]
        return self.find(key)

    def to_csv(self, path=None):
        """The dataset as brdffit's tidy CSV (bf_csv_write; README "Tidy
        CSV"), the file `brdffit convert --to csv` writes: every material,
        angles in degrees, values that read back bit for bit, invalid
        values empty. Written to path (str or os.PathLike) when given,
        else returned as text. Raises InvalidArgumentError for a dataset
        that would not read back identically (materials with different
        channels, two materials under one name, a line break in a name, a
        channel named like one of the CSV's own columns or ending in
        "nm"; include/brdffit.h, bf_csv_write)."""
        rc, out = written_by(lambda fp: lib.bf_csv_write(self._ds, fp))
        if rc == 1:
            raise InvalidArgumentError(
                "to_csv: this dataset cannot be written as tidy CSV so that"
                " it reads back identically (materials with different "
                "channels, two under one name, a line break in a name, or a"
                " channel name the CSV reserves)", rc)
        check(rc, context="to_csv")
        if path is None:
            return out
        with open(os.fspath(path), "w", encoding="utf-8", newline="") as f:
            f.write(out)
        return None

    def __repr__(self):
        return "Dataset(%d materials)" % len(self)


def load(path, format="auto", at=None, all_cells=False):
    """Loads measurements in any format the library reads
    (bf_dataset_load): a CURET folder (table.txt, abrdf.dat, samples.tsv),
    a pbrt-v2/Cornell .brdf, an ASTM E1392 .astm, a MERL .binary or a tidy
    CSV; the format is detected from the content unless given.

    Args:
        path: file or folder (str or os.PathLike).
        format: "auto" (default), "curet", "pbrt", "astm", "merl", "csv".
        at: MERL only -- (n, 4) configurations to sample (radians,
            measurement frame).
        all_cells: MERL only -- True for every valid cell instead.
    Returns a Dataset. Raises LoadError (cannot open), ParseError (the
    file, line and problem), NotFoundError (unknown format name).
    """
    opts = ffi.new("bf_load_opts *")
    opts.format = _format_id(format)
    keep = None
    if at is not None:
        keep = _arrays.matrix("at", at, 4)
        opts.n_at = len(keep)
        opts.at = _arrays.doubles(keep)
    opts.all_cells = 1 if all_cells else 0
    out = ffi.new("bf_dataset **")
    err = new_error()
    rc = lib.bf_dataset_load(os.fsencode(os.fspath(path)), opts, out, err)
    check(rc, err)
    return Dataset._adopt(out[0])
