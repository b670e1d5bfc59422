! The equations of state in the form p = a + b e (as cxx/materials/eos_lanes.hpp and, for JWL,
! eos_coefficients of cxx/materials/constitution.cpp): the linear polynomial, the current
! version's weakly compressible, JWL and Mie-Gruneisen.
module mpm3d_eos
  use mpm3d_material
  implicit none
  private

  public :: eos_coefficients

contains

  ! Pressure of an EOS in the form p = a + b e (e: internal energy per initial volume),
  ! given mu = rho / rho0 - 1.
  pure subroutine eos_coefficients(m, mu, a, b)
    type(material_params), intent(in) :: m
    real(dp), intent(in) :: mu
    real(dp), intent(out) :: a, b
    real(dp) :: mu2, c1, c2, c3, k1, hug, vv, r1v, r2v
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
      ! m%eos_k1, where set, replaces C1 in the linear term alone (rule null_eos).
      c1 = m%rho0 * (m%eos(1) * m%eos(1))
      k1 = c1
      if (m%eos_k1 /= 0.0_dp) k1 = m%eos_k1
      if (mu > 0.0_dp) then
        c2 = c1 * ((2.0_dp * m%eos(2)) - 1.0_dp)
        c3 = (c1 * (m%eos(2) - 1.0_dp)) * ((3.0_dp * m%eos(2)) - 1.0_dp)
        mu2 = mu * mu
        hug = ((k1 * mu) + (c2 * mu2)) + (c3 * (mu2 * mu))
        a = hug * (1.0_dp - (((0.5_dp * m%eos(3)) * mu) / (1.0_dp + mu)))
        b = m%eos(3)
      else
        a = k1 * mu
        b = 0.0_dp
      end if
    end if
  end subroutine eos_coefficients

end module mpm3d_eos
