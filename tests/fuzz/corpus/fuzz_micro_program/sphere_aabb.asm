# The sphere robot (as CuRobo's collision spheres): one sphere-vs-AABB test
# per node, the query being one sphere of a robot link
# (robocore/collision/sphere_robot.h: SphereOverlapsAabb, CollideSphere).
# The sphere meets the box iff the box point closest to its centre lies
# within the radius: clamp the centre into the box, then compare the squared
# distance with the squared radius. Touching counts as overlap.
#
# Inputs per query: c (sphere centre, m), r (radius, m). The fetched node
# holds the box as centre b and half extents h (flat_box_tree.h).
#
# Exit contract (sact_kernel_record.h: SphereKernelRecord): RETURN_IF #0
# fires when the sphere misses the node's box; a node the sphere meets runs
# to PUSH (its children are pushed, or a leaf ends the query as a hit).
#
# No SACT unit is used: the test runs on the generic OP units (ADDSUB,
# MAXMIN, MINMAX, Box-Normal for the DOT, CMP), 9 micro-ops per node on
# every RT-unit backend, against the SACT's PRE + up to 15 axis tests.

prologue:
  MUL     r2, r, r                 # squared radius, once per query

loop:
  LOAD    box, node                # the node's AABB: centre b, half extents h
  SUB.3   lo, b, h                 # lower corner
  ADD.3   hi, b, h                 # upper corner
  MAX.3   q, c, lo                 # clamp the centre into the box ...
  MIN.3   q, q, hi                 # ... q = the box point closest to c
  SUB.3   v, c, q                  # centre to closest point
  DOT.3   d2, v, v                 # squared distance
  CMP.1   miss, d2, r2             # d2 > r^2: the sphere misses the box
  RETURN_IF miss                   # #0: the sphere misses
  PUSH    overlapping              # the sphere meets the box
