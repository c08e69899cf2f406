# The RoboGPU artifact's DeliBot grid march, as a cost description of the
# same work CastMarch does (robocore/ray_cast.h): one ray per thread, a loop
# pass per cell fetched. Used by the artifact preset
# (backends/presets/artifact.json, "kernel": {"march_program": "artifact"};
# docs/artifact_preset.md cites the artifact's files and lines).
#
# What is the artifact's: the seven micro-ops of its per-cell transaction,
# in its order (vulkan_ray_tracing.cc, set_op_sequence, func_type 1,
# node_processing_configuration 10): a vector SUB that steps distance and
# position, an RCP and a DOT that turn the position into the cell index
# (x * size_y + y), then CMP, OR, CMP, OR for the range and map-border test;
# the cell fetch of 8 bytes (its grid holds doubles: pair this program with
# "grid_cell_bytes": 8); and a first pass without a fetch (its root node)
# that runs the same seven micro-ops to place the first sample.
#
# What is ours: the exit markers. The artifact ends a ray outside the
# program (its traversal pushes a leaf); our records say which RETURN_IF
# ended the last pass (exit contract, robocore/kernel_record.h), so the
# occupancy test of the fetched cell is the first lane of the first CMP
# (the artifact decodes it from the fetched value at no op cost) and:
#   RETURN_IF #0 = the cell stops the ray (hit),
#   RETURN_IF #1 = the next sample is out of range or off the map.
# On a conditional-return datapath the hit pass stops after the first CMP
# (four micro-ops), where the artifact runs none of the seven on the
# blocking cell; the two RETURN_IFs are RETURN-unit micro-ops there, which
# the artifact's sequence does not have. Plain TTA+ drops them.
#
# Inputs per ray: s (distance, x, y: m), step (r, r*dx, r*dy, negated so
# one SUB advances all three), inv_r (1/r, from RCP), stride (size_y, 1),
# thr (the occupied threshold), limit_hi (max range, x extent, y extent),
# zero.

prologue:
  SUB.3   s, s, step               # the artifact's root pass: step forward...
  RCP.1   inv_r, r                 # ...index = floor(p / r)...
  DOT.2   g, p, stride             # ...x * size_y + y
  CMP.3   out_hi, s, limit_hi      # range exhausted, x or y past the map
  OR.1    stop, out_hi.y, out_hi.z
  CMP.3   out_lo, s, zero          # x or y below the map
  OR.1    stop, stop, out_lo.y

loop:
  LOAD    cell, g                  # fetch unit: the 8-byte cell at x * size_y + y
  SUB.3   s, s, step               # next sample: distance += r, x += r*dx, y += r*dy
  RCP.1   inv_r, r                 # 1 / r, as the artifact recomputes it per cell
  DOT.2   g, p, stride             # next cell's index, x * size_y + y (the fetch unit floors)
  CMP.3   test, probe, limit_hi    # x: this cell blocks; y: range exhausted; z: x past the map
  RETURN_IF test.x                 # #0: hit at this cell
  OR.1    stop, test.y, test.z
  CMP.3   out, s, bounds           # next sample's y past the map, x or y below 0
  OR.3    stop, out, stop          # any of them
  RETURN_IF stop                   # #1: range exhausted or map border
