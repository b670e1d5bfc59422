! The material models, one entry each (as cxx/materials/material_models.cpp): the deck keyword of
! the 'mate' card, the type, what kind of solid or fluid it is, the card's parameters in
! deck order with the checks of their values, and the derived constants. The deck reader
! asks this module; the stress update of a type is in its family's module (eos.f90,
! j2_plasticity.f90, drucker_prager.f90, neo_hookean.f90), which stress_update in
! constitution.f90 dispatches to. Adding a model: a MAT_ value (material.f90, and
! cxx/materials/material.hpp), one row in MODELS and one case in read_material_card here, its
! stress update (a family module and its branch in constitution.f90), and the same in C++.
module mpm3d_material_models
  use mpm3d_material
  use mpm3d_ffi, only: token_stream
  implicit none
  private

  type :: material_model_t
    character(len=4) :: keyword
    integer :: type
    logical :: fluid         ! no shear stiffness: pressure from its EOS only (hiex, null)
    logical :: johnson_cook  ! Johnson-Cook flow stress (n, C, reference strain rate checked)
    logical :: thermal       ! tracks temperature
  end type material_model_t

  type(material_model_t), parameter :: MODELS(11) = [ &
    material_model_t('elas', MAT_ELAS, .false., .false., .false.), &
    material_model_t('pla1', MAT_PLA1, .false., .false., .false.), &
    material_model_t('pla2', MAT_PLA2, .false., .false., .false.), &
    material_model_t('john', MAT_JOHN, .false., .true., .true.), &
    material_model_t('jcf ', MAT_JCF, .false., .true., .true.), &
    material_model_t('sjc ', MAT_SJC, .false., .true., .false.), &
    material_model_t('sjcf', MAT_SJCF, .false., .true., .false.), &
    material_model_t('hiex', MAT_HIEX, .true., .false., .false.), &
    material_model_t('null', MAT_NULL, .true., .false., .false.), &
    material_model_t('dpm ', MAT_DPM, .false., .false., .false.), &
    material_model_t('neoh', MAT_NEOH, .false., .false., .false.)]

  public :: material_type_of, material_keyword, material_is_fluid, material_is_johnson_cook, &
            material_is_thermal, read_material_card, material_derive

