# Beam-model leaf: runs once per ray after the traversal and turns the
# ray-cast range z_star into the beam's log density for measured range z
# (Thrun et al., Probabilistic Robotics 6.3; BeamLogDensity in
# workloads/delibot/beam_sensor_model.cc).
#
# The artifact's leaf runs a 14-op beam model (REFERENCE.md section 2); this
# leaf has 14 micro-ops too, but the op mix is ours. Neither the paper's ISA
# nor ours has EXP or LOG, so the leaf works in the log domain with a max-log
# approximation of the mixture (the largest of hit, short, max and rand).
# It is a cost description: the exact log density is computed on the host.
#
# Inputs: z, z_star, neg_half_inv_var (-1/(2 sigma^2)), neg_lambda,
# log_z_hit, log_z_rand, log_z_max, z_max, sum (the particle's log weight).

epilogue:
  SUB.1   e, z, z_star             # residual
  MUL     e2, e, e
  MUL     lg_hit, e2, neg_half_inv_var   # log of the hit Gaussian (unnormalized)
  CMP.1   is_short, z, z_star      # the short-reading window: z < z*
  MUL     lg_short, z, neg_lambda  # log of the short exponential
  AND.1   lg_short, is_short, lg_short
  MAX.1   lg, lg_hit, lg_short     # max-log mixture
  ADD.1   lg, lg, log_z_hit
  MAX.1   lg, lg, log_z_rand       # the uniform floor
  CMP.1   is_max, z, z_max         # a max-range reading
  AND.1   lg_max, is_max, log_z_max
  OR.1    lg, lg, lg_max
  ADD.1   sum, sum, lg             # into the particle's log weight
  RETURN
