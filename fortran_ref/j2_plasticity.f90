! J2 plasticity: elas, pla1, pla2, clay and the Johnson-Cook family (as
! cxx/materials/j2_plasticity_lanes.hpp and yield_stress of cxx/materials/constitution.cpp):
! the yield stress, the radial return and the adiabatic heating of thermal Johnson-Cook.
module mpm3d_j2_plasticity
  use mpm3d_material
  implicit none
  private

  public :: yield_stress, radial_return, clay_return, adiabatic_heating

  ! clay_return's Newton iterations (kClayIterations, kClayTolerance of cxx/materials/constitution.hpp)
  integer, parameter :: CLAY_ITERATIONS = 30
  real(dp), parameter :: CLAY_TOLERANCE = 1e-13_dp

contains

  ! Yield stress and plastic modulus d(sigma_y)/d(epeff) for J2 materials.
  subroutine yield_stress(m, epeff, strain_rate, temp, sy, ep)
    type(material_params), intent(in) :: m
    real(dp), intent(in) :: epeff, strain_rate, temp
    real(dp), intent(out) :: sy, ep
    real(dp) :: hard, slope, factor, ratio, tstar, drop, decay
    select case (m%type)
    case (MAT_PLA1)
      sy = m%yield0
      ep = 0.0_dp
    case (MAT_PLA2)
      sy = m%yield0 + (m%hardening * epeff)
      ep = m%hardening
    case (MAT_CLAY)
      drop = m%clay_peak - m%clay_residual
      decay = exp(-(m%clay_softening * epeff))
      sy = m%clay_residual + (drop * decay)
      ep = -((m%clay_softening * drop) * decay)
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

  ! clay's return (clay_return of cxx/materials/constitution.cpp, where the method is explained):
  ! original: the newest program's one linearised step (rule clay_return=linear); else Newton's
  ! method on q_trial - 3G d = sigma_y(epeff + d).
  real(dp) function clay_return(m, s, epeff, original) result(d)
    type(material_params), intent(in) :: m
    real(dp), intent(inout) :: s(6), epeff
    logical, intent(in) :: original
    real(dp) :: j2, q, sy, h, g3, r, ratio
    integer :: c, it
    d = 0.0_dp
    j2 = (0.5_dp * (((s(1) * s(1)) + (s(2) * s(2))) + (s(3) * s(3)))) + &
         (((s(4) * s(4)) + (s(5) * s(5))) + (s(6) * s(6)))
    q = sqrt(3.0_dp * j2)
    call yield_stress(m, epeff, 0.0_dp, 0.0_dp, sy, h)
    if (.not. (q > sy)) return
    g3 = 3.0_dp * m%shear
    d = (q - sy) / (g3 + h)
    if (original) then
      call yield_stress(m, epeff + d, 0.0_dp, 0.0_dp, sy, h)
      if (sy > q) then
        epeff = (epeff + d) - d
        d = 0.0_dp
        return
      end if
      ratio = sy / q
    else
      do it = 1, CLAY_ITERATIONS
        call yield_stress(m, epeff + d, 0.0_dp, 0.0_dp, sy, h)
        r = (q - (g3 * d)) - sy
        if (.not. (abs(r) > (CLAY_TOLERANCE * q))) exit
        d = d + (r / (g3 + h))
      end do
      ratio = (q - (g3 * d)) / q
    end if
    do c = 1, 6
      s(c) = s(c) * ratio
    end do
    epeff = epeff + d
  end function clay_return

  ! Equivalent stress of a deviator, as in the heating term.
  pure real(dp) function q_of(s)
    real(dp), intent(in) :: s(6)
    q_of = sqrt(1.5_dp * ((((s(1) * s(1)) + (s(2) * s(2))) + (s(3) * s(3))) + &
                          2.0_dp * (((s(4) * s(4)) + (s(5) * s(5))) + (s(6) * s(6)))))
  end function q_of

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

end module mpm3d_j2_plasticity
