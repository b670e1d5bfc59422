! MaterialModel (Constitution): the stress update of one particle (the skeleton and the
! dispatch on the material, as cxx/materials/constitution_lanes.hpp) and the programmed burn.
! The model families are modules of their own: stress_ops.f90 (what all share), eos.f90,
! j2_plasticity.f90, drucker_prager.f90, neo_hookean.f90; this module passes on what the
! stages use. Pure functions of their arguments (no module state). Every sum and product is
! written in the same explicit order as the C++ (cxx/materials/), so both give the same bits.
module mpm3d_constitution
  use, intrinsic :: iso_c_binding, only: c_float
  use mpm3d_material
  use mpm3d_stress_ops, only: double_dot, jaumann_rotate, bulk_viscosity, det_identity_plus
  use mpm3d_eos, only: eos_coefficients
  use mpm3d_j2_plasticity, only: yield_stress, radial_return, clay_return, adiabatic_heating
  use mpm3d_drucker_prager, only: dp_return, dp_return_original
  use mpm3d_neo_hookean, only: neo_hookean, neo_hookean_tl
  use mpm3d_rules, only: step_rules
  implicit none
  private

  public :: stress_update, neo_hookean, neo_hookean_tl, det_identity_plus, jaumann_rotate, eos_coefficients, &
            yield_stress, burn_fraction, &
            bulk_viscosity, dp_return

