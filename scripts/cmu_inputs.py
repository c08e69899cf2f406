"""Readers of the CMU Wean Hall inputs for the Python study scripts: the
.dat occupancy map and the robotdata .log laser records, with the same
conventions as rcbench's C++ readers (maps/cmu_map_loader.h,
traces/cmu_log_reader.h).

Map: CMU .dat, values are P(free) (see ../shared/data/README.md); a cell is
occupied if its value is in [0, OCCUPIED_MAX_P_FREE]; -1 is unknown. Frame:
x = first index (line of the data block), y = second index, origin at the
outer corner of cell (0, 0), metres.
Log: L records `L x y theta xl yl thetal r1..r180 ts` (cm, rad, s); O
records `O x y theta ts` are checked and skipped. The laser sits
LASER_FORWARD_M ahead of the robot centre, beam i at -pi/2 + i*pi/180;
ranges >= NO_RETURN_M are SICK no-return codes.

A malformed file raises rcbench_files.InputError with the message
"<file>:<line>: field '<field>': <what is wrong>" (line 0: the whole file).
"""
import math

import numpy as np

from rcbench_files import InputError

OCCUPIED_MAX_P_FREE = 0.35  # a cell is occupied if 0 <= value <= this
NO_RETURN_M = 81.83         # SICK status codes start at 8183 cm
LASER_FORWARD_M = 0.25      # instruct.txt; the logs' xl/yl agree
BEAMS = 180


def input_error(path, line, field, message):
    """An InputError naming the file, the 1-based line (0 = the whole file) and the field."""
    return InputError(f"{path}:{line}: field '{field}': {message}")


def parse_float(path, line_no, field, text):
    try:
        v = float(text)
    except ValueError:
        raise input_error(path, line_no, field, f"'{text}' is not a number") from None
    if not math.isfinite(v):
        raise input_error(path, line_no, field, f"'{text}' is not finite")
    return v


def read_cmu_map(path):
    """Returns (occupied bool [nx, ny], resolution_m)."""
    resolution_m, size, rows = None, None, []
    try:
        f = open(path)
    except OSError as e:
        raise input_error(path, 0, "", f"cannot open map: {e.strerror}") from None
    with f:
        for line_no, line in enumerate(f, 1):
            text = line.strip()
            if not text:
                continue
            if text.startswith("robot_specifications->"):
                key, *value = text.split()
                if key.endswith("->resolution"):
                    if len(value) != 1:
                        raise input_error(path, line_no, "resolution", "expected one value (cm)")
                    resolution_m = parse_float(path, line_no, "resolution", value[0]) / 100.0
                    if resolution_m <= 0:
                        raise input_error(path, line_no, "resolution", "must be positive")
                continue
            if text.startswith("global_map"):
                parts = text.split()
                if len(parts) != 3:
                    raise input_error(path, line_no, "global_map", "expected 'global_map[0]: SIZE_X SIZE_Y'")
                size = (int(parse_float(path, line_no, "size_x", parts[1])),
                        int(parse_float(path, line_no, "size_y", parts[2])))
                if size[0] <= 0 or size[1] <= 0:
                    raise input_error(path, line_no, "global_map", "sizes must be positive")
                continue
            if size is None:
                raise input_error(path, line_no, "global_map", "map data before the 'global_map[0]:' line")
            fields = text.split()
            if len(fields) != size[1]:
                raise input_error(path, line_no, f"cell {len(fields) + 1}" if len(fields) < size[1] else
                                  f"cell {size[1] + 1}", f"{len(fields)} values, expected {size[1]}")
            try:
                row = np.array(fields, dtype=float)
            except ValueError:
                row = np.array([parse_float(path, line_no, f"cell {i + 1}", v) for i, v in enumerate(fields)])
            bad = ~np.isfinite(row) | ~(((row >= 0) & (row <= 1)) | (row == -1))
            if bad.any():
                i = int(np.argmax(bad))
                raise input_error(path, line_no, f"cell {i + 1}",
                                  f"'{fields[i]}' is neither a probability in [0, 1] nor -1 (unknown)")
            rows.append(row)
    if size is None:
        raise input_error(path, 0, "global_map", "no 'global_map[0]: SIZE_X SIZE_Y' line")
    if len(rows) != size[0]:
        raise input_error(path, 0, "global_map", f"{len(rows)} data lines, expected {size[0]}")
    if resolution_m is None:
        raise input_error(path, 0, "resolution", "no 'robot_specifications->resolution' line")
    values = np.vstack(rows)
    return (values >= 0) & (values <= OCCUPIED_MAX_P_FREE), resolution_m


class Log:
    def __init__(self, path, odometry, ranges, times):
        self.path, self.odometry, self.ranges, self.times = path, odometry, ranges, times


def read_cmu_log(path):
    """L records -> Log: odometry [n, 3] (m, m, rad), ranges [n, 180] (m, nan = no return), times [n] (s)."""
    odometry, ranges, times = [], [], []
    try:
        f = open(path)
    except OSError as e:
        raise input_error(path, 0, "", f"cannot open log: {e.strerror}") from None
    names = ["record type", "x", "y", "theta", "xl", "yl", "thetal"] + \
        [f"r{i + 1}" for i in range(BEAMS)] + ["ts"]
    with f:
        for line_no, line in enumerate(f, 1):
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "O":
                if len(fields) != 5:
                    raise input_error(path, line_no, "record type",
                                      f"O record with {len(fields)} fields, expected 5 (O x y theta ts)")
                for i, name in enumerate(["x", "y", "theta", "ts"]):
                    parse_float(path, line_no, name, fields[i + 1])
                continue
            if fields[0] != "L":
                raise input_error(path, line_no, "record type", f"'{fields[0]}' is neither O nor L")
            if len(fields) != len(names):
                raise input_error(path, line_no, "record type",
                                  f"L record with {len(fields)} fields, expected {len(names)} "
                                  f"(L x y theta xl yl thetal r1..r180 ts)")
            values = [parse_float(path, line_no, names[i], fields[i]) for i in range(1, len(fields))]
            r = np.array(values[6:6 + BEAMS]) / 100.0
            if (r < 0).any():
                i = int(np.argmax(r < 0))
                raise input_error(path, line_no, f"r{i + 1}", "negative range")
            r[r >= NO_RETURN_M] = np.nan
            if times and values[-1] < times[-1]:
                raise input_error(path, line_no, "ts", f"time {values[-1]} s goes back (previous L record {times[-1]} s)")
            odometry.append((values[0] / 100.0, values[1] / 100.0, values[2]))
            ranges.append(r)
            times.append(values[-1])
    if not odometry:
        raise input_error(path, 0, "L records", "the log has no laser records")
    return Log(path, np.array(odometry), np.vstack(ranges), np.array(times))


def beam_endpoints(pose, ranges, max_range_m):
    """Map points (n, 2) of the beams of one scan taken at robot pose (x, y, theta), ranges in m
    (nan = no return); beams beyond max_range_m are dropped."""
    angles = -np.pi / 2 + np.arange(BEAMS) * np.pi / 180
    x, y, th = pose
    ok = np.isfinite(ranges) & (ranges <= max_range_m)
    sx, sy = x + LASER_FORWARD_M * math.cos(th), y + LASER_FORWARD_M * math.sin(th)
    return np.column_stack([sx + ranges[ok] * np.cos(th + angles[ok]), sy + ranges[ok] * np.sin(th + angles[ok])])
