! stage_common: what the stage files share: step_context (the bind(C) mirror of struct
! StepContext in cxx/stages/update_step.hpp), the patch buffers, the GIMP stencil, the component
! filter of contact and the box-face boundary conditions (index helpers: stage_index.inc).
!
! Every floating-point operation of the stages happens in the same order as in the C++
! stages (cxx/stage_*.cpp): the same patch decomposition, the same canonical assembly order,
! the same skip rules. Indices stored in the shared arrays (cells, particles, slots, offsets,
! material and body numbers) are C's 0-based ones; the Fortran arrays themselves are 1-based.
module mpm3d_stage_common
  use, intrinsic :: iso_c_binding
  use mpm3d_material
  use mpm3d_grid, only: NODE_FIELDS, shape_gimp, gimp_offset, shape_bspline, bspline_offset
  implicit none
  private

  integer, parameter, public :: SCHEME_MUSL = 0, SCHEME_USL = 1, SCHEME_USF = 2
  ! The shape-function families (enum TransferFamily, cxx/stages/update_step.hpp): the stages
  ! dispatch on step_context%family; the point-shape families share one scatter, gather and
  ! gradient loop through particle_shape (8 or 27 nodes), sgmp has its own (stage_sg.f90).
  integer, parameter, public :: TRANSFER_TRILINEAR = 0, TRANSFER_STENCIL27 = 1, TRANSFER_SMOOTHED_GRADIENT = 2
  ! Fields of the energy stage's columns: kinetic, internal energy, momentum (3), sum |f.v|.
  integer, parameter, public :: REDUCE_FIELDS = 6

  type, bind(C), public :: step_context
    ! Particles (np): x, v (3,np); sig (6,np); scalars (np).
    type(c_ptr) :: x = c_null_ptr, v = c_null_ptr, sig = c_null_ptr, mass = c_null_ptr, &
                   vol = c_null_ptr, epeff = c_null_ptr, ie = c_null_ptr
    type(c_ptr) :: temp = c_null_ptr      ! (np) or null
    type(c_ptr) :: fext = c_null_ptr      ! (3,np) or null
    type(c_ptr) :: lx = c_null_ptr        ! (3,np) local cell coordinates (bin stage)
    type(c_ptr) :: mat = c_null_ptr, body = c_null_ptr   ! int (np), 0-based
    type(c_ptr) :: cell = c_null_ptr      ! int (np), 0-based base cell, -1 outside
    type(c_ptr) :: gravity = c_null_ptr   ! (3,nbody) or null
    type(c_ptr) :: mats = c_null_ptr      ! material_params (nmat)
    ! Grid nodes (nnode).
    type(c_ptr) :: gmass = c_null_ptr, gmom = c_null_ptr, gforce = c_null_ptr
    ! Patches: start (npatch+1), particle list (np), slot (npatch), buffers.
    type(c_ptr) :: patch_start = c_null_ptr, patch_part = c_null_ptr, patch_slot = c_null_ptr
    type(c_ptr) :: patch_buf = c_null_ptr
    type(c_ptr) :: partials = c_null_ptr  ! (REDUCE_FIELDS, npatch + 1) columns of the energy stage
    ! Energy stage: kinetic, internal, momentum (3) in 1..5, sum |f.v| in 9; contact: force in 6..8.
    real(c_double) :: result(9) = 0.0_dp
    real(c_double) :: origin(3) = 0.0_dp
    real(c_double) :: h = 0.0_dp, inv_h = 0.0_dp, dt = 0.0_dp, dt_int = 0.0_dp, mass_cutoff = 0.0_dp
    integer(c_int) :: np = 0, nbody = 0, nmat = 0, nnode = 0
    integer(c_int) :: nc(3) = 0, nn(3) = 0
    integer(c_int) :: patch_cells = 0, npd(3) = 0, npatch = 0, nslot = 0
    integer(c_int) :: fix(6) = 0
    integer(c_int) :: scheme = 0
    integer(c_int) :: has_body_force = 0
    integer(c_int) :: noutside = 0
    ! Explosives and bulk viscosity (stress stage only).
    type(c_ptr) :: tlight = c_null_ptr    ! (np) lighting times, or null (only with hiex)
    type(c_ptr) :: qv = c_null_ptr        ! (np) bulk viscosity pressures, or null (only with bulk)
    real(c_double) :: time = 0.0_dp       ! time at the end of this step
    real(c_double) :: bulk_q1 = 0.0_dp, bulk_q2 = 0.0_dp
    integer(c_int) :: cell_off(3) = 0     ! first cell of the grid window on the deck's lattice
    ! GIMP and multi-velocity contact (issue 5); null / 0 when the deck does not use them.
    type(c_ptr) :: psize = c_null_ptr      ! (np) GIMP particle half-size lp
    type(c_ptr) :: body_comp = c_null_ptr  ! int (nbody) contact component (1 or 2) of each body
    type(c_ptr) :: other = c_null_ptr      ! contact: component 2's step_context (in component 1's)
    type(c_ptr) :: gnormal = c_null_ptr    ! contact: (3,nnode) sum_p m_p grad N_i(x_p), this component
    type(c_ptr) :: cpartials = c_null_ptr  ! contact: (4,npatch) scratch of the contact force and count
    real(c_double) :: contact_mu = 0.0_dp  ! Coulomb friction coefficient
    integer(c_int) :: shape = 0            ! 0 trilinear, 1 uGIMP, 2 B-spline
    integer(c_int) :: patch_halo = 0       ! node layers a buffer holds beyond its cells: 0, 1
    integer(c_int) :: only_comp = 0        ! 0 every particle; 1 or 2 this component only
    integer(c_int) :: contact_normbody = 0 ! normals from component 1, 2, or 0 (both)
    integer(c_int) :: ncontact = 0         ! contact stage: nodes corrected
    type(c_ptr) :: defgrad = c_null_ptr    ! (9,np) F - I (row-major) of each particle: neoh only
    integer(c_int) :: uvf = 0              ! 1: volume from det(I + L dt) (UVFp, neoh)
    real(c_double) :: load_ramp_time = 0.0_c_double   ! QuLo: loads ramp over this time; 0 off
    real(c_double) :: damping = 0.0_c_double          ! Damp: -damping m v in the body force
    type(c_ptr) :: xbin = c_null_ptr       ! positions the bin stage places: x, or the reference ones (TLmp)
    type(c_ptr) :: pk1 = c_null_ptr        ! (9,np) V0 P (TLmp), or null
    integer(c_int) :: tl = 0               ! 1: total Lagrangian MPM
    integer(c_int) :: fix_layers = 1       ! node layers a fixed face holds: 1, or 2 (current
                                           ! version with 27-node stencils or sgmp)
    type(c_ptr) :: aux = c_null_ptr        ! sgmp: (32, ncell) the cell centres' fields
    integer(c_int) :: sg = 0               ! 1: smoothed-gradient MPM (stage_sg.f90)
    integer(c_int) :: family = 0           ! the shape-function family (TRANSFER_*, update_step.hpp)
    ! The C++ kernels' scratch (not used here): pscratch, then sgmp's sg_w, sg_cell, sg_reach.
    type(c_ptr) :: pscratch = c_null_ptr, sg_w = c_null_ptr, sg_cell = c_null_ptr, sg_reach = c_null_ptr
    ! Distributed runs (cxx/parallel/ranks.hpp; null with one rank): the ranks' hook, called between a
    ! scatter into the patch buffers and their assembly, and before the energy and contact
    ! columns are folded (rank_exchange); the particles in one process's storage order
    ! (int (np), 0-based), in which the bin stage fills the lists and the energy stage sums
    ! the particles outside the grid; prebinned: cell and lx already hold the particles'
    ! binning (the same values this bin stage computes).
    type(c_funptr) :: exchange = c_null_funptr
    type(c_ptr) :: exchange_data = c_null_ptr
    type(c_ptr) :: order = c_null_ptr
    integer(c_int) :: prebinned = 0
    ! The C++ kernels' scratch (not used here): sgmp's weights written since the last bin.
    integer(c_int) :: sg_cached = 0
    ! The C++ kernels' scratch (not used here): sgmp's patches at rest and the work shares.
    type(c_ptr) :: sg_still = c_null_ptr, sg_rest = c_null_ptr, patch_work = c_null_ptr
  end type step_context

  ! step_context%exchange's kinds (cxx/stages/update_step.hpp ExchangeKind).
  integer, parameter, public :: EXCHANGE_BUFFERS = 0, EXCHANGE_PARTIALS = 1, EXCHANGE_CONTACT = 2
  abstract interface
    subroutine exchange_hook(c, kind, first, count) bind(C)
      import :: c_ptr, c_int
      type(c_ptr), value :: c
      integer(c_int), value :: kind, first, count
    end subroutine exchange_hook
  end interface

  public :: view_buffers, gimp_stencil, rank_exchange
  public :: other_component, apply_bc, particle_body_force
  public :: mpm3d_f_context_layout

