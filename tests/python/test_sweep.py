"""ontogen.sweep against `ontogen sweep`: the same table, value for value, and the same
results.csv, byte for byte."""

import csv
import os

import pytest

import ontogen
from conftest import cli

# A chain of 3 segments, LEN (1 + S + S^2) tall; A counts the apices (always 1).
CHAIN = """lsystem chain {
  #define LEN 1
  #define S 0.5
  #until 3
  axiom A(1)
  A(s) -> F(LEN * s) A(s * S)
}
"""


def cli_table(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return [{k: (None if v == "" else int(v) if k in ("variant", "seed") else v if k == "error" else float(v))
             for k, v in row.items()} for row in rows]


@pytest.fixture
def chain(tmp_path):
    path = tmp_path / "chain.cell"
    path.write_text(CHAIN)
    cli("sweep", path, "--out", tmp_path / "cli", "--define", "LEN=1:2:3", "--define", "S=0.5,0.25", "--seeds", "7:8",
        "--measure", "h=height", "--measure", "n=count(A)", "--size", "16x16", "--workers", "2")
    return path


def test_sweep_is_the_table_ontogen_sweep_writes(chain, tmp_path):
    rows = ontogen.sweep(chain, tmp_path / "py", defines={"LEN": "1:2:3", "S": [0.5, 0.25]}, seeds=(7, 8),
                         measures={"h": "height", "n": "count(A)"}, size=(16, 16), workers=2)
    expected = cli_table(tmp_path / "cli" / "results.csv")
    assert len(rows) == 12 and rows == expected
    assert [list(row) for row in rows[:1]] == [["variant", "LEN", "S", "seed", "h", "n", "error"]]
    assert [row["LEN"] for row in rows[::4]] == [1.0, 1.5, 2.0]
    assert rows[3]["h"] == 1 + 0.25 + 0.25 ** 2 and rows[3]["n"] == 1 and rows[3]["error"] is None
    for name in ("results.csv", "results.json"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name


def test_sweep_as_a_data_frame(chain, tmp_path):
    pandas = pytest.importorskip("pandas") if os.environ.get("CI") != "true" else __import__("pandas")
    frame = ontogen.sweep(ontogen.load(chain), tmp_path / "py", defines={"LEN": "1:2:3", "S": "0.5,0.25"},
                          seeds="7:8", measures=["h=height", "n=count(A)"], size="16x16", as_frame=True)
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.columns) == ["variant", "LEN", "S", "seed", "h", "n", "error"]
    assert frame.to_dict("records") == cli_table(tmp_path / "cli" / "results.csv")


def test_a_sweep_that_cannot_run_says_why(chain, tmp_path):
    with pytest.raises(ValueError, match="no #define WIDTH"):
        ontogen.sweep(chain, tmp_path / "a", defines={"WIDTH": [1, 2]})
    with pytest.raises(ValueError, match="seed and seeds"):
        ontogen.sweep(chain, tmp_path / "b", seed=1, seeds=(1, 2))
    ontogen.sweep(chain, tmp_path / "c", defines={"LEN": [1]})
    with pytest.raises(ValueError):  # the folder holds that sweep: only resume continues it
        ontogen.sweep(chain, tmp_path / "c", defines={"LEN": [2]})
