"""Column names for rcbench options, with the unit each option's --help states.

The units come from rcbench itself (`rcbench <workload> --help`; the test
cli_help_units makes every numeric option state one), so a parameter column
carries the same unit as the option: --initial-sigma-xy -> initial_sigma_xy_m,
--hypothesis-window -> hypothesis_window_nats. Counts, ratios, indices and
options without a number (files, names) keep the bare name.
"""
import re
import subprocess

# The unit in parentheses, as tests/cli/help_units.sh accepts it, and the
# suffix it gives a column ("" = dimensionless: no suffix).
UNIT_SUFFIX = {
    "m": "m", "s": "s", "rad": "rad", "J": "j", "m/s": "m_per_s", "rad/s": "rad_per_s", "1/m": "per_m",
    "rad/m": "rad_per_m", "deg": "deg", "Hz": "hz", "nats": "nats", "cells": "cells", "core cycles": "cycles",
    "cycles": "cycles", "nodes per ray": "nodes_per_ray", "nodes per query": "nodes_per_query",
    "tree nodes per kernel query": "nodes_per_query", "m, m, rad": "x_m_y_m_theta_rad", "1/sensor update": "per_update",
    "updates": "updates",
    "count": "", "count N": "", "unitless": "", "unitless fraction": "", "fraction": "", "probability": "",
    "index": "", "index k": "", "record index": "", "rad^2/rad^2": "", "rad^2/m^2": "", "m^2/m^2": "",
    "m^2/rad^2": "",
}
UNIT_RE = re.compile(r"\((" + "|".join(re.escape(u) for u in sorted(UNIT_SUFFIX, key=len, reverse=True))
                     + r")[;,): ]")
OPTION_RE = re.compile(r"^\s+(?:-\w,)?(--[A-Za-z0-9-]+(?:,--[A-Za-z0-9-]+)*)(.*)$")


def parse_help(text):
    """{option name without dashes: unit suffix} from one subcommand's --help."""
    lines, current = [], ""
    for line in text.splitlines():
        if re.match(r"^\s{1,8}-", line):
            if current:
                lines.append(current)
            current = line
        elif re.match(r"^\s{20,}\S", line) and current:
            current += " " + line.strip()
        else:
            if current:
                lines.append(current)
            current = ""
    if current:
        lines.append(current)
    units = {}
    for line in lines:
        m = OPTION_RE.match(line)
        if not m:
            continue
        names = [n[2:] for n in m.group(1).split(",")]
        rest = m.group(2)
        unit = UNIT_RE.search(rest + " ")
        suffix = UNIT_SUFFIX[unit.group(1)] if unit and re.search(r"\b(INT|UINT|FLOAT)\b", rest) else ""
        for n in names:
            units[n] = suffix
    return units


class OptionUnits:
    """Column names of one rcbench binary's options (help read once per workload)."""

    def __init__(self, rcbench):
        self.rcbench = rcbench
        self.cache = {}

    def units(self, workload):
        if workload not in self.cache:
            try:
                text = subprocess.run([self.rcbench, workload, "--help"], stdout=subprocess.PIPE,
                                      stderr=subprocess.DEVNULL, text=True, timeout=60).stdout
            except (OSError, subprocess.TimeoutExpired):
                text = ""
            self.cache[workload] = parse_help(text)
        return self.cache[workload]

    def column(self, workload, option):
        base = option.replace("-", "_")
        suffix = self.units(workload).get(option, "")
        if not suffix or base.endswith("_" + suffix):
            return base
        return f"{base}_{suffix}"
