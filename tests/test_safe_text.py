"""Text from a spec is data, never syntax (issue 38, items 1 and 7): the exact names of the
issue in every format gearcoupling writes, each output read back by a real reader, and a
property test over arbitrary unicode names."""

from __future__ import annotations

import csv
import dataclasses
import json
import re

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.export import export_part
from gearcoupling.hob import (
    hob_program,
    measuring_charts,
    plot_measuring_charts,
    write_nominal_csv,
)
from gearcoupling.io import (
    csv_comment,
    escaped,
    gcode_comment,
    inp_comment,
    markdown_text,
    plot_text,
    step_text,
    terminal_text,
    vtk_header,
    write_csv_columns,
    write_csv_rows,
    xml_text,
)
from gearcoupling.loading import write_capacity_csv
from gearcoupling.loading.capacity import Capacity
from gearcoupling.parts import build_part
from gearcoupling.plots import save_figure
from gearcoupling.spec import resolve_spec_path

import clients

#: the names of issue 38
GCODE_NAME = "x)\nM30\nG0 X0 Z-50\n("  # lines 3-4 of hob_program.nc on main
INCLUDE_NAME = "x\n*INCLUDE, INPUT=/etc/passwd\n**"  # a live keyword line in hub.inp
ROWS_NAME = "x\nrow,before,the,header"  # a row before the header of a CSV
FORMULA_NAME = "=cmd|' /C calc'!A0"  # capacity.csv
ESC_NAME = "\x1b[2J\x1b[31mred\x1b[0m"  # clears the terminal, colours it
MARKUP_NAME = "[bold red]x[/bold red] [link=file:///etc/passwd]y[/link]"  # rich markup
NUL_NAME = "a\x00b"
#: one of each kind of character a name must not hold
UNPRINTABLE = [GCODE_NAME, NUL_NAME, ESC_NAME, "a\x7fb", "a\x85b", "a\u2028b", "a\u202eb",
               "a\tb", "a\u00a0b", "a\ue000b"]
HOB_DIAMETER_MM = 101.6


@pytest.fixture(scope="module")
def hub(renzo):
    """A one-tooth hub mesh of renzo-1967 (any spec name can be written with it)."""
    return build_part(renzo, "hub", tolerance_mm=0.05, teeth=[0])


@pytest.fixture(scope="module")
def program(renzo):
    return hob_program(renzo, HOB_DIAMETER_MM)


def named(spec, name: str):
    """``spec`` under ``name``, past the load-time check (as a library caller can)."""
    return dataclasses.replace(spec, name=name)


def spec_file(folder, stem: str, name: str | None, renzo_text: str):
    """renzo-1967 as a spec file ``<stem>.toml``, with ``name = ...`` when given."""
    path = folder / f"{stem}.toml"
    # a TOML basic string: JSON's escapes of C0 are TOML's, DEL must be escaped too
    quoted = json.dumps(name, ensure_ascii=False).replace("\x7f", "\\u007f")
    head = "" if name is None else f"name = {quoted}\n"
    path.write_text(head + renzo_text)
    return path


@pytest.fixture(scope="module")
def renzo_mm(renzo):
    """renzo-1967's resolved file (mm) as plain data."""
    return renzo.to_dict()


@pytest.fixture(scope="module")
def renzo_text():
    return resolve_spec_path("renzo-1967").read_text()


# ---------------------------------------------------------------- layer (b): spec load


@pytest.mark.parametrize("name", UNPRINTABLE)
def test_a_spec_name_with_a_control_or_format_character_is_refused(tmp_path, renzo_text,
                                                                   name):
    path = spec_file(tmp_path, "spec", name, renzo_text)
    with pytest.raises(gc.SpecError, match="printable characters only") as err:
        gc.load_spec(path)
    assert err.value.field == "name"
    assert repr(name) in str(err.value) and str(err.value).isprintable()  # on one line


