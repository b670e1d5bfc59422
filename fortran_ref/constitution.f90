! MaterialModel (Constitution): stress update of one particle, Jaumann rotation, EOS.
! Pure functions of their arguments (no module state). Every sum and product is written
! in the same explicit order as cxx/materials/constitution.cpp, so both give the same bits.
module mpm3d_constitution
  use mpm3d_material
  implicit none
  private

  public :: stress_update, neo_hookean, neo_hookean_tl, det_identity_plus, jaumann_rotate, eos_coefficients, &
            yield_stress, burn_fraction, &
            bulk_viscosity, dp_return

contains

  ! sigma : de with the shear terms counted twice, in a fixed order.
  pure real(dp) function double_dot(s, d)
    real(dp), intent(in) :: s(6), d(6)
    double_dot = (((s(1) * d(1)) + (s(2) * d(2))) + (s(3) * d(3))) + &
                 2.0_dp * (((s(4) * d(4)) + (s(5) * d(5))) + (s(6) * d(6)))
  end function double_dot

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

  ! Rotates sig by the Jaumann rate: sig += W sig - sig W; dw = (w_yz, w_xz, w_xy).
  pure subroutine jaumann_rotate(sig, dw)
    real(dp), intent(inout) :: sig(6)
    real(dp), intent(in) :: dw(3)
    real(dp) :: sxx, syy, szz, syz, sxz, sxy, wyz, wxz, wxy
    sxx = sig(1)
    syy = sig(2)
    szz = sig(3)
    syz = sig(4)
    sxz = sig(5)
    sxy = sig(6)
    wyz = dw(1)
    wxz = dw(2)
    wxy = dw(3)
    sig(1) = sxx + 2.0_dp * ((wxy * sxy) + (wxz * sxz))
    sig(2) = syy + 2.0_dp * ((wyz * syz) - (wxy * sxy))
    sig(3) = szz - 2.0_dp * ((wxz * sxz) + (wyz * syz))
    sig(4) = syz + ((wyz * (szz - syy)) - ((wxy * sxz) + (wxz * sxy)))
    sig(5) = sxz + ((wxz * (szz - sxx)) + ((wxy * syz) - (wyz * sxy)))
    sig(6) = sxy + ((wxy * (syy - sxx)) + ((wxz * syz) + (wyz * sxz)))
  end subroutine jaumann_rotate

  ! Pressure of an EOS in the form p = a + b e (e: internal energy per initial volume),
  ! given mu = rho / rho0 - 1.
  pure subroutine eos_coefficients(m, mu, a, b)
    type(material_params), intent(in) :: m
    real(dp), intent(in) :: mu
    real(dp), intent(out) :: a, b
    real(dp) :: mu2, c1, c2, c3, hug, vv, r1v, r2v
    if (m%eos_type == EOS_JWL) then
      ! JWL: A B R1 R2 omega; V = rho0 / rho.
      vv = 1.0_dp / (1.0_dp + mu)
      r1v = m%eos(3) * vv
      r2v = m%eos(4) * vv
      a = ((m%eos(1) * (1.0_dp - (m%eos(5) / r1v))) * exp(-r1v)) + &
          ((m%eos(2) * (1.0_dp - (m%eos(5) / r2v))) * exp(-r2v))
      b = m%eos(5) / vv
    else if (m%eos_type == EOS_WEAK) then
      ! p = c0^2 (rho - rho0) = rho0 c0^2 mu, independent of e.
      a = (m%rho0 * (m%eos(1) * m%eos(1))) * mu
      b = 0.0_dp
    else if (m%eos_type == EOS_LINEAR) then
      if (mu > 0.0_dp) then
        mu2 = mu * mu
      else
        mu2 = 0.0_dp
      end if
      a = ((m%eos(1) + (m%eos(2) * mu)) + (m%eos(3) * mu2)) + (m%eos(4) * ((mu * mu) * mu))
      b = (m%eos(5) + (m%eos(6) * mu)) + (m%eos(7) * mu2)
    else
      ! Mie-Gruneisen, the book's form (section 5.3.5): in compression the cubic
      ! Hugoniot C1 mu + C2 mu^2 + C3 mu^3 times (1 - g0 mu / (2 (1 + mu))), b = g0;
      ! in tension C1 mu, b = 0.
      c1 = m%rho0 * (m%eos(1) * m%eos(1))
      if (mu > 0.0_dp) then
        c2 = c1 * ((2.0_dp * m%eos(2)) - 1.0_dp)
        c3 = (c1 * (m%eos(2) - 1.0_dp)) * ((3.0_dp * m%eos(2)) - 1.0_dp)
        mu2 = mu * mu
        hug = ((c1 * mu) + (c2 * mu2)) + (c3 * (mu2 * mu))
        a = hug * (1.0_dp - (((0.5_dp * m%eos(3)) * mu) / (1.0_dp + mu)))
        b = m%eos(3)
      else
        a = c1 * mu
        b = 0.0_dp
      end if
    end if
  end subroutine eos_coefficients

  ! Programmed burn of hiex: F = min(1, max(0, (time - t_light) D / (1.5 h))); 1 otherwise.
  pure real(dp) function burn_fraction(m, t_light, time) result(f)
    type(material_params), intent(in) :: m
    real(dp), intent(in) :: t_light, time
    if (m%type /= MAT_HIEX) then
      f = 1.0_dp
      return
    end if
    f = ((time - t_light) * m%det_vel) / m%burn_width
    if (.not. (f > 0.0_dp)) then
      f = 0.0_dp
    else if (.not. (f < 1.0_dp)) then
      f = 1.0_dp
    end if
  end function burn_fraction

  ! Artificial bulk viscosity q = rho l (q1 l d^2 - q2 c d) for d = tr(D) < 0, else 0.
  pure real(dp) function bulk_viscosity(rho, len, c, rate, q1, q2) result(q)
    real(dp), intent(in) :: rho, len, c, rate, q1, q2
    if (.not. (rate < 0.0_dp)) then
      q = 0.0_dp
      return
    end if
    q = (rho * len) * (((q1 * len) * (rate * rate)) - ((q2 * c) * rate))
  end function bulk_viscosity

  ! Drucker-Prager return of a trial stress (deviator s, mean stress sm, tension > 0):
  ! the formulas of cxx/materials/constitution.cpp (dp_return). Returns the equivalent plastic
  ! strain increment.
  real(dp) function dp_return(m, s, sm, bk, g) result(deps)
    type(material_params), intent(in) :: m
    real(dp), intent(inout) :: s(6), sm
    real(dp), intent(in) :: bk, g
    real(dp) :: j2, tau, qphi, kphi, qpsi, sigt, fs, ft, tau_p, alpha_p, h, tau_new, lam, ratio, sm_new
    logical :: tension
    integer :: c
    j2 = (0.5_dp * (((s(1) * s(1)) + (s(2) * s(2))) + (s(3) * s(3)))) + &
         (((s(4) * s(4)) + (s(5) * s(5))) + (s(6) * s(6)))
    tau = sqrt(j2)
    qphi = m%dp_qphi
    kphi = m%dp_kphi
    qpsi = m%dp_qpsi
    sigt = m%dp_tension
    fs = (tau + (qphi * sm)) - kphi
    ft = sm - sigt
    deps = 0.0_dp
    if (.not. (fs > 0.0_dp) .and. .not. (ft > 0.0_dp)) return
    tau_p = kphi - (qphi * sigt)
    alpha_p = sqrt(1.0_dp + (qphi * qphi)) - qphi
    h = (tau - tau_p) - (alpha_p * (sm - sigt))
    tau_new = 0.0_dp
    sm_new = sigt
    tension = .true.
    if (fs > 0.0_dp .and. h > 0.0_dp) then
      lam = fs / (g + ((bk * qphi) * qpsi))
      tau_new = tau - (g * lam)
      sm_new = sm - ((bk * qpsi) * lam)
      ! A non-associated return may land beyond the apex or the cut-off: tension return.
      tension = tau_new < 0.0_dp .or. sm_new > sigt
    end if
    if (tension) then
      if (tau > tau_p) then
        tau_new = tau_p
      else
        tau_new = tau
      end if
      sm_new = sigt
    end if
    sm = sm_new
    if (tau > 0.0_dp) then
      ratio = tau_new / tau
      do c = 1, 6
        s(c) = s(c) * ratio
      end do
    end if
    deps = (tau - tau_new) / (sqrt(3.0_dp) * g)
  end function dp_return

  ! Yield stress and plastic modulus d(sigma_y)/d(epeff) for J2 materials.
  subroutine yield_stress(m, epeff, strain_rate, temp, sy, ep)
    type(material_params), intent(in) :: m
    real(dp), intent(in) :: epeff, strain_rate, temp
    real(dp), intent(out) :: sy, ep
    real(dp) :: hard, slope, factor, ratio, tstar
    select case (m%type)
    case (MAT_PLA1)
      sy = m%yield0
      ep = 0.0_dp
    case (MAT_PLA2)
      sy = m%yield0 + (m%hardening * epeff)
      ep = m%hardening
    case default   ! Johnson-Cook family
      hard = m%yield0
      if (epeff > 0.0_dp) then
        ! pow(e, 1) == e and pow(e, 0) == 1 exactly: the shortcut (as the C++) keeps the bits.
        if (m%jc_n == 1.0_dp) then
          hard = m%yield0 + (m%hardening * epeff)
          slope = (m%jc_n * m%hardening) * 1.0_dp
        else
          hard = m%yield0 + (m%hardening * (epeff ** m%jc_n))
          slope = (m%jc_n * m%hardening) * (epeff ** (m%jc_n - 1.0_dp))
        end if
      else
        if (m%jc_n == 1.0_dp) then
          slope = m%hardening
        else
          slope = 0.0_dp
        end if
      end if
      factor = 1.0_dp
      if (m%jc_c /= 0.0_dp) then
        ratio = strain_rate / m%eps0dot
        if (ratio > 1.0_dp) factor = 1.0_dp + (m%jc_c * log(ratio))
      end if
      if (m%type == MAT_JOHN .or. m%type == MAT_JCF) then
        tstar = (temp - m%t_room) / (m%t_melt - m%t_room)
        if (tstar > 0.0_dp) then
          if (tstar > 1.0_dp) tstar = 1.0_dp
          factor = factor * (1.0_dp - (tstar ** m%jc_m))
        end if
      end if
      sy = hard * factor
      ep = slope * factor
    end select
  end subroutine yield_stress

  ! Radial return of the deviator s against the yield stress; updates epeff and returns
  ! the plastic strain increment (0 when elastic).
  real(dp) function radial_return(m, s, epeff, strain_rate, temp) result(deps)
    type(material_params), intent(in) :: m
    real(dp), intent(inout) :: s(6), epeff
    real(dp), intent(in) :: strain_rate, temp
    real(dp) :: j2, q, sy, ep, g3, ratio
    integer :: c
    deps = 0.0_dp
    if (m%type == MAT_ELAS) return
    j2 = (0.5_dp * (((s(1) * s(1)) + (s(2) * s(2))) + (s(3) * s(3)))) + &
         (((s(4) * s(4)) + (s(5) * s(5))) + (s(6) * s(6)))
    q = sqrt(3.0_dp * j2)
    call yield_stress(m, epeff, strain_rate, temp, sy, ep)
    if (.not. (q > sy)) return
    g3 = 3.0_dp * m%shear
    deps = (q - sy) / (g3 + ep)
    ratio = (q - (g3 * deps)) / q
    do c = 1, 6
      s(c) = s(c) * ratio
    end do
    epeff = epeff + deps
  end function radial_return

  ! Equivalent stress of a deviator, as in the heating term.
  pure real(dp) function q_of(s)
    real(dp), intent(in) :: s(6)
    q_of = sqrt(1.5_dp * ((((s(1) * s(1)) + (s(2) * s(2))) + (s(3) * s(3))) + &
                          2.0_dp * (((s(4) * s(4)) + (s(5) * s(5))) + (s(6) * s(6)))))
  end function q_of

  ! de: strain increment (Voigt, tensor components); dw: spin increment (w_yz, w_xz, w_xy).
  ! vol_old/vol_new: particle volume before and after the increment. temp is read and
  ! written only when has_temp; q (bulk viscosity pressure) only when has_q. burn: the
  ! programmed-burn fraction (hiex); q1, q2, qlen: bulk viscosity coefficients and length.
  subroutine stress_update(m, de, dw, dt, mass, vol_old, vol_new, sig, epeff, ie, has_temp, temp, &
                           has_q, q, burn, q1, q2, qlen)
    type(material_params), intent(in) :: m
    real(dp), intent(in) :: de(6), dw(3), dt, mass, vol_old, vol_new, burn, q1, q2, qlen
    real(dp), intent(inout) :: sig(6), epeff, ie, temp, q
    logical, intent(in) :: has_temp, has_q
    real(dp) :: sig_r(6), dev(6), s(6), s_r(6)
    real(dp) :: dkk, third, two_g, two_mu, vavg, strain_rate, tp, mean_r, lam_dkk, mean, deps, p_new
    real(dp) :: vol0, dv, p_old, dwork, e_star, mu, a, b, e_new, q_new, q_old, base
    logical :: failed, fluid
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
    q_old = 0.0_dp
    q_new = 0.0_dp
    if (has_q) then
      q_old = q
      q_new = bulk_viscosity(mass / vol_new, qlen, m%wave_speed, dkk / dt, q1, q2)
      q = q_new
    end if

    mean_r = mean_of(sig_r)
    if (m%eos_type == EOS_NONE) then
      ! Hypoelastic trial stress, then the return of its deviator (J2) or of the whole
      ! stress (Drucker-Prager).
      lam_dkk = m%lambda * dkk
      do c = 1, 3
        if (has_q) then
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
        deps = dp_return(m, s, mean, m%lambda + (two_g / 3.0_dp), m%shear)
        epeff = epeff + deps
      else
        deps = radial_return(m, s, epeff, strain_rate, tp)
      end if
      p_new = -mean
      failed = m%fail_strain > 0.0_dp .and. epeff >= m%fail_strain
      if (failed) then
        do c = 1, 6
          s(c) = 0.0_dp
        end do
        if (p_new < 0.0_dp) p_new = 0.0_dp
      end if
      call stress_of(s, p_new, has_q, q_new, sig)
      ie = ie + ((0.5_dp * (double_dot(sig_r, de) + double_dot(sig, de))) * vavg)
      call adiabatic_heating(m, s, deps, mass, vol_new, has_temp, temp)
      return
    end if

    ! Deviatoric update plus an equation of state for the pressure. hiex and null carry no
    ! deviatoric stress.
    call minus_diag(sig_r, mean_r, s_r)
    deps = 0.0_dp
    fluid = m%type == MAT_HIEX .or. m%type == MAT_NULL
    if (fluid .and. m%viscosity > 0.0_dp) then
      ! The current version's null: the viscous deviator 2 mu dev(D), D = de / dt.
      two_mu = (2.0_dp * m%viscosity) / dt
      do c = 1, 6
        s(c) = two_mu * dev(c)
      end do
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

    ! Energy equation solved with the new pressure (the EOS is linear in e):
    ! e1 = e* - (p1 + q1) dv / 2, p1 = F (a + b e1).
    vol0 = mass / m%rho0
    dv = (vol_new - vol_old) / vol0
    p_old = -mean_r
    dwork = (0.5_dp * (double_dot(s_r, de) + double_dot(s, de))) * vavg
    e_star = ((ie + dwork) / vol0) - ((0.5_dp * p_old) * dv)
    if (has_q) e_star = e_star - ((0.5_dp * q_new) * dv)
    mu = (vol0 / vol_new) - 1.0_dp
    call eos_coefficients(m, mu, a, b)
    if (m%type == MAT_HIEX) then
      a = burn * a
      b = burn * b
    end if
    p_new = (a + (b * e_star)) / (1.0_dp + ((0.5_dp * b) * dv))
    if (failed .and. p_new < 0.0_dp) p_new = 0.0_dp
    e_new = e_star - ((0.5_dp * p_new) * dv)
    ie = e_new * vol0
    call stress_of(s, p_new, has_q, q_new, sig)
    call adiabatic_heating(m, s, deps, mass, vol_new, has_temp, temp)
  end subroutine stress_update

  ! det(I + A) of a 3x3 increment A (row-major, 0-based), by the cofactors of the first row
  ! (LaneUpdate::det_identity_plus, cxx/materials/constitution_lanes.hpp).
  pure real(dp) function det_identity_plus(a) result(d)
    real(dp), intent(in) :: a(0:8)
    real(dp) :: a0, a4, a8
    a0 = 1.0_dp + a(0)
    a4 = 1.0_dp + a(4)
    a8 = 1.0_dp + a(8)
    d = (a0 * (a4 * a8 - a(5) * a(7)) - a(1) * (a(3) * a8 - a(5) * a(6))) + a(2) * (a(3) * a(7) - a4 * a(6))
  end function det_identity_plus

  ! Compressible neo-Hookean (neoh), as LaneUpdate::neo_hookean: H = F - I advanced by
  ! dL = L dt as H + (dL + dL H); J = det F, B - I = H + H^T + H H^T,
  ! sigma = (G (B - I) + lambda ln J I) / J; internal energy by the trapezoid on de.
  ! With bulk viscosity (has_q), as the current version applies it to neoh: q where the new
  ! mean stress is compressive, in qv and in the stored stress, its work in the energy.
  subroutine neo_hookean(m, dl, de, h, vol_old, vol_new, sig, ie, has_q, qv, mass, dt, q1, q2, qlen)
    type(material_params), intent(in) :: m
    real(dp), intent(in) :: dl(0:8), de(6), vol_old, vol_new, mass, dt, q1, q2, qlen
    logical, intent(in) :: has_q
    real(dp), intent(inout) :: h(0:8), sig(6), ie, qv
    integer, parameter :: ra(6) = [0, 1, 2, 1, 0, 0], rb(6) = [0, 1, 2, 2, 2, 1]
    real(dp) :: hn(0:8), bm(6), sig_old(6), jac, ln_j, inv_j, lam_ln, vavg, work, dkk, mean, q
    integer :: i, k, c, a, b
    do i = 0, 2
      do k = 0, 2
        hn(3 * i + k) = h(3 * i + k) + (dl(3 * i + k) + ((dl(3 * i) * h(k) + dl(3 * i + 1) * h(3 + k)) + &
                                                         dl(3 * i + 2) * h(6 + k)))
      end do
    end do
    h = hn
    jac = det_identity_plus(h)
    ln_j = log(jac)
    do c = 1, 6
      a = ra(c)
      b = rb(c)
      bm(c) = (h(3 * a + b) + h(3 * b + a)) + ((h(3 * a) * h(3 * b) + h(3 * a + 1) * h(3 * b + 1)) + &
                                               h(3 * a + 2) * h(3 * b + 2))
    end do
    inv_j = 1.0_dp / jac
    lam_ln = m%lambda * ln_j
    sig_old = sig
    if (has_q) then
      do c = 1, 3
        sig_old(c) = sig_old(c) + qv
      end do
    end if
    do c = 1, 3
      sig(c) = inv_j * (m%shear * bm(c) + lam_ln)
    end do
    do c = 4, 6
      sig(c) = inv_j * (m%shear * bm(c))
    end do
    vavg = 0.5_dp * (vol_old + vol_new)
    work = double_dot(sig_old, de) + double_dot(sig, de)
    if (has_q) then
      dkk = (de(1) + de(2)) + de(3)
      mean = ((sig(1) + sig(2)) + sig(3)) / 3.0_dp
      q = bulk_viscosity(mass / vol_new, qlen, m%wave_speed, dkk / dt, q1, q2)
      if (mean < 0.0_dp) then
        qv = q
      else
        qv = 0.0_dp
      end if
      work = work - 2.0_dp * (qv * dkk)
      do c = 1, 3
        sig(c) = sig(c) - qv
      end do
    end if
    ie = ie + (0.5_dp * work) * vavg
  end subroutine neo_hookean

  ! Compressible neo-Hookean in total Lagrangian form (TLmp), as LaneUpdate::neo_hookean_tl:
  ! H += dF; P = G (F - F^-T) + lambda ln J F^-T with F^-T = cof(F) / J; pk = V0 P,
  ! sigma = P F^T / J, volume V0 J, internal energy by the trapezoid of V0 P on dF.
  subroutine neo_hookean_tl(m, df, h, mass, pk, sig, vol, ie)
    type(material_params), intent(in) :: m
    real(dp), intent(in) :: df(0:8), mass
    real(dp), intent(inout) :: h(0:8), pk(0:8), ie
    real(dp), intent(out) :: sig(6), vol
    integer, parameter :: ra(6) = [0, 1, 2, 1, 0, 0], rb(6) = [0, 1, 2, 2, 2, 1]
    real(dp) :: f(0:8), cof(0:8), p(0:8), jac, inv_j, ln_j, lam_ln, v0, fit, pn, work_old, work_new
    integer :: r, c, a, b
    do r = 0, 8
      h(r) = h(r) + df(r)
    end do
    do r = 0, 8
      if (mod(r, 4) == 0) then
        f(r) = 1.0_dp + h(r)
      else
        f(r) = h(r)
      end if
    end do
    jac = det_identity_plus(h)
    cof(0) = f(4) * f(8) - f(5) * f(7)
    cof(1) = f(5) * f(6) - f(3) * f(8)
    cof(2) = f(3) * f(7) - f(4) * f(6)
    cof(3) = f(2) * f(7) - f(1) * f(8)
    cof(4) = f(0) * f(8) - f(2) * f(6)
    cof(5) = f(1) * f(6) - f(0) * f(7)
    cof(6) = f(1) * f(5) - f(2) * f(4)
    cof(7) = f(2) * f(3) - f(0) * f(5)
    cof(8) = f(0) * f(4) - f(1) * f(3)
    inv_j = 1.0_dp / jac
    ln_j = log(jac)
    lam_ln = m%lambda * ln_j
    v0 = mass / m%rho0
    do r = 0, 8
      fit = cof(r) * inv_j
      p(r) = (m%shear * (f(r) - fit)) + (lam_ln * fit)
    end do
    do c = 1, 6
      a = ra(c)
      b = rb(c)
      sig(c) = inv_j * (((p(3 * a) * f(3 * b)) + (p(3 * a + 1) * f(3 * b + 1))) + (p(3 * a + 2) * f(3 * b + 2)))
    end do
    work_old = 0.0_dp
    work_new = 0.0_dp
    do r = 0, 8
      pn = v0 * p(r)
      work_old = work_old + (pk(r) * df(r))
      work_new = work_new + (pn * df(r))
      pk(r) = pn
    end do
    ie = ie + 0.5_dp * (work_old + work_new)
    vol = v0 * jac
  end subroutine neo_hookean_tl

  ! Adiabatic heating of thermal Johnson-Cook materials (Taylor-Quinney 0.9).
  subroutine adiabatic_heating(m, s, deps, mass, vol_new, has_temp, temp)
    type(material_params), intent(in) :: m
    real(dp), intent(in) :: s(6), deps, mass, vol_new
    logical, intent(in) :: has_temp
    real(dp), intent(inout) :: temp
    if (has_temp .and. deps > 0.0_dp .and. m%heat_cap > 0.0_dp) then
      temp = temp + ((0.9_dp * (q_of(s) * deps)) / ((mass / vol_new) * m%heat_cap))
    end if
  end subroutine adiabatic_heating

end module mpm3d_constitution
