#!/usr/bin/python3
"""One self-contained HTML report per study: every figure embedded as a data
URI, the summary tables, the failed points with their errors, the merged
CSV itself (as a download link inside the file), the exact configuration,
the git commit and the machines. Nothing is fetched when it is opened.

Figures and tables come from two places: the study's analysis scripts
(<out>/analysis/: *.png figures, *.csv tables, *.md notes, in name order)
and report_figures.py (what any study's points can show by themselves).

The generic figures are also written as PNG files into <out>/report_figures/,
with overview.png tiling them all.

A small script in the page counts the images the browser decoded and writes
the count into the page (<body data-images-decoded="N/M">), so a headless
browser can check it (tests/workflow/report_browser_test.py).

Run by the Snakefile as: report.py OUT/study_config.json
"""
import base64
import datetime
import html
import json
import os
import platform
import socket
import subprocess
import sys

import pandas as pd

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import merge  # noqa: E402
import report_figures  # noqa: E402
from study_config import load_snapshot  # noqa: E402

RECORD_COLUMNS = set(merge.RECORD_COLUMNS)
MAX_TABLE_ROWS = 400

STYLE = """
body { font-family: sans-serif; margin: 2em auto; max-width: 1200px; color: #222; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; padding-bottom: .2em; margin-top: 2em; }
table { border-collapse: collapse; font-size: 12px; margin: .5em 0 1.5em; }
th, td { border: 1px solid #ccc; padding: 2px 6px; text-align: right; }
th { background: #f0f0f0; } td.l, th.l { text-align: left; }
figure { margin: 1em 0 2em; } figure img { max-width: 100%; border: 1px solid #ddd; }
figcaption { font-size: 13px; color: #444; max-width: 900px; }
pre { background: #f7f7f7; padding: .7em; overflow-x: auto; font-size: 12px; }
.failed { color: #b00; } .ok { color: #070; }
.scroll { overflow-x: auto; }
"""

DECODE_CHECK = """
<script>
window.addEventListener('load', function () {
  var imgs = document.getElementsByTagName('img'), ok = 0;
  for (var i = 0; i < imgs.length; i++) if (imgs[i].complete && imgs[i].naturalWidth > 0) ok++;
  document.body.setAttribute('data-images-decoded', ok + '/' + imgs.length);
});
</script>
"""


def esc(x):
    return html.escape(str(x))


def run(cmd):
    try:
        return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                              timeout=30).stdout.strip()
    except (OSError, subprocess.TimeoutExpired):
        return ""


def git_commit():
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    commit = run(["git", "-C", repo, "rev-parse", "HEAD"])
    if not commit:
        return "unknown (not a git checkout)"
    dirty = run(["git", "-C", repo, "status", "--porcelain", "--untracked-files=no"])
    subject = run(["git", "-C", repo, "log", "-1", "--format=%s"])
    return f"{commit}{' with uncommitted changes' if dirty else ''} ({subject})"


def machine():
    cpu = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")), cpu)
    except OSError:
        pass
    mem = ""
    try:
        with open("/proc/meminfo") as f:
            kb = int(next(line.split()[1] for line in f if line.startswith("MemTotal")))
            mem = f"{kb / 2**20:.1f} GiB"
    except (OSError, StopIteration, ValueError):
        pass
    os_name = run(["sh", "-c", ". /etc/os-release; echo $PRETTY_NAME"])
    return {"host": socket.gethostname(), "cpu": cpu, "logical cores": os.cpu_count(), "memory": mem,
            "os": f"{platform.system()} {platform.release()} ({os_name})",
            "python": platform.python_version(), "pandas": pd.__version__,
            "snakemake": run([sys.executable, "-c", "import snakemake; print(snakemake.__version__)"])}


def data_uri(data, mime):
    return f"data:{mime};base64,{base64.b64encode(data).decode()}"


def figure_html(title, caption, png):
    if png is None:
        return f"<h3>{esc(title)}</h3><p class='failed'>{esc(caption)}</p>"
    return (f"<figure><h3>{esc(title)}</h3><img alt='{esc(title)}' src='{data_uri(png, 'image/png')}'>"
            f"<figcaption>{esc(caption)}</figcaption></figure>")


