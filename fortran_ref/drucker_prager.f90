! Drucker-Prager (dpm): the return of a trial stress (as dp_return of cxx/materials/constitution.cpp,
! which cxx/materials/drucker_prager_lanes.hpp runs lane by lane), and the original programs'
! return (rule dp_return=original, as DruckerPragerLanes::dp_return_original).
module mpm3d_drucker_prager
  use mpm3d_material
  implicit none
  private

  public :: dp_return, dp_return_original

contains

  ! tau = sqrt(J2) of the deviator s (Voigt), which both returns start from.
  pure real(dp) function shear_stress(s) result(tau)
    real(dp), intent(in) :: s(6)
    tau = sqrt((0.5_dp * (((s(1) * s(1)) + (s(2) * s(2))) + (s(3) * s(3)))) + &
               (((s(4) * s(4)) + (s(5) * s(5))) + (s(6) * s(6))))
  end function shear_stress

  ! Drucker-Prager return of a trial stress (deviator s, mean stress sm, tension > 0):
  ! the formulas of cxx/materials/constitution.cpp (dp_return). Returns the equivalent plastic
  ! strain increment.
  real(dp) function dp_return(m, s, sm, bk, g) result(deps)
    type(material_params), intent(in) :: m
    real(dp), intent(inout) :: s(6), sm
    real(dp), intent(in) :: bk, g
    real(dp) :: tau, qphi, kphi, qpsi, sigt, fs, ft, tau_p, alpha_p, h, tau_new, lam, ratio, sm_new
    logical :: tension
    integer :: c
    tau = shear_stress(s)
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

  ! The original programs' return (rule dp_return=original; M3DM9, alike in the book and the
  ! current program), with our variables and plastic strain measure: below the cut-off the
  ! shear return where f_s > 0; at or beyond it the shear return above the corner line
  ! (h > 0), which may leave sm beyond the cut-off, else sm = sigma_t keeping the deviator.
  ! The shear return's tau' is k_phi - q_phi sm'; the cut-off is 0 when q_phi = 0.
  real(dp) function dp_return_original(m, s, sm, bk, g) result(deps)
    type(material_params), intent(in) :: m
    real(dp), intent(inout) :: s(6), sm
    real(dp), intent(in) :: bk, g
    real(dp) :: tau, qphi, kphi, qpsi, sigt, fs, ft, tau_p, alpha_p, h, tau_new, lam, ratio
    logical :: shear
    integer :: c
    tau = shear_stress(s)
    qphi = m%dp_qphi
    kphi = m%dp_kphi
    qpsi = m%dp_qpsi
    if (qphi == 0.0_dp) then
      sigt = 0.0_dp
    else
      sigt = m%dp_tension
    end if
    fs = (tau + (qphi * sm)) - kphi
    ft = sm - sigt
    deps = 0.0_dp
    if (ft < 0.0_dp) then
      shear = fs > 0.0_dp
    else
      tau_p = kphi - (qphi * sigt)
      alpha_p = sqrt(1.0_dp + (qphi * qphi)) - qphi
      h = (tau - tau_p) - (alpha_p * ft)
      shear = h > 0.0_dp
      ! The tension return keeps the deviator.
      if (.not. shear) sm = sigt
    end if
    if (.not. shear) return
    lam = fs / (g + ((bk * qphi) * qpsi))
    sm = sm - ((bk * qpsi) * lam)
    tau_new = kphi - (qphi * sm)
    ratio = tau_new / tau
    do c = 1, 6
      s(c) = s(c) * ratio
    end do
    deps = (tau - tau_new) / (sqrt(3.0_dp) * g)
  end function dp_return_original

end module mpm3d_drucker_prager
