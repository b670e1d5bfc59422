! The compressible neo-Hookean solid (neoh), updated and in total Lagrangian form (TLmp), as
! cxx/materials/neo_hookean_lanes.hpp.
module mpm3d_neo_hookean
  use mpm3d_material
  use mpm3d_stress_ops, only: double_dot, bulk_viscosity, det_identity_plus
  implicit none
  private

  public :: neo_hookean, neo_hookean_tl

contains

  ! Compressible neo-Hookean (neoh), as NeoHookeanLanes::neo_hookean: H = F - I advanced by
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

  ! Compressible neo-Hookean in total Lagrangian form (TLmp), as NeoHookeanLanes::neo_hookean_tl:
  ! H += dF; P = G (F - F^-T) + lambda ln J F^-T with F^-T = cof(F) / J; pk = V0 P,
  ! sigma = P F^T / J, volume V0 J (vol: the old in, the new out), internal energy by the
  ! trapezoid of V0 P on dF; work_current_volume (rule tl_shape=centre): the current program's,
  ! the trapezoid of P on dF times the mean old and new current volume.
  subroutine neo_hookean_tl(m, df, h, mass, pk, sig, vol, ie, work_current_volume)
    type(material_params), intent(in) :: m
    real(dp), intent(in) :: df(0:8), mass
    real(dp), intent(inout) :: h(0:8), pk(0:8), ie, vol
    real(dp), intent(out) :: sig(6)
    logical, intent(in) :: work_current_volume
    integer, parameter :: ra(6) = [0, 1, 2, 1, 0, 0], rb(6) = [0, 1, 2, 2, 2, 1]
    real(dp) :: f(0:8), cof(0:8), p(0:8), jac, inv_j, ln_j, lam_ln, v0, fit, pn, work_old, work_new, vol_new
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
    vol_new = v0 * jac
    if (work_current_volume) then
      ie = ie + (0.5_dp * (work_old + work_new)) * ((0.5_dp * (vol + vol_new)) / v0)
    else
      ie = ie + 0.5_dp * (work_old + work_new)
    end if
    vol = vol_new
  end subroutine neo_hookean_tl

end module mpm3d_neo_hookean
