! The material models, one entry each (as cxx/materials/material_models.cpp): the deck keyword of
! the 'mate' card, the type, what kind of solid or fluid it is, and the derived constants. The
! deck reader (read_material_card in data_in_cards.f90: the card's numbers in deck order, with
! the checks of their values) asks this module; the stress update of a type is in its family's
! module (eos.f90, j2_plasticity.f90, drucker_prager.f90, neo_hookean.f90), which stress_update
! in constitution.f90 dispatches to. Adding a model: a MAT_ value (material.f90, and
! cxx/materials/material.hpp), one row in MODELS here and one case in read_material_card, its
! stress update (a family module and its branch in constitution.f90), and the same in C++.
module mpm3d_material_models
  use mpm3d_material
  implicit none
  private

  type :: material_model_t
    character(len=4) :: keyword
    integer :: type
    logical :: fluid         ! no shear stiffness: pressure from its EOS only (hiex, null)
    logical :: johnson_cook  ! Johnson-Cook flow stress (n, C, reference strain rate checked)
    logical :: thermal       ! tracks temperature
  end type material_model_t

  type(material_model_t), parameter :: MODELS(12) = [ &
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
    material_model_t('neoh', MAT_NEOH, .false., .false., .false.), &
    material_model_t('clay', MAT_CLAY, .false., .false., .false.)]

  public :: material_type_of, material_keyword, material_is_fluid, material_is_johnson_cook, &
            material_is_thermal, material_derive

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
    if (m%type == MAT_CLAY) then
      if (.not. (m%clay_residual >= 0.0_dp) .or. .not. (m%clay_peak >= m%clay_residual)) then
        err = 'clay strengths need 0 <= residual kappa_r <= peak kappa_p'
        return
      end if
      if (.not. (m%clay_softening >= 0.0_dp)) then
        err = 'clay softening coefficient eta must not be negative'
        return
      end if
      ! The steepest softening slope (at epeff = 0) below 3G: else no unique return.
      if (.not. (m%clay_softening * (m%clay_peak - m%clay_residual) < 3.0_dp * m%shear)) then
        err = 'clay softening eta (kappa_p - kappa_r) must be below 3G = E / (1 + nu)'
        return
      end if
    end if
  end subroutine material_derive

end module mpm3d_material_models
