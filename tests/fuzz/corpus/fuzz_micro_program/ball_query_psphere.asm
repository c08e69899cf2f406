# Ball query, P-Sphere formulation (RoboGPU paper, "ball query": the query is
# a sphere over the states): BallQueryTree::Search in
# robocore/ball_query/ball_query_search.cc, one query per thread. Loop pass =
# one BVH2 node fetch; the node holds both children's boxes, and a state's
# box is the state itself (lo = hi = its coordinates), so one exact
# sphere-vs-box test serves internal children and states alike.
#
# Inputs per query: q (coordinates 0-2), q2 (coordinates 3-4), rho2 (the
# sphere's squared radius; it shrinks to the k-th best squared distance once
# k states are found), the k-best list (best, kth2).
# Node (robocore/ball_query/ball_query_tree.h): alo, ahi, alo2, ahi2 (child
# a's box), the same for b, leaf_a and leaf_b (is the child a state).
#
# Written for the 5-D arm: coordinates 0-2 run as .3 and 3-4 as .2 micro-ops.
# On the vec3 RoboCore/TTA+ datapath any dimension up to 6 costs the same;
# SIMT instructions and energy count 5 coordinates.
#
# Exit contract (ball_query_tree.h): RETURN_IF #0 = neither child touches the
# sphere (nothing to push or insert); RETURN_IF #1 = no state inside the
# sphere (only internal children pushed). No exit: a state was inside and
# went through the k-best insertion.

loop:
  LOAD    node, addr               # one BVH2 node (32 n + 8 bytes)
  PUSH    visited                  # node counter
  # child a: squared distance from q to its box (clamp, subtract, dot)
  MAX.3   ca, q, alo
  MIN.3   ca, ca, ahi
  SUB.3   da, q, ca
  DOT.3   sa, da, da
  MAX.2   ca2, q2, alo2
  MIN.2   ca2, ca2, ahi2
  SUB.2   da2, q2, ca2
  DOT.2   sa2, da2, da2
  ADD.1   sa, sa, sa2
  CMP.1   in_a, rho2, sa           # touches the sphere (sa <= rho2)
  # child b: the same
  MAX.3   cb, q, blo
  MIN.3   cb, cb, bhi
  SUB.3   db, q, cb
  DOT.3   sb, db, db
  MAX.2   cb2, q2, blo2
  MIN.2   cb2, cb2, bhi2
  SUB.2   db2, q2, cb2
  DOT.2   sb2, db2, db2
  ADD.1   sb, sb, sb2
  CMP.1   in_b, rho2, sb
  OR.1    any, in_a, in_b
  NOT.1   none, any
  RETURN_IF none                   # #0: both children outside the sphere
  # near child first: order the stack entries by squared distance (kept
  # with the entry, so a later pop drops it without a fetch once rho2 shrinks)
  CMP.1   b_first, sa, sb
  NOT.1   inner_a, leaf_a
  NOT.1   inner_b, leaf_b
  AND.1   push_a, in_a, inner_a
  AND.1   push_b, in_b, inner_b
  AND.1   top, b_first, push_b     # the stack entry popped next
  AND.1   state_a, in_a, leaf_a
  AND.1   state_b, in_b, leaf_b
  OR.1    state, state_a, state_b
  NOT.1   no_state, state
  RETURN_IF no_state               # #1: no state inside the sphere
  # a state inside: compare-exchange into the sorted k-best list, then
  # shrink the sphere to the k-th best distance
  MIN.1   d2, sa, sb
  CMP.1   better, kth2, d2
  MIN.1   best, best, d2
  MAX.1   kth2, kth2, best
  MIN.1   rho2, rho2, kth2
