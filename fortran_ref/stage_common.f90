! stage_common: what the stage files share: step_context (the bind(C) mirror of struct
! StepContext in cxx/stages/update_step.hpp), the patch buffers, the GIMP stencil, the component
! filter of contact and the box-face boundary conditions (index helpers: stage_index.inc).
!
! Every floating-point operation of the stages happens in the same order as in the C++
! stages (cxx/stages/stage_*.cpp): the same patch decomposition, the same canonical assembly order,
! the same skip rules. Indices stored in the shared arrays (cells, particles, slots, offsets,
! material and body numbers) are C's 0-based ones; the Fortran arrays themselves are 1-based.
module mpm3d_stage_common
  use, intrinsic :: iso_c_binding
  use mpm3d_material
  use mpm3d_grid, only: NODE_FIELDS, stencil_27
  use mpm3d_rules, only: step_rules
  implicit none
  private
  public :: step_rules

  integer, parameter, public :: SCHEME_MUSL = 0, SCHEME_USL = 1, SCHEME_USF = 2
  ! The shape-function families (enum TransferFamily, cxx/stages/update_step.hpp): the stages
  ! dispatch on step_context%family; the point-shape families share one scatter, gather and
  ! gradient loop through particle_shape (8 or 27 nodes), sgmp has its own (stage_sg.f90).
  integer, parameter, public :: TRANSFER_TRILINEAR = 0, TRANSFER_STENCIL27 = 1, TRANSFER_SMOOTHED_GRADIENT = 2
  ! Fields of the energy stage's columns: kinetic, internal energy, momentum (3), sum |f.v|.
  integer, parameter, public :: REDUCE_FIELDS = 7

  ! The particles (np) and their materials and bodies (struct StepParticles).
  type, bind(C), public :: step_particles
    ! x, v (3,np); sig (6,np); mass, vol, epeff, ie (np)
    type(c_ptr) :: x = c_null_ptr, v = c_null_ptr, sig = c_null_ptr, mass = c_null_ptr, &
                   vol = c_null_ptr, epeff = c_null_ptr, ie = c_null_ptr
    type(c_ptr) :: temp = c_null_ptr  ! (np) or null: only with thermal Johnson-Cook materials
    type(c_ptr) :: fext = c_null_ptr  ! (3,np) or null: only with point or body loads
    type(c_ptr) :: lx = c_null_ptr  ! (3,np) local cell coordinates, written by the bin stage
    type(c_ptr) :: mat = c_null_ptr, body = c_null_ptr  ! (np) 0-based
    ! (np) base cell index written by the bin stage; -1: outside the grid
    type(c_ptr) :: cell = c_null_ptr
    type(c_ptr) :: gravity = c_null_ptr  ! (3,nbody) or null
    type(c_ptr) :: mats = c_null_ptr  ! (nmat)
    ! (np) lighting time of each particle, or null: only with hiex
    type(c_ptr) :: tlight = c_null_ptr
    ! (np) bulk viscosity pressure of each particle, or null: only with bulk
    type(c_ptr) :: qv = c_null_ptr
    type(c_ptr) :: psize = c_null_ptr  ! (np) GIMP particle half-size lp, or null
    type(c_ptr) :: defgrad = c_null_ptr  ! (9,np) F - I, row-major, or null: only with neoh
    ! (3,np) the positions the bin stage places: x, or the reference ones (TLmp)
    type(c_ptr) :: xbin = c_null_ptr
    type(c_ptr) :: pk1 = c_null_ptr  ! (9,np) V0 P, row-major (TLmp), or null (updated Lagrangian)
    integer(c_int) :: np = 0, nbody = 0, nmat = 0
  end type step_particles

  ! The background grid's window and its node arrays (nnode) (struct StepGrid).
  type, bind(C), public :: step_grid
    ! mass, momentum (3,nnode), force (3,nnode)
    type(c_ptr) :: gmass = c_null_ptr, gmom = c_null_ptr, gforce = c_null_ptr
    ! lower corner of the deck's box (the lattice origin)
    real(c_double) :: origin(3) = 0.0_c_double
    real(c_double) :: h = 0.0_c_double, inv_h = 0.0_c_double, mass_cutoff = 0.0_c_double
    integer(c_int) :: nnode = 0
    integer(c_int) :: nc(3) = 0, nn(3) = 0  ! cells and nodes per axis of the window
    ! first cell of the window on the deck's lattice (adaptive grid)
    integer(c_int) :: cell_off(3) = 0
    integer(c_int) :: fix(6) = 0  ! boundary condition of each box face: 0 free, 1 fixed, 2 symmetry
    ! node layers a held face holds: 1, or 2 (current version, 27 nodes or sgmp)
    integer(c_int) :: fix_layers = 1
  end type step_grid

  ! The patch decomposition: lists, buffers and their sizes (struct StepPatches).
  type, bind(C), public :: step_patches
    ! start (npatch+1), particle list (np), slot (npatch)
    type(c_ptr) :: patch_start = c_null_ptr, patch_part = c_null_ptr, patch_slot = c_null_ptr
    type(c_ptr) :: patch_buf = c_null_ptr  ! the non-empty patches' buffers (kNodeFields per node)
    ! C++ kernels' scratch: (np) patch of each particle during binning
    type(c_ptr) :: pscratch = c_null_ptr
    ! (npatch + 1) prefix sums of the patches' work for thread_patches, or null
    type(c_ptr) :: patch_work = c_null_ptr
    ! C++ kernels' scratch (not used here): the nodes the 27-node scatters touched per buffer
    type(c_ptr) :: patch_box = c_null_ptr
    integer(c_int) :: patch_cells = 0  ! cells per patch edge
    integer(c_int) :: npd(3) = 0  ! patches per axis
    ! patch_halo: node layers a buffer holds beyond its cells
    integer(c_int) :: npatch = 0, nslot = 0, patch_halo = 0
  end type step_patches

  ! The step's time (struct StepClock).
  type, bind(C), public :: step_clock
    ! time: at the end of this step (the burn fraction's clock)
    real(c_double) :: dt = 0.0_c_double, dt_int = 0.0_c_double, time = 0.0_c_double
  end type step_clock

  ! What the deck asks of the step (struct StepMethod).
  type, bind(C), public :: step_method
    ! bulk viscosity coefficients (quadratic, linear); length h
    real(c_double) :: bulk_q1 = 0.0_c_double, bulk_q2 = 0.0_c_double
    ! QuLo: the point loads ramp over this time; Damp: -damping m v (0: off)
    real(c_double) :: load_ramp_time = 0.0_c_double, damping = 0.0_c_double
    integer(c_int) :: scheme = 0  ! SCHEME_MUSL, SCHEME_USL or SCHEME_USF
    integer(c_int) :: has_body_force = 0  ! gravity or loads present: forces carry N * (m g + f_ext)
    integer(c_int) :: uvf = 0  ! 1: volume from det(I + L dt) (UVFp, and always for neoh)
    integer(c_int) :: tl = 0  ! 1: total Lagrangian (TLmp)
    integer(c_int) :: shape = 0  ! 0 trilinear (8 nodes), 1 uGIMP, 2 B-spline (27 nodes)
    integer(c_int) :: sg = 0  ! 1: smoothed-gradient MPM (sgmp)
    ! the shape-function family (TransferFamily), chosen when the deck is bound
    integer(c_int) :: family = 0
  end type step_method

  ! What the energy, bin and contact stages report (struct StepResults).
  type, bind(C), public :: step_results
    ! (kReduceFields, npatch + 1) the energy stage's columns, the last for the particles outside the grid
    type(c_ptr) :: partials = c_null_ptr
    ! energy: kinetic, internal, momentum (3) in 0..4, sum |f.v| in 8; contact: force in 5..7
    real(c_double) :: result(10) = 0.0_c_double
    integer(c_int) :: noutside = 0  ! bin stage: particles outside the grid
  end type step_results

  ! Multi-velocity contact; null / 0 without it (struct StepContact).
  type, bind(C), public :: step_contact
    ! (nbody) contact component (1 or 2) of each body, or null
    type(c_ptr) :: body_comp = c_null_ptr
    type(c_ptr) :: other = c_null_ptr  ! component 2's context, set in component 1's; else null
    type(c_ptr) :: gnormal = c_null_ptr  ! (3,nnode) sum_p m_p grad N_i(x_p) of this component
    ! (kContactFields, npatch) scratch of the contact force and count
    type(c_ptr) :: cpartials = c_null_ptr
    real(c_double) :: contact_mu = 0.0_c_double  ! Coulomb friction coefficient
    integer(c_int) :: only_comp = 0  ! 0: every particle; 1 or 2: this context's component only
    integer(c_int) :: contact_normbody = 0  ! normals from component 1, 2, or 0 (both)
    integer(c_int) :: ncontact = 0  ! contact stage: nodes corrected in this step
  end type step_contact

  ! Smoothed-gradient MPM's state (transfer/smoothed_gradient.cpp); null / 0 otherwise (struct StepSgmp).
  type, bind(C), public :: step_sgmp
    type(c_ptr) :: aux = c_null_ptr  ! (kAuxFields, ncell) the cell centres' fields
    type(c_ptr) :: sg_w = c_null_ptr  ! C++ kernels: each patch-list entry's weights (kSgWeights)
    type(c_ptr) :: sg_cell = c_null_ptr  ! C++ kernels: (np, 8) the centres of the entry's corners
    ! C++ kernels: bits 2a, 2a+1: a corner lies in the patch below, above on axis a
    type(c_ptr) :: sg_reach = c_null_ptr
    ! C++ kernels: nonzero once sg_w and sg_cell hold this bin's weights (2: with sg_reach)
    integer(c_int) :: sg_cached = 0
  end type step_sgmp

  ! Distributed runs (cxx/solver/ranks.hpp); null / 0 with one rank (struct StepRanks).
  type, bind(C), public :: step_ranks
    ! called between a scatter and its assembly, and before the energy and contact columns are folded
    type(c_funptr) :: exchange = c_null_funptr
    type(c_ptr) :: exchange_data = c_null_ptr
    type(c_ptr) :: order = c_null_ptr  ! (np) the particles in one process's storage order, or null
    integer(c_int) :: prebinned = 0  ! 1: cell, lx and pscratch already hold the particles' binning
  end type step_ranks

  ! C++ kernels: patches at rest (docs/ARCHITECTURE.md); null when not looked for (struct StepRest).
  type, bind(C), public :: step_rest
    ! (np) bit 0: the stress update changed nothing; bit 1: G2P changed nothing
    type(c_ptr) :: still = c_null_ptr
    type(c_ptr) :: at_rest = c_null_ptr  ! (npatch) 1 where every stage skips the patch
  end type step_rest

  ! struct StepContext (cxx/stages/update_step.hpp): the groups above, in its order.
  type, bind(C), public :: step_context
    type(step_particles) :: part
    type(step_grid) :: grid
    type(step_patches) :: patch
    type(step_clock) :: clock
    type(step_method) :: method
    type(step_results) :: out
    type(step_contact) :: contact
    type(step_sgmp) :: sgmp
    type(step_ranks) :: ranks
    type(step_rest) :: rest
    type(step_rules) :: rules
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
    qq = c%patch%patch_cells + 1 + 2 * c%patch%patch_halo
    pn = qq * qq * qq
    call c_f_pointer(c%patch%patch_buf, buf, [NODE_FIELDS, pn, c%patch%nslot])
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
    real(dp) :: lp_cells
    ci(1) = mod(cl, c%grid%nc(1))
    ci(2) = mod(cl / c%grid%nc(1), c%grid%nc(2))
    ci(3) = cl / (c%grid%nc(1) * c%grid%nc(2))
    lp_cells = 0.0_dp
    if (c%method%shape == 1) lp_cells = lp * c%grid%inv_h
    call stencil_27(c%method%shape, ci, lxp, c%grid%nc, lp_cells, c%grid%inv_h, o, sn, sg)
  end subroutine gimp_stencil

  ! True when particle p (1-based) belongs to another component than the context's.
  logical function other_component(c, p, body, bcomp)
    type(step_context), intent(in) :: c
    integer, intent(in) :: p
    integer(c_int), intent(in) :: body(:), bcomp(:)
    other_component = .false.
    if (c%contact%only_comp > 0) other_component = bcomp(body(p) + 1) /= c%contact%only_comp
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
    call c_f_pointer(c%part%mass, mass, [c%part%np])
    call c_f_pointer(c%part%v, v, [3, c%part%np])
    call c_f_pointer(c%part%body, body, [c%part%np])
    call c_f_pointer(c%part%gravity, grav, [3, max(c%part%nbody, 1)])
    has_fext = c_associated(c%part%fext)
    if (has_fext) call c_f_pointer(c%part%fext, fext, [3, c%part%np])
    mp = mass(p)
    if (c%method%load_ramp_time > 0.0_dp .or. c%method%damping > 0.0_dp) then
      do a = 1, 3
        f = 0.0_dp
        if (has_fext) then
          if (c%method%load_ramp_time > 0.0_dp .and. c%clock%time < c%method%load_ramp_time) then
            f = (fext(a, p) / c%method%load_ramp_time) * c%clock%time
          else
            f = fext(a, p)
          end if
        end if
        if (c%method%damping > 0.0_dp) f = f - (c%method%damping * mp) * v(a, p)
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
    layers = max(1, c%grid%fix_layers)   ! 0 (unset) means 1
    do face = 0, 5
      kind = c%grid%fix(face + 1)
      if (kind == 0) cycle
      axis = face / 2
      u = mod(axis + 1, 3)
      w = mod(axis + 2, 3)
      do layer = 0, layers - 1
        if (mod(face, 2) == 0) then
          fixed_index = layer
        else
          fixed_index = c%grid%nn(axis + 1) - 1 - layer
        end if
        do jw = 0, c%grid%nn(w + 1) - 1
          do ju = 0, c%grid%nn(u + 1) - 1
            idx(axis) = fixed_index
            idx(u) = ju
            idx(w) = jw
            n = idx(0) + c%grid%nn(1) * (idx(1) + c%grid%nn(2) * idx(2)) + 1
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
    if (.not. c_associated(c%ranks%exchange)) return
    call c_f_procpointer(c%ranks%exchange, hook)
    call hook(c_loc(c), int(kind, c_int), int(first, c_int), int(count, c_int))
  end subroutine rank_exchange

  ! The layout of step_context (its size, then every group's and every member's offset, in
  ! the order of layout_check.cpp) and of material_params (size, eos_e0, eos_type, dp_tension, clay_peak, eos_k1).
  subroutine mpm3d_f_context_layout(out) bind(C, name='mpm3d_f_context_layout')
    integer(c_size_t), intent(out) :: out(123)
    type(step_context), target :: c
    type(material_params), target :: m(2)
    integer(c_intptr_t) :: c0, m0
    c0 = transfer(c_loc(c), 0_c_intptr_t)
    m0 = transfer(c_loc(m(1)), 0_c_intptr_t)
    out(1) = c_sizeof(c)
    out(2) = transfer(c_loc(c%part), 0_c_intptr_t) - c0
    out(3) = transfer(c_loc(c%part%x), 0_c_intptr_t) - c0
    out(4) = transfer(c_loc(c%part%v), 0_c_intptr_t) - c0
    out(5) = transfer(c_loc(c%part%sig), 0_c_intptr_t) - c0
    out(6) = transfer(c_loc(c%part%mass), 0_c_intptr_t) - c0
    out(7) = transfer(c_loc(c%part%vol), 0_c_intptr_t) - c0
    out(8) = transfer(c_loc(c%part%epeff), 0_c_intptr_t) - c0
    out(9) = transfer(c_loc(c%part%ie), 0_c_intptr_t) - c0
    out(10) = transfer(c_loc(c%part%temp), 0_c_intptr_t) - c0
    out(11) = transfer(c_loc(c%part%fext), 0_c_intptr_t) - c0
    out(12) = transfer(c_loc(c%part%lx), 0_c_intptr_t) - c0
    out(13) = transfer(c_loc(c%part%mat), 0_c_intptr_t) - c0
    out(14) = transfer(c_loc(c%part%body), 0_c_intptr_t) - c0
    out(15) = transfer(c_loc(c%part%cell), 0_c_intptr_t) - c0
    out(16) = transfer(c_loc(c%part%gravity), 0_c_intptr_t) - c0
    out(17) = transfer(c_loc(c%part%mats), 0_c_intptr_t) - c0
    out(18) = transfer(c_loc(c%part%tlight), 0_c_intptr_t) - c0
    out(19) = transfer(c_loc(c%part%qv), 0_c_intptr_t) - c0
    out(20) = transfer(c_loc(c%part%psize), 0_c_intptr_t) - c0
    out(21) = transfer(c_loc(c%part%defgrad), 0_c_intptr_t) - c0
    out(22) = transfer(c_loc(c%part%xbin), 0_c_intptr_t) - c0
    out(23) = transfer(c_loc(c%part%pk1), 0_c_intptr_t) - c0
    out(24) = transfer(c_loc(c%part%np), 0_c_intptr_t) - c0
    out(25) = transfer(c_loc(c%part%nbody), 0_c_intptr_t) - c0
    out(26) = transfer(c_loc(c%part%nmat), 0_c_intptr_t) - c0
    out(27) = transfer(c_loc(c%grid), 0_c_intptr_t) - c0
    out(28) = transfer(c_loc(c%grid%gmass), 0_c_intptr_t) - c0
    out(29) = transfer(c_loc(c%grid%gmom), 0_c_intptr_t) - c0
    out(30) = transfer(c_loc(c%grid%gforce), 0_c_intptr_t) - c0
    out(31) = transfer(c_loc(c%grid%origin), 0_c_intptr_t) - c0
    out(32) = transfer(c_loc(c%grid%h), 0_c_intptr_t) - c0
    out(33) = transfer(c_loc(c%grid%inv_h), 0_c_intptr_t) - c0
    out(34) = transfer(c_loc(c%grid%mass_cutoff), 0_c_intptr_t) - c0
    out(35) = transfer(c_loc(c%grid%nnode), 0_c_intptr_t) - c0
    out(36) = transfer(c_loc(c%grid%nc), 0_c_intptr_t) - c0
    out(37) = transfer(c_loc(c%grid%nn), 0_c_intptr_t) - c0
    out(38) = transfer(c_loc(c%grid%cell_off), 0_c_intptr_t) - c0
    out(39) = transfer(c_loc(c%grid%fix), 0_c_intptr_t) - c0
    out(40) = transfer(c_loc(c%grid%fix_layers), 0_c_intptr_t) - c0
    out(41) = transfer(c_loc(c%patch), 0_c_intptr_t) - c0
    out(42) = transfer(c_loc(c%patch%patch_start), 0_c_intptr_t) - c0
    out(43) = transfer(c_loc(c%patch%patch_part), 0_c_intptr_t) - c0
    out(44) = transfer(c_loc(c%patch%patch_slot), 0_c_intptr_t) - c0
    out(45) = transfer(c_loc(c%patch%patch_buf), 0_c_intptr_t) - c0
    out(46) = transfer(c_loc(c%patch%pscratch), 0_c_intptr_t) - c0
    out(47) = transfer(c_loc(c%patch%patch_work), 0_c_intptr_t) - c0
    out(48) = transfer(c_loc(c%patch%patch_box), 0_c_intptr_t) - c0
    out(49) = transfer(c_loc(c%patch%patch_cells), 0_c_intptr_t) - c0
    out(50) = transfer(c_loc(c%patch%npd), 0_c_intptr_t) - c0
    out(51) = transfer(c_loc(c%patch%npatch), 0_c_intptr_t) - c0
    out(52) = transfer(c_loc(c%patch%nslot), 0_c_intptr_t) - c0
    out(53) = transfer(c_loc(c%patch%patch_halo), 0_c_intptr_t) - c0
    out(54) = transfer(c_loc(c%clock), 0_c_intptr_t) - c0
    out(55) = transfer(c_loc(c%clock%dt), 0_c_intptr_t) - c0
    out(56) = transfer(c_loc(c%clock%dt_int), 0_c_intptr_t) - c0
    out(57) = transfer(c_loc(c%clock%time), 0_c_intptr_t) - c0
    out(58) = transfer(c_loc(c%method), 0_c_intptr_t) - c0
    out(59) = transfer(c_loc(c%method%bulk_q1), 0_c_intptr_t) - c0
    out(60) = transfer(c_loc(c%method%bulk_q2), 0_c_intptr_t) - c0
    out(61) = transfer(c_loc(c%method%load_ramp_time), 0_c_intptr_t) - c0
    out(62) = transfer(c_loc(c%method%damping), 0_c_intptr_t) - c0
    out(63) = transfer(c_loc(c%method%scheme), 0_c_intptr_t) - c0
    out(64) = transfer(c_loc(c%method%has_body_force), 0_c_intptr_t) - c0
    out(65) = transfer(c_loc(c%method%uvf), 0_c_intptr_t) - c0
    out(66) = transfer(c_loc(c%method%tl), 0_c_intptr_t) - c0
    out(67) = transfer(c_loc(c%method%shape), 0_c_intptr_t) - c0
    out(68) = transfer(c_loc(c%method%sg), 0_c_intptr_t) - c0
    out(69) = transfer(c_loc(c%method%family), 0_c_intptr_t) - c0
    out(70) = transfer(c_loc(c%out), 0_c_intptr_t) - c0
    out(71) = transfer(c_loc(c%out%partials), 0_c_intptr_t) - c0
    out(72) = transfer(c_loc(c%out%result), 0_c_intptr_t) - c0
    out(73) = transfer(c_loc(c%out%noutside), 0_c_intptr_t) - c0
    out(74) = transfer(c_loc(c%contact), 0_c_intptr_t) - c0
    out(75) = transfer(c_loc(c%contact%body_comp), 0_c_intptr_t) - c0
    out(76) = transfer(c_loc(c%contact%other), 0_c_intptr_t) - c0
    out(77) = transfer(c_loc(c%contact%gnormal), 0_c_intptr_t) - c0
    out(78) = transfer(c_loc(c%contact%cpartials), 0_c_intptr_t) - c0
    out(79) = transfer(c_loc(c%contact%contact_mu), 0_c_intptr_t) - c0
    out(80) = transfer(c_loc(c%contact%only_comp), 0_c_intptr_t) - c0
    out(81) = transfer(c_loc(c%contact%contact_normbody), 0_c_intptr_t) - c0
    out(82) = transfer(c_loc(c%contact%ncontact), 0_c_intptr_t) - c0
    out(83) = transfer(c_loc(c%sgmp), 0_c_intptr_t) - c0
    out(84) = transfer(c_loc(c%sgmp%aux), 0_c_intptr_t) - c0
    out(85) = transfer(c_loc(c%sgmp%sg_w), 0_c_intptr_t) - c0
    out(86) = transfer(c_loc(c%sgmp%sg_cell), 0_c_intptr_t) - c0
    out(87) = transfer(c_loc(c%sgmp%sg_reach), 0_c_intptr_t) - c0
    out(88) = transfer(c_loc(c%sgmp%sg_cached), 0_c_intptr_t) - c0
    out(89) = transfer(c_loc(c%ranks), 0_c_intptr_t) - c0
    out(90) = transfer(c_loc(c%ranks%exchange), 0_c_intptr_t) - c0
    out(91) = transfer(c_loc(c%ranks%exchange_data), 0_c_intptr_t) - c0
    out(92) = transfer(c_loc(c%ranks%order), 0_c_intptr_t) - c0
    out(93) = transfer(c_loc(c%ranks%prebinned), 0_c_intptr_t) - c0
    out(94) = transfer(c_loc(c%rest), 0_c_intptr_t) - c0
    out(95) = transfer(c_loc(c%rest%still), 0_c_intptr_t) - c0
    out(96) = transfer(c_loc(c%rest%at_rest), 0_c_intptr_t) - c0
    out(97) = c_sizeof(m(1))
    out(98) = transfer(c_loc(m(1)%eos_e0), 0_c_intptr_t) - m0
    out(99) = transfer(c_loc(m(1)%eos_type), 0_c_intptr_t) - m0
    out(100) = transfer(c_loc(m(1)%dp_tension), 0_c_intptr_t) - m0
    out(101) = transfer(c_loc(c%rules), 0_c_intptr_t) - c0
    out(102) = transfer(c_loc(c%rules%program), 0_c_intptr_t) - c0
    out(103) = transfer(c_loc(c%rules%time_step), 0_c_intptr_t) - c0
    out(104) = transfer(c_loc(c%rules%bulk_book), 0_c_intptr_t) - c0
    out(105) = transfer(c_loc(c%rules%bulk_switch), 0_c_intptr_t) - c0
    out(106) = transfer(c_loc(c%rules%bulk_linear), 0_c_intptr_t) - c0
    out(107) = transfer(c_loc(c%rules%burn), 0_c_intptr_t) - c0
    out(108) = transfer(c_loc(c%rules%dp_return), 0_c_intptr_t) - c0
    out(109) = transfer(c_loc(c%rules%deck_reals), 0_c_intptr_t) - c0
    out(110) = transfer(c_loc(c%rules%tl_shape), 0_c_intptr_t) - c0
    out(111) = transfer(c_loc(c%rules%sg_lower), 0_c_intptr_t) - c0
    out(112) = transfer(c_loc(c%rules%sg_beyond), 0_c_intptr_t) - c0
    out(113) = transfer(c_loc(c%rules%fluid_viscous), 0_c_intptr_t) - c0
    out(114) = transfer(c_loc(c%rules%bulk_work), 0_c_intptr_t) - c0
    out(115) = transfer(c_loc(c%rules%pressure_q), 0_c_intptr_t) - c0
    out(116) = transfer(c_loc(c%rules%clay_return), 0_c_intptr_t) - c0
    out(117) = transfer(c_loc(m(1)%clay_peak), 0_c_intptr_t) - m0
    out(118) = transfer(c_loc(c%rules%null_eos), 0_c_intptr_t) - c0
    out(119) = transfer(c_loc(m(1)%eos_k1), 0_c_intptr_t) - m0
    out(120) = transfer(c_loc(c%rules%start_temp), 0_c_intptr_t) - c0
    out(121) = transfer(c_loc(m(1)%p_min), 0_c_intptr_t) - m0
    out(122) = transfer(c_loc(m(1)%has_p_min), 0_c_intptr_t) - m0
    out(123) = transfer(c_loc(c%rules%contact), 0_c_intptr_t) - c0
  end subroutine mpm3d_f_context_layout

end module mpm3d_stage_common