contains

  ! The patch buffers (NODE_FIELDS, patch_nodes, nslot); only called with nslot > 0.
  subroutine view_buffers(c, buf)
    type(step_context), intent(in) :: c
    real(dp), pointer, intent(out) :: buf(:,:,:)
    integer :: qq, pn
    qq = c%patch_cells + 1 + 2 * c%patch_halo
    pn = qq * qq * qq
    call c_f_pointer(c%patch_buf, buf, [NODE_FIELDS, pn, c%nslot])
  end subroutine view_buffers

  ! 27-node stencil (shape 1 GIMP, 2 B-spline; lp is only read with GIMP) of particle p
  ! (1-based): cell indices ci (0-based), offsets o, weights and gradients of the 27 nodes
  ! (cxx gimp_stencil).
  subroutine gimp_stencil(c, cl, lxp, lp, ci, o, sn, sg)
    type(step_context), intent(in) :: c
    integer, intent(in) :: cl
    real(dp), intent(in) :: lxp(3), lp
    integer, intent(out) :: ci(3), o(3)
    real(dp), intent(out) :: sn(27), sg(3, 27)
    integer :: a
    ci(1) = mod(cl, c%nc(1))
    ci(2) = mod(cl / c%nc(1), c%nc(2))
    ci(3) = cl / (c%nc(1) * c%nc(2))
    if (c%shape == 2) then
      do a = 1, 3
        o(a) = bspline_offset(ci(a))
      end do
      call shape_bspline(lxp, o, c%inv_h, sn, sg)
      return
    end if
    do a = 1, 3
      o(a) = gimp_offset(lxp(a), ci(a), c%nc(a))
    end do
    call shape_gimp(lxp, o, lp * c%inv_h, c%inv_h, sn, sg)
  end subroutine gimp_stencil

  ! True when particle p (1-based) belongs to another component than the context's.
  logical function other_component(c, p, body, bcomp)
    type(step_context), intent(in) :: c
    integer, intent(in) :: p
    integer(c_int), intent(in) :: body(:), bcomp(:)
    other_component = .false.
    if (c%only_comp > 0) other_component = bcomp(body(p) + 1) /= c%only_comp
  end function other_component

  ! The body force of particle p (1-based; cxx particle_body_force): the point load (ramped
  ! with QuLo), the damping (Damp), gravity.
  subroutine particle_body_force(c, p, fb)
    type(step_context), intent(in) :: c
    integer, intent(in) :: p
    real(dp), intent(out) :: fb(3)
    real(dp), pointer :: mass(:), v(:,:), fext(:,:), grav(:,:)
    integer(c_int), pointer :: body(:)
    real(dp) :: mp, f
    integer :: a
    logical :: has_fext
    call c_f_pointer(c%mass, mass, [c%np])
    call c_f_pointer(c%v, v, [3, c%np])
    call c_f_pointer(c%body, body, [c%np])
    call c_f_pointer(c%gravity, grav, [3, max(c%nbody, 1)])
    has_fext = c_associated(c%fext)
    if (has_fext) call c_f_pointer(c%fext, fext, [3, c%np])
    mp = mass(p)
    if (c%load_ramp_time > 0.0_dp .or. c%damping > 0.0_dp) then
      do a = 1, 3
        f = 0.0_dp
        if (has_fext) then
          if (c%load_ramp_time > 0.0_dp .and. c%time < c%load_ramp_time) then
            f = (fext(a, p) / c%load_ramp_time) * c%time
          else
            f = fext(a, p)
          end if
        end if
        if (c%damping > 0.0_dp) f = f - (c%damping * mp) * v(a, p)
        fb(a) = f + mp * grav(a, body(p) + 1)
      end do
    else
      do a = 1, 3
        fb(a) = mp * grav(a, body(p) + 1)
        if (has_fext) fb(a) = fb(a) + fext(a, p)
      end do
    end if
  end subroutine particle_body_force

  ! The boundary conditions live here rather than with the grid update (stage_grid.f90)
  ! because P2G, G2P (MUSL remap) and contact apply them too.
  ! Boundary conditions of the box faces on a nodal vector field (3,nnode):
  ! 1 fixed (all components zero), otherwise symmetry (normal component zero).
  subroutine apply_bc(c, a)
    type(step_context), intent(in) :: c
    real(dp), intent(inout) :: a(:,:)
    integer :: face, kind, axis, fixed_index, u, w, ju, jw, n, layer, layers
    integer :: idx(0:2)
    layers = max(1, c%fix_layers)   ! 0 (unset) means 1
    do face = 0, 5
      kind = c%fix(face + 1)
      if (kind == 0) cycle
      axis = face / 2
      u = mod(axis + 1, 3)
      w = mod(axis + 2, 3)
      do layer = 0, layers - 1
        if (mod(face, 2) == 0) then
          fixed_index = layer
        else
          fixed_index = c%nn(axis + 1) - 1 - layer
        end if
        do jw = 0, c%nn(w + 1) - 1
          do ju = 0, c%nn(u + 1) - 1
            idx(axis) = fixed_index
            idx(u) = ju
            idx(w) = jw
            n = idx(0) + c%nn(1) * (idx(1) + c%nn(2) * idx(2)) + 1
            if (kind == 1) then
              a(1, n) = 0.0_dp
              a(2, n) = 0.0_dp
              a(3, n) = 0.0_dp
            else
              a(axis + 1, n) = 0.0_dp
            end if
          end do
        end do
      end do
    end do
  end subroutine apply_bc

  ! The ranks' hook of a distributed run (nothing with one process): kind EXCHANGE_BUFFERS
  ! gives the ghost patches' buffers fields first..first+count-1 (0-based) their owners' sums,
  ! the others every rank's energy or contact columns.
  subroutine rank_exchange(c, kind, first, count)
    type(step_context), intent(in), target :: c
    integer, intent(in) :: kind, first, count
    procedure(exchange_hook), pointer :: hook
    if (.not. c_associated(c%exchange)) return
    call c_f_procpointer(c%exchange, hook)
    call hook(c_loc(c), int(kind, c_int), int(first, c_int), int(count, c_int))
  end subroutine rank_exchange

  ! Layout of step_context and material_params as this compiler sees them (for the
  ! layout test against the C structs): sizes and a few offsets, in bytes.
  subroutine mpm3d_f_context_layout(out) bind(C, name='mpm3d_f_context_layout')
    integer(c_size_t), intent(out) :: out(26)
    type(step_context), target :: c
    type(material_params), target :: m(2)
    out(1) = c_sizeof(c)
    out(2) = transfer(c_loc(c%result), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(3) = transfer(c_loc(c%np), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(4) = transfer(c_loc(c%fix), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(5) = transfer(c_loc(c%noutside), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(6) = c_sizeof(m(1))
    out(7) = transfer(c_loc(m(1)%eos_e0), 0_c_intptr_t) - transfer(c_loc(m(1)), 0_c_intptr_t)
    out(8) = transfer(c_loc(m(1)%eos_type), 0_c_intptr_t) - transfer(c_loc(m(1)), 0_c_intptr_t)
    out(9) = transfer(c_loc(c%bulk_q2), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(10) = transfer(c_loc(m(1)%dp_tension), 0_c_intptr_t) - transfer(c_loc(m(1)), 0_c_intptr_t)
    out(11) = transfer(c_loc(c%cell_off), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(12) = transfer(c_loc(c%psize), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(13) = transfer(c_loc(c%ncontact), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(14) = transfer(c_loc(c%defgrad), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(15) = transfer(c_loc(c%uvf), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(16) = transfer(c_loc(c%damping), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(17) = transfer(c_loc(c%tl), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(18) = transfer(c_loc(c%fix_layers), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(19) = transfer(c_loc(c%aux), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(20) = transfer(c_loc(c%sg), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(21) = transfer(c_loc(c%exchange), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(22) = transfer(c_loc(c%order), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(23) = transfer(c_loc(c%prebinned), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(24) = transfer(c_loc(c%sg_cached), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(25) = transfer(c_loc(c%patch_work), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(26) = transfer(c_loc(c%family), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
  end subroutine mpm3d_f_context_layout

end module mpm3d_stage_common
