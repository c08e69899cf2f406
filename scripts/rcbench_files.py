"""Helpers shared by the study scripts: where ../shared/data is, how the
arguments after `--` reach rcbench, readers of ground-truth (or reference)
pose files and rcbench timeline CSVs, and atomic writers for the merged
results and figures they produce. A malformed file raises InputError with a
message naming the file, and the line where there is one."""
import contextlib
import csv
import math
import os
import tempfile

# ../shared/data beside the project root, wherever the script is run from.
SHARED_DATA = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "data"))

EVIDENCE_COLUMN = "log_mean_likelihood_nats"


def split_extra_args(argv):
    """(the script's own arguments, the arguments after `--`, passed to rcbench unchanged)."""
    if "--" not in argv:
        return argv, []
    cut = argv.index("--")
    return argv[:cut], argv[cut + 1:]


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


# The first line of a timeline whose run has not finished (traces/csv_table.h).
INCOMPLETE_MARKER = "# rcbench: INCOMPLETE"


@contextlib.contextmanager
def atomic_output(path, mode="w", **open_args):
    """Opens a temporary file beside `path` and renames it into place when the
    block ends without an exception, so a killed or failed study never leaves
    a partial result (as rcbench's own AtomicFile). Creates the folder."""
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=os.path.basename(path) + ".tmp")
    try:
        with os.fdopen(fd, mode, **open_args) as f:
            yield f
        umask = os.umask(0)  # mkstemp makes the file private; give it the usual mode
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def save_figure(fig, path, **savefig_args):
    """fig.savefig through atomic_output; the format comes from `path`."""
    fmt = os.path.splitext(path)[1].lstrip(".") or None
    with atomic_output(path, "wb") as f:
        fig.savefig(f, format=fmt, **savefig_args)


def read_timeline_rows(path, columns):
    """The rows of an rcbench timeline CSV as dicts; every name in `columns` must be a column.
    A timeline still marked incomplete (its run was killed or has not finished) is an InputError."""
    try:
        with open(path) as f:
            if f.readline().startswith(INCOMPLETE_MARKER):
                raise InputError(f"{path}: the timeline is marked incomplete (its run was killed or has not finished)")
            f.seek(0)
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise InputError(f"{path}: {e.strerror}") from None
    if not rows:
        raise InputError(f"{path}: empty timeline")
    for column in columns:
        if column not in rows[0]:
            raise InputError(f"{path}: no '{column}' column (has {', '.join(rows[0])})")
    return rows


def read_cumulative_evidence(path):
    """Per timeline record: (running sum of log_mean_likelihood_nats, whether
    the record had a sensor update, est_x_m, est_y_m). The running sum is the
    log marginal likelihood of the scans so far. A sensor update without a
    finite value (rcbench leaves the cell empty only for a value it cannot
    write) makes the sum meaningless and raises InputError."""
    rows = read_timeline_rows(path, ("iteration", "sensor_updated", EVIDENCE_COLUMN, "est_x_m", "est_y_m"))
    out, total = [], 0.0
    for r in rows:
        updated = r["sensor_updated"] == "1"
        if updated:
            value = float(r[EVIDENCE_COLUMN]) if r[EVIDENCE_COLUMN] != "" else math.nan
            if not math.isfinite(value):
                raise InputError(f"{path}: record {r['iteration']}: sensor update without a finite {EVIDENCE_COLUMN}")
            total += value
        out.append((total, updated, float(r["est_x_m"]), float(r["est_y_m"])))
    return out


def write_atomic(path, data):
    """Write data (str: text, bytes: binary) to path through a temporary file
    in the same folder, renamed into place only once it is complete, so a
    failed run leaves no partial file; creates the parent folders."""
    import tempfile
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=".tmp-")
    try:
        with os.fdopen(fd, "wb" if isinstance(data, bytes) else "w") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
