# The rule bulk_work (the bulk viscosity's work by the new q over the step, as the current
# program), on current-version decks (bulk viscosity on by default; tests/rules.cmake:
# rules_add): with an EOS (sjc + Mie-Gruneisen: -q dV in the energy equation), without one
# (dpm: -q tr(de) V), and john without one (the current program counts it twice there).
rules_add(bulk_work_new ${_rules_inputs}/methods/j2eos_linear.mpm 40 --rule bulk_work=new)
rules_add(bulk_work_new_no_eos ${_rules_inputs}/methods/dpm_linear.mpm 40 --rule bulk_work=new)
rules_add(bulk_work_new_john ${_rules_inputs}/rules/john_wall.mpm 40 --rule bulk_work=new)