contains

  ! The MaterialType of a deck keyword (cut to four characters), 0 when unknown.
  integer function material_type_of(keyword)
    character(len=*), intent(in) :: keyword
    integer :: k
    material_type_of = 0
    do k = 1, size(MODELS)
      if (trim(MODELS(k)%keyword) == keyword) material_type_of = MODELS(k)%type
    end do
  end function material_type_of

  ! The table row of a type, 0 when unknown.
  pure integer function row_of(mtype)
    integer, intent(in) :: mtype
    integer :: k
    row_of = 0
    do k = 1, size(MODELS)
      if (MODELS(k)%type == mtype) row_of = k
    end do
  end function row_of

  function material_keyword(mtype) result(k)
    integer, intent(in) :: mtype
    character(len=4) :: k
    k = '?   '
    if (row_of(mtype) > 0) k = MODELS(row_of(mtype))%keyword
  end function material_keyword

  logical function material_is_fluid(mtype)
    integer, intent(in) :: mtype
    material_is_fluid = .false.
    if (row_of(mtype) > 0) material_is_fluid = MODELS(row_of(mtype))%fluid
  end function material_is_fluid

  logical function material_is_johnson_cook(mtype)
    integer, intent(in) :: mtype
    material_is_johnson_cook = .false.
    if (row_of(mtype) > 0) material_is_johnson_cook = MODELS(row_of(mtype))%johnson_cook
  end function material_is_johnson_cook

  logical function material_is_thermal(mtype)
    integer, intent(in) :: mtype
    material_is_thermal = .false.
    if (row_of(mtype) > 0) material_is_thermal = MODELS(row_of(mtype))%thermal
  end function material_is_thermal

  ! The numbers of a 'mate' card of type mp%type, in deck order, and the checks of the
  ! card's own values (errors name the card's line); current_version: the current version's
  ! card where it differs (null: density, bulk modulus, viscosity).
  subroutine read_material_card(ts, mp, line, current_version)
    type(token_stream), intent(inout) :: ts
    type(material_params), intent(inout) :: mp
    integer, intent(in) :: line
    logical, intent(in) :: current_version
    real(dp) :: et
    if (.not. material_is_fluid(mp%type)) then
      mp%rho0 = ts%real('density')
      mp%young = ts%real("Young's modulus")
      mp%poisson = ts%real("Poisson's ratio")
    end if
    select case (mp%type)
    case (MAT_ELAS, MAT_NEOH)
    case (MAT_PLA1)
      mp%yield0 = ts%real('yield stress')
    case (MAT_PLA2)
      mp%yield0 = ts%real('yield stress')
      et = ts%real('tangent modulus')
      if (.not. (et >= 0.0_dp .and. et < mp%young)) call ts%fail(line, 'tangent modulus must lie in [0, E)')
      mp%hardening = (mp%young * et) / (mp%young - et)
    case (MAT_JOHN, MAT_JCF)
      call read_johnson_cook(ts, mp)
      mp%jc_m = ts%real('m')
      mp%t_room = ts%real('room temperature')
      mp%t_melt = ts%real('melting temperature')
      mp%heat_cap = ts%real('specific heat')
      mp%eps0dot = ts%real('reference strain rate')
      if (mp%type == MAT_JCF) mp%fail_strain = ts%real('failure strain')
      if (.not. (mp%t_melt > mp%t_room)) call ts%fail(line, 'melting temperature must exceed room temperature')
      if (.not. (mp%heat_cap > 0.0_dp)) call ts%fail(line, 'specific heat must be positive')
    case (MAT_SJC, MAT_SJCF)
      call read_johnson_cook(ts, mp)
      mp%eps0dot = ts%real('reference strain rate')
      if (mp%type == MAT_SJCF) mp%fail_strain = ts%real('failure strain')
    case (MAT_HIEX)
      mp%rho0 = ts%real('density')
      mp%wave_speed = ts%real('the detonation velocity')
      mp%det_vel = mp%wave_speed
    case (MAT_NULL)
      mp%rho0 = ts%real('density')
      if (current_version) then
        mp%bulk_modulus = ts%real('the bulk modulus')
        mp%viscosity = ts%real('the viscosity')
        if (.not. (mp%rho0 > 0.0_dp)) call ts%fail(line, 'density must be positive')
        if (.not. (mp%bulk_modulus > 0.0_dp)) call ts%fail(line, 'bulk modulus must be positive')
        if (.not. (mp%viscosity >= 0.0_dp)) call ts%fail(line, 'viscosity must not be negative')
        mp%wave_speed = sqrt(mp%bulk_modulus / mp%rho0)
      else
        mp%wave_speed = ts%real('the wave speed')
      end if
    case (MAT_DPM)
      mp%dp_qphi = ts%real('q_phi')
      mp%dp_kphi = ts%real('k_phi')
      mp%dp_qpsi = ts%real('q_psi')
      mp%dp_tension = ts%real('the tension cut-off')
    end select
  end subroutine read_material_card

  ! The Johnson-Cook flow-stress numbers every JC card starts with.
  subroutine read_johnson_cook(ts, mp)
    type(token_stream), intent(inout) :: ts
    type(material_params), intent(inout) :: mp
    mp%yield0 = ts%real('A')
    mp%hardening = ts%real('B')
    mp%jc_n = ts%real('n')
    mp%jc_c = ts%real('C')
  end subroutine read_johnson_cook

  ! Fills the derived constants of m from the deck values (same operation order as
  ! cxx/materials/material.cpp); returns an error text or ''.
  subroutine material_derive(m, err)
    type(material_params), intent(inout) :: m
    character(len=:), allocatable, intent(out) :: err
    err = ''
    if (.not. (m%rho0 > 0.0_dp)) then
      err = 'density must be positive'
      return
    end if
    if (material_is_fluid(m%type)) then
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

end module mpm3d_material_models
