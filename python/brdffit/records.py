"""records: the rows of a table the library writes (fits.csv,
ranking.csv, dispersion.csv) as Python records.

The library owns the tables' columns and formats; the records are built
from its structs (bf_fits_lines, bf_ranking_lines, bf_dispersion_points:
brdffit._study), never
from the CSV text read back: a number is the library's int or double, a
name or word (a material named "123", a unit "1") its text, an empty
field None (NaN in a DataFrame).
"""


class Records(list):
    """A list of dicts, one per row, keyed by the table's column names
    (in the table's order: see .columns), plus .to_dataframe().

    Attributes:
        columns: the column names, in the table's order.
        text: the CSV text the library wrote for the same lines ("" when
            built from rows).
        wins: for brdffit.rank, {criterion: [(model, wins), ...]}; None
            otherwise.
        dispersion: for brdffit.compare, the rows of dispersion.csv
            (Records: sample, name, channel, model, wavelength_nm, n,
            ci_low, ci_high, n_ml; empty without fresnel="dielectric" on
            spectral channels); None otherwise.
    """

    def __init__(self, rows=(), columns=(), text=""):
        super().__init__(rows)
        self.columns = tuple(columns)
        self.text = text
        self.wins = None
        self.dispersion = None

    def column(self, name):
        """The values of column name, as a list."""
        return [r[name] for r in self]

    def to_dataframe(self):
        """The records as a pandas DataFrame (columns in table order).
        Raises ImportError when pandas is not installed (it is optional)."""
        try:
            import pandas
        except ImportError as exc:
            raise ImportError("to_dataframe needs pandas (Debian: "
                              "python3-pandas); the records themselves are "
                              "plain dicts") from exc
        df = pandas.DataFrame.from_records(list(self),
                                           columns=list(self.columns))
        for col in self.columns:  # every field empty: a number column
            if all(r[col] is None for r in self):
                df[col] = df[col].astype(float)
        return df