def table_html(frame, max_rows=MAX_TABLE_ROWS):
    shown = frame.head(max_rows)
    head = "".join(f"<th class='l'>{esc(c)}</th>" for c in shown.columns)
    body = []
    for _, r in shown.iterrows():
        cells = []
        for c in shown.columns:
            v = r[c]
            if isinstance(v, float):
                text = "" if pd.isna(v) else f"{v:.6g}"
                cells.append(f"<td>{text}</td>")
            else:
                cls = " class='l failed'" if c == "status" and v != "ok" else " class='l'"
                cells.append(f"<td{cls}>{esc('' if pd.isna(v) else v)}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    more = (f"<p>The first {max_rows} of {len(frame)} rows; the merged CSV has all.</p>"
            if len(frame) > max_rows else "")
    return f"<div class='scroll'><table><tr>{head}</tr>{''.join(body)}</table></div>{more}"


def overview(table):
    """One table per group: labels, the parameters that vary in it, status, wall time, key metrics."""
    import point_metrics
    parts = []
    for group, rows in table.groupby("group", sort=False):
        varying = [c for c in rows.columns if c not in RECORD_COLUMNS and "." not in c
                   and rows[c].astype(str).nunique() > 1]
        metrics = [c for c in point_metrics.KEY_METRICS if c in rows.columns and rows[c].notna().any()]
        cols = ["point"] + varying + ["status", "wall_s"] + metrics
        parts.append(f"<h3>Group {esc(group)} ({len(rows)} points, {rows['workload'].iloc[0]})</h3>"
                     + table_html(rows[list(dict.fromkeys(cols))]))
    return "\n".join(parts)


def analysis_sections(analysis_dir):
    parts = []
    try:
        with open(os.path.join(analysis_dir, "analysis.json")) as f:
            scripts = json.load(f)["scripts"]
    except (OSError, ValueError):
        scripts = []
    for s in scripts:
        status = "ok" if s["exit_code"] == 0 else f"failed (exit {s['exit_code']})"
        parts.append(f"<h3>{esc(s['script'])}: <span class='{'ok' if s['exit_code'] == 0 else 'failed'}'>"
                     f"{esc(status)}</span></h3>")
        if s["exit_code"] != 0:
            parts.append(f"<pre>{esc(s['stderr'][-4000:])}</pre>")
        for name in sorted(s["files"]):
            path = os.path.join(analysis_dir, name)
            if name.endswith(".png"):
                with open(path, "rb") as f:
                    caption_path = path[:-4] + ".caption"
                    caption = open(caption_path).read().strip() if os.path.exists(caption_path) else name
                    parts.append(figure_html(name, caption, f.read()))
            elif name.endswith(".csv"):
                parts.append(f"<h4>{esc(name)}</h4>" + table_html(pd.read_csv(path)))
            elif name.endswith((".md", ".txt")):
                with open(path) as f:
                    parts.append(f"<h4>{esc(name)}</h4><pre>{esc(f.read())}</pre>")
    return "\n".join(parts)


