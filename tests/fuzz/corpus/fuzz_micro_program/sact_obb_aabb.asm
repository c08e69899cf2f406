# One OBB-vs-AABB separating-axis test (SACT) per node, staged: the
# pre-process, then the 6 box-normal axes, then the 9 edge x edge axes, each
# followed by its early-exit RETURN_IF (paper: "SACT on TTA+"; REFERENCE.md
# section 1). RETURN_IF #k fires when axis k separates the pair, so a record
# whose node exit is k prices a test that stopped at axis k.
#
# On RoboCore, PRE/BOX/EDGE run on the chained SACT units and each RETURN_IF
# that tests the axis just computed is folded into the CTRL block. On TTA+
# each SACT micro-op runs as its TTA+ expansion (47 micro-ops for a full
# test) and each RETURN_IF is a RETURN-unit micro-op.
#
# The collision kernel (a later issue) will use this program; today it serves
# the datapath tests.

loop:
  LOAD    box, node                # the node's AABB
  PRE     frame, obb, box          # relative rotation and translation
  BOX     sep, frame, 0
  RETURN_IF sep                    # #0: box-normal axis 0 separates
  BOX     sep, frame, 1
  RETURN_IF sep                    # #1: box-normal axis 1 separates
  BOX     sep, frame, 2
  RETURN_IF sep                    # #2: box-normal axis 2 separates
  BOX     sep, frame, 3
  RETURN_IF sep                    # #3: box-normal axis 3 separates
  BOX     sep, frame, 4
  RETURN_IF sep                    # #4: box-normal axis 4 separates
  BOX     sep, frame, 5
  RETURN_IF sep                    # #5: box-normal axis 5 separates
  EDGE    sep, frame, 0
  RETURN_IF sep                    # #6: edge axis 0 separates
  EDGE    sep, frame, 1
  RETURN_IF sep                    # #7: edge axis 1 separates
  EDGE    sep, frame, 2
  RETURN_IF sep                    # #8: edge axis 2 separates
  EDGE    sep, frame, 3
  RETURN_IF sep                    # #9: edge axis 3 separates
  EDGE    sep, frame, 4
  RETURN_IF sep                    # #10: edge axis 4 separates
  EDGE    sep, frame, 5
  RETURN_IF sep                    # #11: edge axis 5 separates
  EDGE    sep, frame, 6
  RETURN_IF sep                    # #12: edge axis 6 separates
  EDGE    sep, frame, 7
  RETURN_IF sep                    # #13: edge axis 7 separates
  EDGE    sep, frame, 8
  RETURN_IF sep                    # #14: edge axis 8 separates
  PUSH    overlapping              # no axis separates: the pair overlaps
