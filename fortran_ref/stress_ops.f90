! The operations the stress updates of all the models share (as cxx/materials/stress_ops_lanes.hpp):
! sigma : de, the Jaumann rotation, the artificial bulk viscosity and det(I + A). Pure; every
! sum and product in the C++ order, so both give the same bits.
module mpm3d_stress_ops
  use mpm3d_material
  implicit none
  private

  public :: double_dot, jaumann_rotate, bulk_viscosity, det_identity_plus

contains

  ! sigma : de with the shear terms counted twice, in a fixed order.
  pure real(dp) function double_dot(s, d)
    real(dp), intent(in) :: s(6), d(6)
    double_dot = (((s(1) * d(1)) + (s(2) * d(2))) + (s(3) * d(3))) + &
                 2.0_dp * (((s(4) * d(4)) + (s(5) * d(5))) + (s(6) * d(6)))
  end function double_dot

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

  ! Artificial bulk viscosity q = rho l (q1 l d^2 - q2 c d) for d = tr(D) < 0, else 0.
  pure real(dp) function bulk_viscosity(rho, len, c, rate, q1, q2) result(q)
    real(dp), intent(in) :: rho, len, c, rate, q1, q2
    if (.not. (rate < 0.0_dp)) then
      q = 0.0_dp
      return
    end if
    q = (rho * len) * (((q1 * len) * (rate * rate)) - ((q2 * c) * rate))
  end function bulk_viscosity

  ! det(I + A) of a 3x3 increment A (row-major, 0-based), by the cofactors of the first row
  ! (StressOps::det_identity_plus, cxx/materials/stress_ops_lanes.hpp).
  pure real(dp) function det_identity_plus(a) result(d)
    real(dp), intent(in) :: a(0:8)
    real(dp) :: a0, a4, a8
    a0 = 1.0_dp + a(0)
    a4 = 1.0_dp + a(4)
    a8 = 1.0_dp + a(8)
    d = (a0 * (a4 * a8 - a(5) * a(7)) - a(1) * (a(3) * a8 - a(5) * a(6))) + a(2) * (a(3) * a(7) - a4 * a(6))
  end function det_identity_plus

end module mpm3d_stress_ops
