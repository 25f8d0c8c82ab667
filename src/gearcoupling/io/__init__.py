"""Files in and out: atomic writes, JSON with one rule for non-finite numbers, CSV, TOML
read strictly with file:line errors, CalculiX/Abaqus INP numbers and the bundled
resources (templates, studies)."""

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
from .toml import (
    MAX_NESTING,
    Table,
    array_lengths,
    line_of,
    parse_override,
    parse_toml,
    read_toml,
    set_dotted,
    unknown_key,
)

__all__ = [
    "MAX_NESTING",
    "NonFiniteError",
    "Table",
    "array_lengths",
    "as_path",
    "atomic_path",
    "bundled_dir",
    "bundled_names",
    "default_output_dir",
    "inp_element_lines",
    "inp_id_lines",
    "inp_node_lines",
    "inp_number",
    "line_of",
    "not_a_file",
    "output_folder",
    "parse_override",
    "parse_toml",
    "plain",
    "read_toml",
    "remove_stale_temporaries",
    "require_file",
    "resolve_bundled",
    "safe_name",
    "set_dotted",
    "unknown_key",
    "writable_file",
    "write_csv_columns",
    "write_csv_records",
    "write_csv_rows",
    "write_json",
    "write_text",
]
