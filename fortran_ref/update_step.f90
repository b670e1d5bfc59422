! update_step: the stages of the Fortran reference by identifier: the identifiers (enum Stage
! of cxx/stages/step_order.h), run_stage, which calls a stage by identifier, and the interfaces of
! the step table of cxx/stages/step_order.c that mpm3d_ref walks; re-exports the bind(C) stages (one
! stage_*.f90 file each) and step_context for mpm3d_ref and data_in.
module mpm3d_update_step
  use, intrinsic :: iso_c_binding, only: c_int
  use mpm3d_stage_common, only: step_context, SCHEME_MUSL, SCHEME_USL, SCHEME_USF, REDUCE_FIELDS, &
                                TRANSFER_TRILINEAR, TRANSFER_STENCIL27, TRANSFER_SMOOTHED_GRADIENT, &
                                mpm3d_f_context_layout
  use mpm3d_stage_bin, only: mpm3d_f_bin
  use mpm3d_stage_p2g, only: mpm3d_f_p2g, mpm3d_f_forces
  use mpm3d_stage_grid, only: mpm3d_f_integrate, mpm3d_f_contact, mpm3d_f_recontact
  use mpm3d_stage_g2p, only: mpm3d_f_g2p
  use mpm3d_stage_stress, only: mpm3d_f_stress
  use mpm3d_stage_energy, only: mpm3d_f_energy
  implicit none
  private

  ! data_in.f90 and mpm3d_ref.f90 take these from here.
  public :: step_context, SCHEME_MUSL, SCHEME_USL, SCHEME_USF, REDUCE_FIELDS
  public :: mpm3d_f_bin, mpm3d_f_p2g, mpm3d_f_forces, mpm3d_f_integrate, mpm3d_f_g2p, &
            mpm3d_f_stress, mpm3d_f_energy, mpm3d_f_contact, mpm3d_f_recontact
  public :: mpm3d_f_context_layout

  ! Stage identifiers, the values of enum Stage in cxx/stages/step_order.h (checked by fref_layout).
  integer, parameter, public :: ST_BIN = 0, ST_P2G = 1, ST_FORCES = 2, ST_INTEGRATE = 3, &
                                ST_G2P = 4, ST_STRESS = 5, ST_ENERGY = 6, ST_CONTACT = 7, &
                                ST_RECONTACT = 8, ST_COUNT = 9
  public :: run_stage, mpm3d_f_step_constants, mpm3d_step_order, mpm3d_stage_needs_contact, mpm3d_stage_per_component

  ! The step table (cxx/stages/step_order.h): the longest row, a scheme's row, which stages run
  ! only with contact and which run on each component's context.
  integer, parameter, public :: MPM3D_MAX_STEP_STAGES = 16
  interface
    integer(c_int) function mpm3d_step_order(scheme, order) bind(C, name='mpm3d_step_order')
      import :: c_int
      integer(c_int), value :: scheme
      integer(c_int), intent(out) :: order(*)
    end function mpm3d_step_order
    integer(c_int) function mpm3d_stage_needs_contact(stage) bind(C, name='mpm3d_stage_needs_contact')
      import :: c_int
      integer(c_int), value :: stage
    end function mpm3d_stage_needs_contact
    integer(c_int) function mpm3d_stage_per_component(stage) bind(C, name='mpm3d_stage_per_component')
      import :: c_int
      integer(c_int), value :: stage
    end function mpm3d_stage_per_component
  end interface

contains

  ! Runs stage id on one context.
  subroutine run_stage(id, c)
    integer, intent(in) :: id
    type(step_context), intent(inout), target :: c
    select case (id)
    case (ST_BIN)
      call mpm3d_f_bin(c)
    case (ST_P2G)
      call mpm3d_f_p2g(c)
    case (ST_FORCES)
      call mpm3d_f_forces(c)
    case (ST_INTEGRATE)
      call mpm3d_f_integrate(c)
    case (ST_G2P)
      call mpm3d_f_g2p(c)
    case (ST_STRESS)
      call mpm3d_f_stress(c)
    case (ST_ENERGY)
      call mpm3d_f_energy(c)
    case (ST_CONTACT)
      call mpm3d_f_contact(c)
    case (ST_RECONTACT)
      call mpm3d_f_recontact(c)
    case default
      error stop 'mpm3d_update_step: unknown stage'
    end select
  end subroutine run_stage

  ! The identifiers this module and stage_common repeat from cxx/stages/step_order.h, for the
  ! layout check: the stages in order, ST_COUNT, the schemes, the longest row.
  subroutine mpm3d_f_step_constants(out) bind(C, name='mpm3d_f_step_constants')
    integer(c_int), intent(out) :: out(17)
    out = [ST_BIN, ST_P2G, ST_FORCES, ST_INTEGRATE, ST_G2P, ST_STRESS, ST_ENERGY, ST_CONTACT, &
           ST_RECONTACT, ST_COUNT, SCHEME_MUSL, SCHEME_USL, SCHEME_USF, MPM3D_MAX_STEP_STAGES, &
           TRANSFER_TRILINEAR, TRANSFER_STENCIL27, TRANSFER_SMOOTHED_GRADIENT]
  end subroutine mpm3d_f_step_constants

end module mpm3d_update_step
