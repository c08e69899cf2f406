"""Readers shared by the study scripts: ground-truth (or reference) pose
files and rcbench timeline CSVs. A malformed file raises InputError with a
message naming the file, and the line where there is one."""
import csv


class InputError(Exception):
    pass


def read_poses(path):
    """[[t_s, x_m, y_m, theta_rad], ...] from a ground-truth file ('#' lines are comments)."""
    rows = []
    try:
        with open(path) as f:
            for line_no, line in enumerate(f, 1):
                fields = line.split()
                if not fields or fields[0].startswith("#"):
                    continue
                if len(fields) != 4:
                    raise InputError(f"{path}:{line_no}: {len(fields)} fields, expected 4 (t_s x_m y_m theta_rad)")
                try:
                    rows.append([float(v) for v in fields])
                except ValueError:
                    raise InputError(f"{path}:{line_no}: a field is not a number") from None
    except OSError as e:
        raise InputError(f"{path}: {e.strerror}") from None
    if not rows:
        raise InputError(f"{path}: no poses")
    return rows


def read_timeline_rows(path, columns):
    """The rows of an rcbench timeline CSV as dicts; every name in `columns` must be a column."""
    try:
        with open(path) as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise InputError(f"{path}: {e.strerror}") from None
    if not rows:
        raise InputError(f"{path}: empty timeline")
    for column in columns:
        if column not in rows[0]:
            raise InputError(f"{path}: no '{column}' column (has {', '.join(rows[0])})")
    return rows
