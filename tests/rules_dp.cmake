# Rule dp_return (Drucker-Prager): the original programs' branches. The slope reaches the
# tension branch (kept deviator) and the shear return beyond the cut-off within 20 steps;
# the method deck has cohesion and a non-zero cut-off.
rules_add(dp_return_slope ${_rules_inputs}/granular/slope.mpm 40 --rule dp_return=original)
rules_add(dp_return_dpm_linear ${_rules_inputs}/methods/dpm_linear.mpm 40 --rule dp_return=original)
