"""What every analysis script shares: its arguments (MERGED_CSV OUT_DIR), the
merged table, and atomic writers for its figures (PNG + a .caption file the
report shows under it) and tables (CSV, and Markdown for docs/)."""
import os
import sys

import pandas as pd


def arguments(usage):
    """(merged CSV path, output folder) from argv; exits with `usage` otherwise
    (status 0 for -h / --help, 2 for wrong arguments)."""
    if len(sys.argv) == 2 and sys.argv[1] in ("-h", "--help"):
        print(f"usage: {os.path.basename(sys.argv[0])} MERGED_CSV OUT_DIR\n{usage}")
        sys.exit(0)
    if len(sys.argv) != 3 or sys.argv[1].startswith("-"):
        print(f"usage: {os.path.basename(sys.argv[0])} MERGED_CSV OUT_DIR\n{usage}", file=sys.stderr)
        sys.exit(2)
    os.makedirs(sys.argv[2], exist_ok=True)
    return sys.argv[1], sys.argv[2]


def load(merged_csv):
    """(every point, the points that succeeded) of a merged study table."""
    table = pd.read_csv(merged_csv)
    for column in ("point", "status", "folder"):
        if column not in table.columns:
            sys.exit(f"{merged_csv}: no '{column}' column (is it a study's merged CSV?)")
    return table, table[table["status"] == "ok"].copy()


def require_columns(table, merged_csv, columns, study):
    """Exits naming the first of `columns` the merged table lacks: then it is
    not `study`'s table."""
    for column in columns:
        if column not in table.columns:
            sys.exit(f"{merged_csv}: no '{column}' column: not {study}'s table")


def _atomic(path, write):
    tmp = f"{path}.tmp-{os.getpid()}"
    write(tmp)
    os.replace(tmp, path)


def _write_text(path, text):
    with open(path, "w") as f:
        f.write(text)


def save_figure(fig, out_dir, name, caption, dpi=110):
    path = os.path.join(out_dir, name)
    _atomic(path, lambda tmp: fig.savefig(tmp, dpi=dpi, format="png"))
    _atomic(path[:-4] + ".caption", lambda tmp: _write_text(tmp, caption + "\n"))
    return path


def save_table(frame, out_dir, name):
    path = os.path.join(out_dir, name)
    _atomic(path, lambda tmp: frame.to_csv(tmp, index=False))
    return path


def save_text(text, out_dir, name):
    path = os.path.join(out_dir, name)
    _atomic(path, lambda tmp: _write_text(tmp, text))
    return path


def cpu_name():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"