contains

  ! Mean of the three normal components of a stress, in a fixed order.
  pure real(dp) function mean_of(a)
    real(dp), intent(in) :: a(6)
    mean_of = ((a(1) + a(2)) + a(3)) / 3.0_dp
  end function mean_of

  ! r = a - x I (Voigt): x off the three normal components, the shear components copied.
  pure subroutine minus_diag(a, x, r)
    real(dp), intent(in) :: a(6), x
    real(dp), intent(out) :: r(6)
    integer :: c
    do c = 1, 3
      r(c) = a(c) - x
    end do
    do c = 4, 6
      r(c) = a(c)
    end do
  end subroutine minus_diag

  ! The stress from its deviator s and the pressure p, plus the bulk viscosity q when has_q.
  pure subroutine stress_of(s, p, has_q, q, sig)
    real(dp), intent(in) :: s(6), p, q
    logical, intent(in) :: has_q
    real(dp), intent(out) :: sig(6)
    real(dp) :: p_tot
    if (has_q) then
      p_tot = p + q
    else
      p_tot = p
    end if
    call minus_diag(s, p_tot, sig)
  end subroutine stress_of

  ! Programmed burn of hiex: F = min(1, max(0, (time - t_light) D / (1.5 h))); with step
  ! (rule burn=step) the original's F = 1 once time (the end of the step) is past the
  ! lighting time, which it holds in single precision, else 0. 1 for every other material.
  pure real(dp) function burn_fraction(m, t_light, time, step) result(f)
    type(material_params), intent(in) :: m
    real(dp), intent(in) :: t_light, time
    logical, intent(in) :: step
    if (m%type /= MAT_HIEX) then
      f = 1.0_dp
      return
    end if
    if (step) then
      f = 0.0_dp
      if (time > real(real(t_light, c_float), dp)) f = 1.0_dp
      return
    end if
    f = ((time - t_light) * m%det_vel) / m%burn_width
    if (.not. (f > 0.0_dp)) then
      f = 0.0_dp
    else if (.not. (f < 1.0_dp)) then
      f = 1.0_dp
    end if
  end function burn_fraction

  ! de: strain increment (Voigt, tensor components); dw: spin increment (w_yz, w_xz, w_xy).
  ! vol_old/vol_new: particle volume before and after the increment (vol_new less a dpm
  ! particle's opening beyond its tension cut-off, on return). temp is read and
  ! written only when has_temp; q (bulk viscosity pressure) only when has_q. burn: the
  ! programmed-burn fraction (hiex); q1, q2, qlen: bulk viscosity coefficients and length.
  ! rules: the rules in force (rules.f90; read: bulk_switch, bulk_linear, dp_return, fluid_viscous,
  ! bulk_work).
  subroutine stress_update(m, de, dw, dt, mass, vol_old, vol_new, sig, epeff, ie, has_temp, temp, &
                           has_q, q, burn, q1, q2, qlen, rules)
    type(material_params), intent(in) :: m
    type(step_rules), intent(in) :: rules
    real(dp), intent(in) :: de(6), dw(3), dt, mass, vol_old, burn, q1, q2, qlen
    real(dp), intent(inout) :: vol_new, sig(6), epeff, ie, temp, q
    logical, intent(in) :: has_temp, has_q
    real(dp) :: sig_r(6), dev(6), s(6), s_r(6), mean_trial, bulk
    real(dp) :: dkk, third, two_g, two_mu, vavg, strain_rate, tp, mean_r, lam_dkk, mean, deps, p_new
    real(dp) :: vol0, dv, p_old, dwork, e_star, mu, a, b, e_new, q_new, q_old, base, q_speed, work
    logical :: failed, fluid, q_on
    integer :: c

    call jaumann_rotate(sig, dw)
    do c = 1, 6
      sig_r(c) = sig(c)
    end do

    dkk = (de(1) + de(2)) + de(3)
    third = dkk / 3.0_dp
    call minus_diag(de, third, dev)
    two_g = 2.0_dp * m%shear
    vavg = 0.5_dp * (vol_old + vol_new)
    ! Only the Johnson-Cook rate term reads it; it is formed only when that term is on.
    if (m%jc_c /= 0.0_dp) then
      strain_rate = sqrt((2.0_dp / 3.0_dp) * double_dot(dev, dev)) / dt
    else
      strain_rate = 0.0_dp
    end if
    if (has_temp) then
      tp = temp
    else
      tp = 0.0_dp
    end if
    ! Bulk viscosity: the stored stress carries the last q in its pressure.
    q_on = has_q
    q_speed = m%wave_speed     ! the linear term's c
    if (has_q .and. rules%bulk_linear /= 0) call bulk_q_original(m, q_on, q_speed)
    q_old = 0.0_dp
    q_new = 0.0_dp
    if (q_on) then
      q_old = q
      q_new = bulk_viscosity(mass / vol_new, qlen, q_speed, dkk / dt, q1, q2)
      q = q_new
    end if

    mean_r = mean_of(sig_r)
    if (m%eos_type == EOS_NONE) then
      ! Hypoelastic trial stress, then the return of its deviator (J2) or of the whole
      ! stress (Drucker-Prager).
      lam_dkk = m%lambda * dkk
      do c = 1, 3
        if (q_on) then
          base = sig_r(c) + q_old
        else
          base = sig_r(c)
        end if
        sig(c) = base + (lam_dkk + (two_g * de(c)))
      end do
      do c = 4, 6
        sig(c) = sig_r(c) + (two_g * de(c))
      end do
      mean = mean_of(sig)
      call minus_diag(sig, mean, s)
      if (m%type == MAT_DPM) then
        if (rules%dp_return /= 0) then
          deps = dp_return_original(m, s, mean, m%lambda + (two_g / 3.0_dp), m%shear)
        else
          ! Beyond the tension cut-off the particles separate: the return's volumetric opening
          ! is space between them, not a larger particle (as the cxx update).
          mean_trial = mean
          bulk = m%lambda + (two_g / 3.0_dp)
          deps = dp_return(m, s, mean, bulk, m%shear)
          if (mean == m%dp_tension .and. mean_trial > mean) &
            vol_new = vol_new - (vol_old * ((mean_trial - mean) / bulk))
        end if
        epeff = epeff + deps
      else if (m%type == MAT_CLAY) then
        deps = clay_return(m, s, epeff, rules%clay_return /= 0)
      else
        deps = radial_return(m, s, epeff, strain_rate, tp)
      end if
      if (q_on .and. rules%bulk_switch /= 0) then
        ! Rule bulk_switch=stress: q only where the new mean stress (after the return) is compressive.
        if (.not. (mean < 0.0_dp)) q_new = 0.0_dp
        q = q_new
      end if
      p_new = -mean
      failed = m%fail_strain > 0.0_dp .and. epeff >= m%fail_strain
      if (failed) then
        do c = 1, 6
          s(c) = 0.0_dp
        end do
        if (p_new < 0.0_dp) p_new = 0.0_dp
      end if
      call stress_of(s, p_new, q_on, q_new, sig)
      work = double_dot(sig_r, de) + double_dot(sig, de)
      if (q_on .and. rules%bulk_work /= 0) then
        ! Rule bulk_work=new: q's work by the new q over the whole step (the old stress's q_old
        ! replaced by q_new), as the current program; for john it subtracts that work twice.
        work = work + ((q_old - q_new) * dkk)
        if (m%type == MAT_JOHN) work = work - (2.0_dp * (q_new * dkk))
      end if
      ie = ie + ((0.5_dp * work) * vavg)
      call adiabatic_heating(m, s, deps, mass, vol_new, has_temp, temp)
      return
    end if

    ! Deviatoric update plus an equation of state for the pressure. hiex and null carry no
    ! deviatoric stress.
    call minus_diag(sig_r, mean_r, s_r)
    deps = 0.0_dp
    fluid = m%type == MAT_HIEX .or. m%type == MAT_NULL
    if (fluid .and. m%viscosity > 0.0_dp) then
      ! The current version's null: the viscous deviator 2 mu dev(D), D = de / dt; under the
      ! rule fluid_viscous=full the original's 2 mu D (its integer 1/3 drops the trace term).
      two_mu = (2.0_dp * m%viscosity) / dt
      if (rules%fluid_viscous /= 0) then
        do c = 1, 6
          s(c) = two_mu * de(c)
        end do
      else
        do c = 1, 6
          s(c) = two_mu * dev(c)
        end do
      end if
    else if (fluid) then
      do c = 1, 6
        s(c) = 0.0_dp
      end do
    else
      do c = 1, 6
        s(c) = s_r(c) + (two_g * dev(c))
      end do
      deps = radial_return(m, s, epeff, strain_rate, tp)
    end if
    failed = m%fail_strain > 0.0_dp .and. epeff >= m%fail_strain
    if (failed) then
      do c = 1, 6
        s(c) = 0.0_dp
      end do
    end if
    if (q_on .and. rules%bulk_switch /= 0) then
      ! Rule bulk_switch=stress: q only where the rotated old mean stress, without its q, is
      ! compressive.
      if (.not. (mean_r + q_old < 0.0_dp)) q_new = 0.0_dp
      q = q_new
    end if

    ! Energy equation solved with the new pressure (the EOS is linear in e):
    ! e1 = e* - (p1 + q1) dv / 2, p1 = F (a + b e1).
    vol0 = mass / m%rho0
    dv = (vol_new - vol_old) / vol0
    p_old = -mean_r
    dwork = (0.5_dp * (double_dot(s_r, de) + double_dot(s, de))) * vavg
    e_star = ((ie + dwork) / vol0) - ((0.5_dp * p_old) * dv)
    if (q_on) then
      ! Rule bulk_work=new: the current program's -q_new dv in place of the old and new q's
      ! halves (p_old carries q_old).
      if (rules%bulk_work /= 0) then
        e_star = e_star - ((q_new - (0.5_dp * q_old)) * dv)
      else
        e_star = e_star - ((0.5_dp * q_new) * dv)
      end if
    end if
    mu = (vol0 / vol_new) - 1.0_dp
    call eos_coefficients(m, mu, a, b)
    if (m%type == MAT_HIEX) then
      a = burn * a
      b = burn * b
    end if
    p_new = (a + (b * e_star)) / (1.0_dp + ((0.5_dp * b) * dv))
    if (failed .and. p_new < 0.0_dp) p_new = 0.0_dp
    if (m%has_p_min /= 0 .and. p_new < m%p_min) p_new = m%p_min
    e_new = e_star - ((0.5_dp * p_new) * dv)
    ie = e_new * vol0
    call stress_of(s, p_new, q_on, q_new, sig)
    call adiabatic_heating(m, s, deps, mass, vol_new, has_temp, temp)
  end subroutine stress_update

  ! The current program's bulk viscosity (rules bulk_switch=stress, bulk_linear=original;
  ! the C++ LaneUpdate::bulk_q_original says what it does for each model): whether
  ! material m gets q (on), and the linear term's c (speed).
  pure subroutine bulk_q_original(m, on, speed)
    type(material_params), intent(in) :: m
    logical, intent(out) :: on
    real(dp), intent(out) :: speed
    logical :: with_eos, linear
    with_eos = m%type == MAT_SJC .or. m%type == MAT_SJCF .or. m%type == MAT_JCF .or. m%type == MAT_HIEX .or. &
               m%type == MAT_NULL
    linear = m%type == MAT_ELAS .or. m%type == MAT_NEOH .or. m%type == MAT_NULL
    speed = 0.0_dp
    if (linear) speed = m%wave_speed
    on = .not. with_eos .or. m%eos_type == EOS_MIE_GRUNEISEN .or. m%eos_type == EOS_WEAK
  end subroutine bulk_q_original

end module mpm3d_constitution
