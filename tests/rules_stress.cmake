# The stress update's rules (burn, fluid_viscous, bulk_switch, bulk_linear, null_eos, clay_return), each on a deck
# where it acts (tests/rules.cmake: rules_add). The bulk viscosity decks are current-version
# decks (bulk viscosity on by default).
rules_add(burn_step ${_rules_inputs}/explosives/slab_small.mpm 40 --rule burn=step)
rules_add(fluid_viscous_full ${_rules_inputs}/fluids/viscous_column.mpm 40 --rule fluid_viscous=full)
# Without an EOS (dpm: the new mean stress, after the return) and with one (sjc +
# Mie-Gruneisen: the rotated old mean stress).
rules_add(bulk_switch_stress ${_rules_inputs}/methods/dpm_linear.mpm 40 --rule bulk_switch=stress)
rules_add(bulk_switch_stress_eos ${_rules_inputs}/methods/j2eos_linear.mpm 40 --rule bulk_switch=stress)
# sjc + Mie-Gruneisen loses the linear term, hiex (JWL) its bulk viscosity.
rules_add(bulk_linear_original ${_rules_inputs}/methods/j2eos_linear.mpm 40 --rule bulk_linear=original)
rules_add(bulk_linear_original_hiex ${_rules_inputs}/methods/hiex_linear.mpm 40 --rule bulk_linear=original)
# The four together, with the current program's other rules: hiex, viscous null.
rules_add(stress_current ${_rules_inputs}/explosives/water_tube.mpm 40 --rules current)
# Rule null_eos: the null's wave speed in place of the EOS's first coefficient, with the
# weakly compressible EOS (c0) and with Mie-Gruneisen (rho0 c0^2 in the linear term only).
rules_add(null_eos_weak ${_rules_inputs}/fluids/dam_break_coarse.mpm 40 --rule null_eos=wave_speed)
rules_add(null_eos_mie_gruneisen ${CMAKE_CURRENT_SOURCE_DIR}/decks/water_tube_mg.mpm 40 --rule null_eos=wave_speed)
# Rule clay_return (the newest program's clay): its linearised return on our column.
rules_add(clay_return_column ${_rules_inputs}/clay/clay_column.mpm 60 --rule clay_return=linear)
