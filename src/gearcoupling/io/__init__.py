"""Files in and out: atomic writes, JSON with one rule for non-finite numbers, CSV, TOML
read strictly with file:line errors, CalculiX/Abaqus INP numbers, the bundled
resources (templates, studies), and text from a spec made safe for each target."""

from .atomic import (
    atomic_path,
    default_output_dir,
    remove_stale_temporaries,
    safe_name,
    write_text,
)
from .csv import write_csv_columns, write_csv_records, write_csv_rows
from .files import as_path, not_a_file, output_folder, require_file, writable_file
from .inp import inp_element_lines, inp_id_lines, inp_node_lines, inp_number
from .json import NonFiniteError, plain, write_json
from .resources import bundled_dir, bundled_names, resolve_bundled
from .text import (
    csv_cell,
    csv_comment,
    escaped,
    gcode_comment,
    inp_comment,
    markdown_text,
    plot_text,
    step_text,
    terminal_text,
    vtk_header,
    xml_text,
)
from .toml import Table, line_of, parse_override, read_toml, set_dotted, unknown_key

__all__ = [
    "NonFiniteError",
    "Table",
    "as_path",
    "atomic_path",
    "bundled_dir",
    "bundled_names",
    "csv_cell",
    "csv_comment",
    "default_output_dir",
    "escaped",
    "gcode_comment",
    "inp_comment",
    "inp_element_lines",
    "inp_id_lines",
    "inp_node_lines",
    "inp_number",
    "line_of",
    "markdown_text",
    "not_a_file",
    "output_folder",
    "parse_override",
    "plain",
    "plot_text",
    "read_toml",
    "remove_stale_temporaries",
    "require_file",
    "resolve_bundled",
    "safe_name",
    "set_dotted",
    "step_text",
    "terminal_text",
    "unknown_key",
    "vtk_header",
    "writable_file",
    "write_csv_columns",
    "write_csv_records",
    "write_csv_rows",
    "write_json",
    "write_text",
    "xml_text",
]
