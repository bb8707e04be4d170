"""records: the rows of a table the library writes (fits.csv,
ranking.csv) as Python records.

The library owns the tables' columns and formats. compare()'s records
are built from the library's structs (bf_fits_lines); rank() asks its
writer for ranking.csv's text and from_csv reads it back, column by
column, as pandas.read_csv infers types -- a column whose every value is
an integer becomes int, one whose values are numbers becomes float, any
other stays str; an empty field is None (NaN in a DataFrame). Columns that
hold names and words (TEXT_COLUMNS: a material named "123", a unit "1")
stay str whatever they hold.
"""

import csv
import io

# Columns of fits.csv and ranking.csv that name things or hold words: never
# converted to numbers.
TEXT_COLUMNS = frozenset(("name", "channel", "model", "parameter", "unit",
                          "objective", "fit", "ci_method", "flags",
                          "counts_as") +
                         tuple("p%d" % i for i in range(1, 17)))


def _convert(values):
    """The column values converted as described in the module doc."""
    present = [v for v in values if v != ""]
    for kind in (int, float):
        try:
            converted = [kind(v) for v in present]
        except ValueError:
            continue
        it = iter(converted)
        return [None if v == "" else next(it) for v in values]
    return [None if v == "" else v for v in values]


class Records(list):
    """A list of dicts, one per row, keyed by the table's column names
    (in the table's order: see .columns), plus .to_dataframe().

    Attributes:
        columns: the column names, in the table's order.
        text: the CSV text the records were read from ("" when built from
            rows).
        wins: for brdffit.rank, {criterion: [(model, wins), ...]}; None
            otherwise.
    """

    def __init__(self, rows=(), columns=(), text=""):
        super().__init__(rows)
        self.columns = tuple(columns)
        self.text = text
        self.wins = None

    @classmethod
    def from_csv(cls, text):
        """Records of the CSV text (a header line, then rows)."""
        reader = csv.reader(io.StringIO(text, newline=""))
        try:
            header = next(reader)
        except StopIteration:
            return cls(text=text)
        rows = [r for r in reader if r]
        for r in rows:
            if len(r) != len(header):
                raise ValueError("records: a row has %d fields, the header "
                                 "%d" % (len(r), len(header)))
        cols = [[None if r[j] == "" else r[j] for r in rows]
                if header[j] in TEXT_COLUMNS
                else _convert([r[j] for r in rows])
                for j in range(len(header))]
        return cls(({h: cols[j][i] for j, h in enumerate(header)}
                    for i in range(len(rows))), header, text)

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
