# Exact ray marching on the distance field: CastRayMarching in
# robocore/ray_cast.h, one ray per thread. Loop pass = one distance-field
# fetch (4-byte float).
#
# Inputs per ray: as dda_step.asm, plus one and margin = (sqrt(2) + 1/2) * r.
# A datapath program has no branches: each pass computes both the safe jump
# and the single exact step, and selects one (as predicated code would).
#
# Exit contract (robocore/kernel_record.h): RETURN_IF #0 = the distance is 0,
# the cell stops the ray (hit); RETURN_IF #1 = out of range or off the map.

prologue:
  RCP.2   inv_d, d
  CMP.2   up, d, zero              # per axis: stepping up? (the exit-face offset)
  SUB.2   down, one, up            # the entry-face offset
  MUL.2   oc, o, inv_r
  ADD.2   c, oc, zero              # starting cell (the fetch unit floors)

loop:
  LOAD    dist, c                  # 4-byte distance to the nearest stopping cell
  PUSH    visited                  # node counter
  CMP.1   blocked, dist, zero      # distance 0: the cell itself stops the ray
  RETURN_IF blocked                # #0: hit at t_enter
  # single exact step, as in dda_step.asm
  ADD.2   b, c, up
  MUL.2   bm, b, r
  SUB.2   rel, bm, o
  MUL.2   tb, rel, inv_d
  CMP.1   x_first, tb.x, tb.y
  MIN.1   t_exit, tb.x, tb.y
  AND.2   move, x_first, up
  ADD.2   c_step, c, move
  # safe jump: from the entry point by dist - margin, accepted only if the
  # landing cell's interior is crossed after t_enter
  SUB.1   jump, dist, margin
  CMP.1   can_jump, jump, r
  ADD.1   t_land, t_enter, jump
  MUL.2   dl, d, t_land
  ADD.2   pl, o, dl
  MUL.2   c_land, pl, inv_r        # landing cell (the fetch unit floors)
  ADD.2   lo, c_land, down         # entry face of the landing cell
  MUL.2   lom, lo, r
  SUB.2   lrel, lom, o
  MUL.2   tl, lrel, inv_d
  MAX.1   t_in, tl.x, tl.y
  ADD.2   hi, c_land, up           # exit face
  MUL.2   him, hi, r
  SUB.2   hrel, him, o
  MUL.2   th, hrel, inv_d
  MIN.1   t_out, th.x, th.y
  CMP.1   inside, t_in, t_out
  CMP.1   ahead, t_enter, t_in
  AND.1   accept, inside, ahead
  AND.1   accept, accept, can_jump
  # select the jump or the step, then test range and border
  AND.2   c, accept, c_land
  OR.2    c, c, c_step
  AND.1   t_enter, accept, t_in
  OR.1    t_enter, t_enter, t_exit
  CMP.1   far, t_max, t_enter
  CMP.2   below, c, zero
  CMP.2   above, size, c
  OR.2    outside, below, above
  OR.1    stop, outside.x, outside.y
  OR.1    stop, stop, far
  RETURN_IF stop                   # #1: range exhausted or map border

epilogue:
  MIN.1   range, t_enter, t_max
