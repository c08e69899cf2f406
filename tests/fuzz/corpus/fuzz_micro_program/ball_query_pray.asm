# Ball query, P-Ray formulation (RoboGPU paper, "ball query": the tree's
# states are spheres, the query is a ray): BallQueryTree::Search in
# robocore/ball_query/ball_query_search.cc, one query per thread. The ray is
# a zero-length probe at the query point. Loop pass = one BVH2 node fetch;
# the node holds both children's boxes. The box an RT unit tests is the box
# of the spheres below a child: the child's box grown by the radius rho on
# every axis (a slab test, no distance). A child that is a state then runs
# the intersection test: is the probe inside the state's sphere.
#
# Inputs per query: q (coordinates 0-2), q2 (coordinates 3-4), rho (the
# spheres' radius) and rho2 = rho^2; both shrink to the k-th best distance
# once k states are found. Node: as ball_query_psphere.asm.
#
# Departure from an RT unit with fixed sphere boxes (RTNN): the node stores
# the children's tight boxes and the program grows them by rho (SUB, ADD),
# which is what lets rho shrink during the traversal.
#
# Written for the 5-D arm (.3 then .2 micro-ops), as ball_query_psphere.asm.
#
# Exit contract (ball_query_tree.h): RETURN_IF #0 = the probe is outside
# both children's sphere boxes; RETURN_IF #1 = no state's sphere holds the
# probe. No exit: a state's sphere held it and went through the k-best
# insertion.

loop:
  LOAD    node, addr               # one BVH2 node (32 n + 8 bytes)
  PUSH    visited                  # node counter
  # child a: probe inside its box grown by rho?
  SUB.3   lo, alo, rho
  ADD.3   hi, ahi, rho
  CMP.3   above, q, lo
  CMP.3   below, hi, q
  AND.3   in3, above, below
  SUB.2   lo2, alo2, rho
  ADD.2   hi2, ahi2, rho
  CMP.2   above2, q2, lo2
  CMP.2   below2, hi2, q2
  AND.2   in2, above2, below2
  AND.1   in_a, in3.x, in3.y
  AND.1   in_a, in_a, in3.z
  AND.1   in2a, in2.x, in2.y
  AND.1   in_a, in_a, in2a
  # child b: the same
  SUB.3   lo, blo, rho
  ADD.3   hi, bhi, rho
  CMP.3   above, q, lo
  CMP.3   below, hi, q
  AND.3   in3, above, below
  SUB.2   lo2, blo2, rho
  ADD.2   hi2, bhi2, rho
  CMP.2   above2, q2, lo2
  CMP.2   below2, hi2, q2
  AND.2   in2, above2, below2
  AND.1   in_b, in3.x, in3.y
  AND.1   in_b, in_b, in3.z
  AND.1   in2b, in2.x, in2.y
  AND.1   in_b, in_b, in2b
  OR.1    any, in_a, in_b
  NOT.1   none, any
  RETURN_IF none                   # #0: the probe misses both sphere boxes
  # stack entries for internal children, in stored order (a ray has no
  # distance to order them by)
  NOT.1   inner_a, leaf_a
  NOT.1   inner_b, leaf_b
  AND.1   push_a, in_a, inner_a
  AND.1   push_b, in_b, inner_b
  # intersection test of a state child: probe inside the state's sphere
  SUB.3   da, q, alo
  DOT.3   sa, da, da
  SUB.2   da2, q2, alo2
  DOT.2   sa2, da2, da2
  ADD.1   sa, sa, sa2
  CMP.1   hit_a, rho2, sa
  AND.1   hit_a, hit_a, leaf_a
  SUB.3   db, q, blo
  DOT.3   sb, db, db
  SUB.2   db2, q2, blo2
  DOT.2   sb2, db2, db2
  ADD.1   sb, sb, sb2
  CMP.1   hit_b, rho2, sb
  AND.1   hit_b, hit_b, leaf_b
  OR.1    hit, hit_a, hit_b
  NOT.1   no_hit, hit
  RETURN_IF no_hit                 # #1: no state's sphere holds the probe
  # compare-exchange into the sorted k-best list; shrink the spheres
  MIN.1   d2, sa, sb
  CMP.1   better, kth2, d2
  MIN.1   best, best, d2
  MAX.1   kth2, kth2, best
  MIN.1   rho2, rho2, kth2
  # the slab test needs rho itself: rho = kth2 * rsqrt(kth2); the ISA has no
  # RSQRT, so the reciprocal unit's RCP stands for it (same unit, same latency)
  RCP     rinv, kth2
  MUL     rho, kth2, rinv
