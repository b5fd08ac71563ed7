"""Reading the output files a gradem command wrote: CSV (with an optional '# ...' banner line at
the top, as `gradem lab` writes on representative data) and JSON. Every problem is an InputError
naming the file, the line where there is one, and what was expected."""

import csv
import json
import math
import os


class InputError(Exception):
    """A result file is missing or not what the generator expects."""


def require(folder, name, written_by):
    """Path of `name` in `folder`; InputError naming the command that writes it when missing."""
    path = os.path.join(folder, name)
    if not os.path.isfile(path):
        raise InputError(f"{path}: no such file (written by {written_by}); expected the output folder of that command")
    return path


def read_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except json.JSONDecodeError as e:
        raise InputError(f"{path}:{e.lineno}: not valid JSON: {e.msg}") from None
    except OSError as e:
        raise InputError(f"{path}: cannot read: {e.strerror}") from None


def read_csv(path, required_columns):
    """Rows of a CSV file as dicts of strings, and the banner lines ('# ...') before its header.
    Each row carries its line number under the key '_line'."""
    try:
        with open(path, encoding="utf-8", newline="") as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise InputError(f"{path}: cannot read: {e.strerror}") from None
    banner = []
    first = 0
    while first < len(lines) and lines[first].startswith("#"):
        banner.append(lines[first].lstrip("# ").strip())
        first += 1
    if first >= len(lines):
        raise InputError(f"{path}: empty; expected a header line with {', '.join(required_columns)}")
    reader = csv.DictReader(lines[first:])
    missing = [c for c in required_columns if c not in (reader.fieldnames or [])]
    if missing:
        raise InputError(f"{path}:{first + 1}: header lacks column(s) {', '.join(missing)}")
    rows = []
    for k, row in enumerate(reader):
        row["_line"] = first + 2 + k
        rows.append(row)
    return rows, banner


def number(row, key, path):
    """The float in column `key` of `row` (NaN when empty); InputError naming file:line otherwise."""
    text = (row.get(key) or "").strip()
    if text == "":
        return math.nan
    try:
        return float(text)
    except ValueError:
        raise InputError(f"{path}:{row['_line']}: column {key} = '{text}': expected a number") from None


def field(obj, key, path, kind=None):
    """obj[key] of a JSON object; InputError naming the file and key when absent (or of the wrong
    JSON type when `kind` is given)."""
    if not isinstance(obj, dict) or key not in obj:
        raise InputError(f"{path}: missing key '{key}'")
    value = obj[key]
    if kind is not None and not isinstance(value, kind):
        raise InputError(f"{path}: key '{key}' has the wrong type ({type(value).__name__})")
    return value


def finite(value):
    """A JSON number as float; None/null -> NaN."""
    if value is None:
        return math.nan
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan
