! MaterialData: material and equation-of-state parameters (the original's MaterialData).
! material_params mirrors struct MaterialParams of cxx/materials/material.hpp field by field
! (bind(C)), so the kernels read the same table whichever language filled it.
module mpm3d_material
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none
  private

  integer, parameter, public :: dp = c_double

  ! MaterialType
  integer, parameter, public :: MAT_ELAS = 1, MAT_PLA1 = 2, MAT_PLA2 = 3, MAT_JOHN = 4, &
                                MAT_SJC = 5, MAT_SJCF = 6, MAT_JCF = 7, MAT_HIEX = 8, &
                                MAT_NULL = 9, MAT_DPM = 10, MAT_NEOH = 11, MAT_CLAY = 12
  ! EosType
  ! EOS_WEAK: the current version's weakly compressible p = c0^2 (rho - rho0) (type 4).
  integer, parameter, public :: EOS_NONE = 0, EOS_LINEAR = 1, EOS_MIE_GRUNEISEN = 2, EOS_JWL = 3, EOS_WEAK = 4

  type, bind(C), public :: material_params
    real(c_double) :: rho0 = 0.0_dp        ! initial density
    real(c_double) :: young = 0.0_dp       ! Young's modulus E
    real(c_double) :: poisson = 0.0_dp     ! Poisson's ratio nu
    real(c_double) :: shear = 0.0_dp       ! G = E / (2 (1 + nu))
    real(c_double) :: lambda = 0.0_dp      ! Lame lambda
    real(c_double) :: yield0 = 0.0_dp      ! yield stress (pla1, pla2) or Johnson-Cook A
    real(c_double) :: hardening = 0.0_dp   ! pla2: E Et / (E - Et); JC: B
    real(c_double) :: jc_n = 0.0_dp
    real(c_double) :: jc_c = 0.0_dp
    real(c_double) :: jc_m = 0.0_dp
    real(c_double) :: t_room = 0.0_dp
    real(c_double) :: t_melt = 0.0_dp
    real(c_double) :: heat_cap = 0.0_dp
    real(c_double) :: eps0dot = 0.0_dp
    real(c_double) :: fail_strain = 0.0_dp
    real(c_double) :: wave_speed = 0.0_dp
    real(c_double) :: eos(8) = 0.0_dp      ! EOS parameters as in the deck (seos)
    real(c_double) :: eos_e0 = 0.0_dp      ! initial internal energy per unit initial volume
    integer(c_int) :: type = 0             ! MaterialType
    integer(c_int) :: eos_type = 0         ! EosType
    ! Appended for hiex, null and dpm (as in cxx/materials/material.hpp).
    real(c_double) :: det_vel = 0.0_dp     ! hiex: detonation velocity D
    real(c_double) :: burn_width = 0.0_dp  ! hiex: programmed-burn ramp width 1.5 h
    real(c_double) :: dp_qphi = 0.0_dp     ! dpm: q_phi
    real(c_double) :: dp_kphi = 0.0_dp     ! dpm: k_phi
    real(c_double) :: dp_qpsi = 0.0_dp     ! dpm: q_psi
    real(c_double) :: dp_tension = 0.0_dp  ! dpm: tension cut-off (capped at the apex)
    real(c_double) :: bulk_modulus = 0.0_dp  ! current null: K (wave speed sqrt(K / rho0))
    real(c_double) :: viscosity = 0.0_dp     ! current null: dynamic viscosity mu (0: none)
    ! Appended for clay: sigma_y(epeff) = residual + (peak - residual) exp(-softening epeff).
    real(c_double) :: clay_peak = 0.0_dp       ! kappa_p: peak yield stress
    real(c_double) :: clay_residual = 0.0_dp   ! kappa_r: residual yield stress
    real(c_double) :: clay_softening = 0.0_dp  ! eta: softening coefficient
    ! Mie-Gruneisen: the linear term's coefficient when non-zero, else rho0 c0^2 (rule null_eos).
    real(c_double) :: eos_k1 = 0.0_dp
    ! Extension 'pmin' (null only): cavitation cut-off p_min (<= 0) where has_p_min /= 0.
    real(c_double) :: p_min = 0.0_dp
    integer(c_int) :: has_p_min = 0
  end type material_params

end module mpm3d_material
