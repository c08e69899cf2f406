# Fixed-step grid march: CastMarch in robocore/ray_cast.h (RoWild / RoboGPU
# DeliBot semantics), one ray per thread. Loop pass k samples the point
# o + k*r*d and fetches the cell under it.
#
# Inputs per ray: o (origin, m), d (unit direction), r (cell size, m),
# inv_r (1/r), t_max (max range, m), ext (map extent, m), free (the free-cell
# code), one, zero.
#
# Departure from the artifact: its per-cell transaction is SUB, RCP, DOT,
# CMP, OR, CMP, OR plus an 8-byte fetch, because its grid stores doubles.
# Our grid stores one byte per cell (CellState), so LOAD fetches 1 byte, and
# the micro-ops below are the ones CastMarch itself performs: a sample point
# computed by formula (never accumulated), an occupancy test, and the
# range/map-border test for the next sample.
#
# Exit contract (robocore/kernel_record.h): RETURN_IF #0 = the cell stops the
# ray (hit), RETURN_IF #1 = the next sample is out of range or off the map.

prologue:
  MUL     n_max, t_max, inv_r      # index of the last sample, floor(max_range / r)
  SUB.2   p, o, zero               # first sample at the origin

loop:
  LOAD    cell, p                  # fetch unit: index = floor(p / r), x-major; 1-byte cell
  PUSH    visited                  # node counter (nodes per ray, for the scheduler)
  CMP.1   blocked, cell, free      # occupied or unknown stops the ray
  RETURN_IF blocked                # #0: hit at t = k*r
  ADD.1   k, k, one                # next sample index
  MUL     t, k, r                  # t = k*r
  MUL.2   td, d, t                 # t*d
  ADD.2   p, o, td                 # next sample point
  CMP.1   done, k, n_max           # past the last sample?
  CMP.2   below, p, zero           # off the map on the low side...
  CMP.2   above, ext, p            # ...or on the high side
  OR.2    outside, below, above
  OR.1    stop, outside.x, outside.y
  OR.1    stop, stop, done
  RETURN_IF stop                   # #1: range exhausted or map border

epilogue:
  MUL     range, k, r              # range = k*r (or max range)
  MIN.1   range, range, t_max
