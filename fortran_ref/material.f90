! MaterialData: material and equation-of-state parameters (the original's MaterialData).
! material_params mirrors struct MaterialParams of cxx/material.hpp field by field
! (bind(C)), so the kernels read the same table whichever language filled it.
module mpm3d_material
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none
  private

  integer, parameter, public :: dp = c_double

  ! MaterialType
  integer, parameter, public :: MAT_ELAS = 1, MAT_PLA1 = 2, MAT_PLA2 = 3, MAT_JOHN = 4, &
                                MAT_SJC = 5, MAT_SJCF = 6, MAT_JCF = 7, MAT_HIEX = 8, &
                                MAT_NULL = 9, MAT_DPM = 10
  ! EosType
  integer, parameter, public :: EOS_NONE = 0, EOS_LINEAR = 1, EOS_MIE_GRUNEISEN = 2, EOS_JWL = 3

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
    ! Appended for hiex, null and dpm (as in cxx/material.hpp).
    real(c_double) :: det_vel = 0.0_dp     ! hiex: detonation velocity D
    real(c_double) :: burn_width = 0.0_dp  ! hiex: programmed-burn ramp width 1.5 h
    real(c_double) :: dp_qphi = 0.0_dp     ! dpm: q_phi
    real(c_double) :: dp_kphi = 0.0_dp     ! dpm: k_phi
    real(c_double) :: dp_qpsi = 0.0_dp     ! dpm: q_psi
    real(c_double) :: dp_tension = 0.0_dp  ! dpm: tension cut-off (capped at the apex)
  end type material_params

  public :: material_derive, material_keyword

contains

  function material_keyword(mtype) result(k)
    integer, intent(in) :: mtype
    character(len=4) :: k
    select case (mtype)
    case (MAT_ELAS); k = 'elas'
    case (MAT_PLA1); k = 'pla1'
    case (MAT_PLA2); k = 'pla2'
    case (MAT_JOHN); k = 'john'
    case (MAT_SJC);  k = 'sjc '
    case (MAT_SJCF); k = 'sjcf'
    case (MAT_JCF);  k = 'jcf '
    case (MAT_HIEX); k = 'hiex'
    case (MAT_NULL); k = 'null'
    case (MAT_DPM);  k = 'dpm '
    case default;    k = '?   '
    end select
  end function material_keyword

  ! Fills the derived constants of m from the deck values (same operation order as
  ! cxx/material.cpp); returns an error text or ''.
  subroutine material_derive(m, err)
    type(material_params), intent(inout) :: m
    character(len=:), allocatable, intent(out) :: err
    err = ''
    if (.not. (m%rho0 > 0.0_dp)) then
      err = 'density must be positive'
      return
    end if
    if (m%type == MAT_HIEX .or. m%type == MAT_NULL) then
      ! No deviatoric stiffness: pressure from the EOS only. wave_speed is D or c.
      if (.not. (m%wave_speed > 0.0_dp)) then
        if (m%type == MAT_HIEX) then
          err = 'detonation velocity must be positive'
        else
          err = 'wave speed must be positive'
        end if
        return
      end if
      m%young = 0.0_dp
      m%poisson = 0.0_dp
      m%shear = 0.0_dp
      m%lambda = 0.0_dp
      return
    end if
    if (.not. (m%young > 0.0_dp)) then
      err = "Young's modulus must be positive"
      return
    end if
    if (.not. (m%poisson > -1.0_dp .and. m%poisson < 0.5_dp)) then
      err = "Poisson's ratio must lie in (-1, 0.5)"
      return
    end if
    m%shear = m%young / (2.0_dp * (1.0_dp + m%poisson))
    m%lambda = (m%young * m%poisson) / ((1.0_dp + m%poisson) * (1.0_dp - 2.0_dp * m%poisson))
    m%wave_speed = sqrt((m%lambda + 2.0_dp * m%shear) / m%rho0)
    if (m%type == MAT_DPM) then
      if (.not. (m%dp_qphi >= 0.0_dp) .or. .not. (m%dp_kphi >= 0.0_dp) .or. .not. (m%dp_qpsi >= 0.0_dp)) then
        err = 'Drucker-Prager q_phi, k_phi and q_psi must not be negative'
        return
      end if
      if (.not. (m%dp_tension >= 0.0_dp)) then
        err = 'Drucker-Prager tension cut-off must not be negative'
        return
      end if
      if (m%dp_qphi > 0.0_dp) then
        if (m%dp_tension > m%dp_kphi / m%dp_qphi) m%dp_tension = m%dp_kphi / m%dp_qphi
      end if
    end if
  end subroutine material_derive

end module mpm3d_material
