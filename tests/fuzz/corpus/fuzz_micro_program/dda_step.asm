# Exact grid traversal (Amanatides & Woo): CastDda in robocore/ray_cast.h,
# one ray per thread. Loop pass = one cell the ray crosses.
#
# Inputs per ray: o (origin, m), d (unit direction), r (cell size, m),
# inv_r (1/r), t_max (max range, m), size (map size, cells), free, zero.
# Cell boundaries are computed from the origin by formula each pass, as in
# the C++ kernel, so dda and rm agree exactly.
#
# Exit contract (robocore/kernel_record.h): RETURN_IF #0 = the cell stops the
# ray (hit), RETURN_IF #1 = the next cell is out of range or off the map.

prologue:
  RCP.2   inv_d, d                 # 1/d per axis (the boundary-time divisor)
  CMP.2   up, d, zero              # per axis: stepping up? (also the far-face offset)
  MUL.2   oc, o, inv_r             # origin in cell units
  ADD.2   c, oc, zero              # starting cell = floor(o / r) (the fetch unit floors)

loop:
  LOAD    cell, c                  # 1-byte cell at index c.x * size_y + c.y
  PUSH    visited                  # node counter
  CMP.1   blocked, cell, free
  RETURN_IF blocked                # #0: hit at t_enter
  ADD.2   b, c, up                 # index of the boundary the ray leaves through
  MUL.2   bm, b, r                 # boundary position (m)
  SUB.2   rel, bm, o
  MUL.2   tb, rel, inv_d           # boundary times (tx, ty)
  CMP.1   x_first, tb.x, tb.y      # tx <= ty steps x (ties step x, as CastDda)
  MIN.1   t_enter, tb.x, tb.y      # entry time of the next cell
  AND.2   move, x_first, up        # the axis that steps, with its sign
  ADD.2   c, c, move               # next cell
  CMP.1   far, t_max, t_enter      # out of range?
  CMP.2   below, c, zero           # off the map?
  CMP.2   above, size, c
  OR.2    outside, below, above
  OR.1    stop, outside.x, outside.y
  OR.1    stop, stop, far
  RETURN_IF stop                   # #1: range exhausted or map border

epilogue:
  MIN.1   range, t_enter, t_max