def test_the_cli_refuses_the_gcode_name_in_one_line_with_exit_2(tmp_path, renzo_text, capsys):
    path = spec_file(tmp_path, "spec", GCODE_NAME, renzo_text)
    assert main(["hob", str(path), "--hob-diameter", "101.6", "-o", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "name = " in err and "\x1b" not in err
    assert not (tmp_path / "o").exists()


def test_printable_names_load_unchanged(tmp_path, renzo_text):
    for name in (FORMULA_NAME, MARKUP_NAME, "Kupplung Ø 120 – Größe 3 😀", "a$b\\c", ""):
        assert gc.load_spec(spec_file(tmp_path, "spec", name, renzo_text)).name == name


def test_a_name_from_the_file_stem_gets_its_control_characters_escaped(tmp_path, renzo_text,
                                                                       capsys):
    """Without ``name`` the file's stem names the spec: the issue's G-code name as a file
    name gives a one-line name, and ``hob`` a program with the lines of any other name."""
    path = spec_file(tmp_path, GCODE_NAME, None, renzo_text)
    spec = gc.load_spec(path)
    assert spec.name == r"x)\x0aM30\x0aG0 X0 Z-50\x0a(" and spec.name.isprintable()
    out = tmp_path / "out"
    assert main(["hob", str(path), "--hob-diameter", "101.6", "-o", str(out)]) == 0
    plain = spec_file(tmp_path, "plain", None, renzo_text)
    assert main(["hob", str(plain), "--hob-diameter", "101.6", "-o", str(tmp_path / "p")]) == 0
    got = (out / "hob_program.nc").read_text().splitlines()
    ref = (tmp_path / "p" / "hob_program.nc").read_text().splitlines()
    assert len(got) == len(ref) and got[2:] == ref[2:] and got[0] == "%"
    assert got[1] == gcode_comment(f"gearcoupling hob program: spec {spec.name}, crowning "
                                   f"{spec.hub.crowning.kind}")
    assert "\x1b" not in capsys.readouterr().out


# ---------------------------------------------------------------- G-code


def program_words(text: str) -> list[str]:
    """The blocks of a G-code program with its ``( )`` comments removed, as a controller
    reads them; a comment that does not close on its line is refused."""
    blocks = []
    for line in text.splitlines():
        body = re.sub(r"\([^()]*\)", "", line)
        assert "(" not in body and ")" not in body and ";" not in body, line
        if body.strip():
            blocks.append(body.strip())
    return blocks


@pytest.mark.parametrize("name", [GCODE_NAME, NUL_NAME, "a;b%c", "ü€\u202e"])
def test_the_gcode_name_stays_a_comment(program, name):
    """The issue's name: on main lines 3-4 were ``M30`` and ``G0 X0 Z-50`` (a rapid move to
    the hub axis). Now the program's blocks are those of any other name."""
    text = dataclasses.replace(program, spec_name=name).gcode()
    ref = program.gcode()
    assert len(text.splitlines()) == len(ref.splitlines())
    assert program_words(text) == program_words(ref)
    assert program_words(text).count("M30") == 1 and program_words(text)[-2] == "M30"
    assert text.isascii() and "\x00" not in text
    line = text.splitlines()[1]
    assert line.startswith("(gearcoupling hob program: spec ") and line.endswith(")")
    assert not set(line[1:-1]) & set("();%")  # ; and % end a block or a program elsewhere


# ---------------------------------------------------------------- INP, VTK, 3MF, STEP


def keyword_lines(path) -> list[str]:
    """The keyword lines of an INP file (``*...``, not ``**`` comments), as CalculiX reads
    them: the first 132 characters of each line."""
    return [ln[:132] for ln in path.read_text().splitlines()
            if ln.startswith("*") and not ln.startswith("**")]


def test_the_include_name_stays_an_inp_comment(tmp_path, renzo, hub):
    import meshio

    evil = export_part(named(renzo, INCLUDE_NAME), "hub", tmp_path / "evil.inp", mesh=hub)
    ref = export_part(renzo, "hub", tmp_path / "ref.inp", mesh=hub)
    assert keyword_lines(evil) == keyword_lines(ref)
    assert not any(ln.upper().startswith("*INCLUDE") for ln in keyword_lines(evil))
    lines = evil.read_text().splitlines()
    assert len(lines) == len(ref.read_text().splitlines())
    assert all(len(ln) <= 132 and ln.isascii() for ln in lines)
    back = meshio.read(evil, file_format="abaqus")
    assert len(back.cells[0].data) == len(hub.faces)
    assert set(back.cell_sets) == set(meshio.read(ref, file_format="abaqus").cell_sets)


@pytest.mark.parametrize("name", [INCLUDE_NAME, ESC_NAME, "é" * 300])
def test_the_vtk_header_is_one_line_the_vtk_reader_reads(tmp_path, renzo, hub, name):
    vtk = clients.module("vtk", "pip install vtk (in the test extra)")
    path = export_part(named(renzo, name), "hub", tmp_path / "hub.vtk", mesh=hub)
    reader = vtk.vtkUnstructuredGridReader()
    reader.ReadAllScalarsOn()
    reader.SetFileName(str(path))
    reader.Update()
    assert reader.GetOutput().GetNumberOfCells() == len(hub.faces)
    assert reader.GetOutput().GetCellData().GetArray("kind") is not None
    assert reader.GetHeader() == vtk_header(f"{name}-hub (mm)")
    assert len(reader.GetHeader()) <= 255


def test_a_name_with_xml_syntax_stays_the_3mf_title(tmp_path, renzo, hub):
    lib3mf = clients.module("lib3mf", "pip install lib3mf (in the test extra)")
    name = 'a<b>&c"\'</metadata><metadata name="Designer">x'
    path = export_part(named(renzo, name), "hub", tmp_path / "hub.3mf", mesh=hub)
    model = lib3mf.get_wrapper().CreateModel()
    reader = model.QueryReader("3mf")
    reader.SetStrictModeActive(True)
    reader.ReadFromFile(str(path))
    metadata = model.GetMetaDataGroup()
    found = {metadata.GetMetaData(i).GetName(): metadata.GetMetaData(i).GetValue()
             for i in range(metadata.GetMetaDataCount())}
    assert found == {"Title": f"{name}-hub", "Application": "gearcoupling"}


@pytest.mark.parametrize("name", [GCODE_NAME, ESC_NAME, "ü€😀'\\"])
def test_the_step_product_name_is_printable_ascii(tmp_path, name):
    clients.ocp()
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox

    from gearcoupling.export.step import read_step_volume, write_step

    path = write_step(BRepPrimAPI_MakeBox(10.0, 20.0, 30.0).Shape(), tmp_path / "b.step",
                      name=name)
    data = path.read_bytes()
    assert data.isascii() and not re.search(rb"[\x00-\x09\x0b-\x0c\x0e-\x1f\x7f]", data)
    # ISO 10303-21: line breaks are not part of the file's tokens; '' and \\ are escapes
    product = re.search(r"PRODUCT\('((?:[^']|'')*)'", data.decode().replace("\n", ""))
    assert product is not None
    value = product[1].replace("''", "'").replace("\\\\", "\\")
    counted = re.fullmatch(r"(.*) \d+", value)  # OpenCASCADE numbers its products
    assert counted is not None and counted[1] == step_text(name)
    assert read_step_volume(path) == pytest.approx(6000.0, rel=1e-9)


def test_mesh_formats_without_a_title_carry_no_name(tmp_path, renzo, hub):
    """STL, PLY, OBJ and GLB: the name is in no line of the file (GLB: JSON)."""
    for ext in ("stl", "ply", "obj", "glb"):
        data = export_part(named(renzo, GCODE_NAME), "hub", tmp_path / f"h.{ext}",
                           mesh=hub).read_bytes()
        assert b"M30\n" not in data and b"\nG0 X0" not in data, ext


# ---------------------------------------------------------------- CSV


def read_csv(path) -> tuple[list[list[str]], list[str], list[list[str]]]:
    """``(comment records, header, rows)`` as Python's csv module reads the file: the
    records before the header must each be one ``#`` line."""
    with open(path, newline="", encoding="utf-8") as fh:
        records = list(csv.reader(fh))
    k = next(i for i, r in enumerate(records) if not (r and r[0].startswith("#")))
    return records[:k], records[k], records[k + 1:]


def no_formula(records) -> bool:
    return not any(cell[:1] in ("=", "+", "-", "@") for r in records for cell in r)


def test_a_newline_in_a_comment_puts_no_row_before_the_header(tmp_path, renzo):
    """measuring_charts.csv (and every CSV with a ``#`` line naming the spec: hob_path.csv,
    stiffness_matrix.csv write through the same writer)."""
    charts = measuring_charts(named(renzo, ROWS_NAME), points=5)
    path = write_nominal_csv(charts, tmp_path / "measuring_charts.csv")
    comments, header, rows = read_csv(path)
    assert len(comments) == 4 and header[0] == "trace" and len(rows) == 4 * 2 * 5
    assert len(path.read_text().splitlines()) == 4 + 1 + len(rows)
    head = f"hob centre path for {ROWS_NAME}, x,=1+1,-2,\"q"
    path = write_csv_rows(tmp_path / "hob.csv", ["x_mm"], [[1.5], [-2.0]], comments=[head])
    comments, header, rows = read_csv(path)
    assert len(comments) == 1 and header == ["x_mm"] and rows == [["1.5"], ["-2"]]
    assert no_formula(comments) and comments[0][0].startswith("# hob centre path for x")


def test_a_formula_name_is_text_in_capacity_csv(tmp_path, renzo):
    cap = Capacity(named(renzo, FORMULA_NAME), 1.0, "linear", "ccw", 1.0, 1234.5,
                   "tooth_load", {"tooth_load": 1234.5}, None, None, 0.4, 1.1, -1.0e3)
    path = write_capacity_csv({FORMULA_NAME: [cap]}, tmp_path / "capacity.csv")
    comments, header, rows = read_csv(path)
    assert not comments and header[0] == "spec" and len(rows) == 1
    assert rows[0][0] == "'" + FORMULA_NAME and no_formula([rows[0][:1]])
    assert rows[0][-1] == "-1000"  # numbers keep their sign


@pytest.mark.parametrize("cell", ["+1+cmd", "-2-3", "@SUM(A1)", "=1", "\ttab", "\rcr"])
def test_text_cells_are_neither_formulas_nor_line_breaks(tmp_path, cell):
    path = write_csv_columns(tmp_path / "t.csv", ["name", "x"],
                             [[cell, "-1.5"], np.array([1.0, -2.0])])
    _, header, rows = read_csv(path)
    assert header == ["name", "x"] and len(rows) == 2 and len(path.read_text().splitlines()) == 3
    assert rows[0][0][:1] not in ("=", "+", "-", "@", "\t", "\r")
    assert rows[1] == ["-1.5", "-2"]  # a number given as text stays a number


def test_a_text_column_given_as_a_numpy_array_is_text(tmp_path):
    """On main a numpy string cell went to float() and raised deep in the writer."""
    path = write_csv_columns(tmp_path / "t.csv", ["part", "n"],
                             [np.array(["hub", "=sleeve"]), np.array([1, 2])])
    assert read_csv(path)[1:] == (["part", "n"], [["hub", "1"], ["'=sleeve", "2"]])


# ---------------------------------------------------------------- terminal


def test_spec_prints_the_stem_name_as_text(tmp_path, renzo_text, capsys, monkeypatch):
    """``gearcoupling spec`` of a file whose stem holds ESC sequences and rich markup:
    the ESC is shown escaped, the markup as written."""
    monkeypatch.setenv("COLUMNS", "400")  # no table cell wraps
    stem = ESC_NAME + MARKUP_NAME.replace("/", "_")
    path = spec_file(tmp_path, stem, None, renzo_text)
    assert main(["spec", str(path)]) == 0
    out = capsys.readouterr().out
    assert "\x1b" not in out
    assert f"[{escaped(stem)}]" in out  # the heading: markup as written, ESC escaped
    assert r"\x1b[2J\x1b[31mred\x1b[0m[bold red]x[_bold red] [link=file:" in out


def test_the_progress_label_is_not_markup(capsys, monkeypatch):
    from gearcoupling.commands.common import progress

    monkeypatch.setenv("COLUMNS", "400")

    with progress(f"check {MARKUP_NAME} {ESC_NAME}", 1) as update:
        update(1, 1)
    err = capsys.readouterr().err
    assert "[bold red]x[/bold red]" in err and "\x1b[2J" not in err and r"\x1b[2J" in err


# ---------------------------------------------------------------- plots, markdown


@pytest.mark.parametrize("name", [r"x $\frac$ y", "a$b$c", r"a\$b", "l1\nl2"])
def test_a_plot_title_shows_the_name_as_given(tmp_path, renzo, name):
    from matplotlib.cbook import is_math_text

    """``$\\frac$`` made matplotlib raise at drawing, ``a$b$c`` drew ``b`` as math."""
    charts = measuring_charts(named(renzo, name), points=5)
    fig = plot_measuring_charts(charts)
    save_figure(fig, tmp_path / "charts.png")
    title = fig.get_suptitle()
    assert not is_math_text(title)
    assert title.replace(r"\$", "$").startswith(f"{escaped(name)}: ")  # as matplotlib draws


def test_markdown_shows_html_and_markup_as_text():
    from markdown_it import MarkdownIt

    name = '<img src=x onerror="alert(1)"> **b** [l](https://x.org) a@b.c `c` &amp; \\'
    html = MarkdownIt("commonmark").render(f"**{markdown_text(name)}**")
    assert "<img" not in html and "<a " not in html and "<code>" not in html
    assert html.count("<strong>") == 1
    text = re.sub(r"</?(p|strong)>", "", html).strip()
    assert text == name.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;") \
        .replace('"', "&quot;")


# ---------------------------------------------------------------- any name


@settings(max_examples=60, derandomize=True, deadline=None, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(name=st.text(max_size=40))
def test_no_name_changes_the_lines_of_an_output(tmp_path, program, renzo_mm, name):
    """Any unicode name: the G-code's blocks, the INP comment, the VTK header, the CSV
    records, the terminal and plot text keep their lines; a spec file either refuses the
    name (naming ``name``) or keeps it as given."""
    ref = program.gcode()
    text = dataclasses.replace(program, spec_name=name).gcode()
    assert program_words(text) == program_words(ref)
    assert len(text.splitlines()) == len(ref.splitlines()) and text.isascii()
    for line in (inp_comment(name), vtk_header(name), terminal_text(name), plot_text(name),
                 xml_text(name), csv_comment(name), markdown_text(name)):
        assert len(line.splitlines()) <= 1 and line.isprintable()
    assert inp_comment(name).startswith("** ") and len(inp_comment(name)) <= 132
    path = write_csv_rows(tmp_path / "p.csv", ["spec", "x"], [[name, 1.0]], comments=[name])
    comments, header, rows = read_csv(path)
    assert len(comments) == 1 and header == ["spec", "x"] and len(rows) == 1
    assert no_formula(comments)
    if not no_formula(rows):
        float(rows[0][0])  # only a number may start with + or -: anything else raises
    try:
        spec = gc.spec_from_dict(dict(renzo_mm, name=name))
    except gc.SpecError as err:
        assert err.field == "name" and not name.isprintable()
    else:
        assert spec.name == name and name.isprintable()