def provenance(table):
    rows = [("git commit of the study scripts", git_commit()),
            ("report written", datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"))]
    rows += [(f"report machine: {k}", v) for k, v in machine().items()]
    hosts = table["host"].value_counts()
    rows.append(("points ran on", ", ".join(f"{h} ({n})" for h, n in hosts.items())))
    binaries = table["rcbench_sha256"].value_counts()
    rows.append(("rcbench binaries (SHA-256)", ", ".join(f"{b[:16]}... ({n} points)" for b, n in binaries.items())
                 + (" - MORE THAN ONE: the points ran different builds" if len(binaries) > 1 else "")))
    if "started_utc" in table.columns and table["started_utc"].notna().any():
        rows.append(("points started", f"{table['started_utc'].min()} to {table['started_utc'].max()}"))
    rows.append(("sum of point wall times", f"{table['wall_s'].sum():.1f} s"))
    return "<table>" + "".join(f"<tr><th class='l'>{esc(k)}</th><td class='l'>{esc(v)}</td></tr>"
                               for k, v in rows) + "</table>"


def save_figures(figures, folder, tile_height=420, columns=3):
    """The generic figures as PNG files too (<out>/report_figures/NN_title.png), and all of
    them tiled into overview.png, for documents."""
    import io
    from PIL import Image
    os.makedirs(folder, exist_ok=True)
    for name in os.listdir(folder):
        os.remove(os.path.join(folder, name))
    tiles = []
    for k, (title, _, png) in enumerate(figures):
        if png is None:
            continue
        slug = "".join(c if c.isalnum() else "_" for c in title.lower()).strip("_")[:60]
        with open(os.path.join(folder, f"{k + 1:02d}_{slug}.png"), "wb") as f:
            f.write(png)
        image = Image.open(io.BytesIO(png)).convert("RGB")
        tiles.append(image.resize((max(1, round(image.width * tile_height / image.height)), tile_height)))
    if tiles:
        rows = [tiles[i:i + columns] for i in range(0, len(tiles), columns)]
        width = max(sum(t.width for t in row) for row in rows)
        sheet = Image.new("RGB", (width, tile_height * len(rows)), "white")
        for r, row in enumerate(rows):
            x = 0
            for t in row:
                sheet.paste(t, (x, r * tile_height))
                x += t.width
        sheet.save(os.path.join(folder, "overview.png"), optimize=True)


def write_report(study, merged_csv, analysis_dir, out_html, snapshot):
    table = pd.read_csv(merged_csv)
    n_ok = int((table["status"] == "ok").sum())
    failed = table[table["status"] != "ok"]
    with open(merged_csv, "rb") as f:
        csv_link = (f"<a download='{esc(os.path.basename(merged_csv))}' href='{data_uri(f.read(), 'text/csv')}'>"
                    f"{esc(os.path.basename(merged_csv))}</a>")
    parts = [f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>Study {esc(study.name)}</title>"
             f"<style>{STYLE}</style></head><body>",
             f"<h1>Study {esc(study.name)}</h1>",
             f"<p>{esc(study.config.get('description', ''))}</p>",
             f"<p><b>{len(table)} points</b>: <span class='ok'>{n_ok} ok</span>"
             + (f", <span class='failed'>{len(failed)} failed</span>" if len(failed) else "")
             + f". Merged table: {csv_link} ({len(table.columns)} columns, embedded in this file).</p>",
             "<h2>Provenance</h2>", provenance(table)]
    if len(failed):
        parts += ["<h2 class='failed'>Failed points</h2>",
                  table_html(failed[["point", "group", "exit_code", "error", "folder"]])]
    parts += ["<h2>Analysis</h2>", analysis_sections(analysis_dir) or "<p>No analysis scripts.</p>"]
    figures = report_figures.all_figures(table)
    save_figures(figures, os.path.join(study.out, "report_figures"))
    parts += ["<h2>Figures from the points' own outputs</h2>"]
    parts += [figure_html(*f) for f in figures] or ["<p>None of this study's points wrote such outputs.</p>"]
    parts += ["<h2>Points</h2>", "<p>Per group: labels, the parameters that vary, and the key metrics; the merged "
              "CSV has every parameter and metric.</p>", overview(table)]
    parts.append("<h2>Configuration</h2>")
    for path, text in snapshot["config_files"].items():
        parts.append(f"<h3>{esc(path)}</h3><pre>{esc(text)}</pre>")
    import yaml
    parts.append("<h3>Effective configuration (the files and the command line's --config overrides)</h3>"
                 f"<pre>{esc(yaml.safe_dump(snapshot['config'], sort_keys=False))}</pre>")
    parts.append(DECODE_CHECK + "</body></html>\n")
    tmp = f"{out_html}.tmp-{os.getpid()}"
    with open(tmp, "w") as f:
        f.write("\n".join(parts))
    os.replace(tmp, out_html)
    print(f"wrote {out_html} ({len(figures)} generic figure(s))", file=sys.stderr)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: report.py OUT/study_config.json   (the Snakefile writes it)")
    study, snapshot = load_snapshot(sys.argv[1])
    write_report(study, study.merged_csv(), os.path.join(study.out, "analysis"),
                 os.path.join(study.out, "report.html"), snapshot)


if __name__ == "__main__":
    main()
