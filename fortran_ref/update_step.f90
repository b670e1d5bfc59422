! update_step: the stages of one explicit MPM time step, Fortran reference versions.
! Each stage is a bind(C) subroutine taking one step_context by reference, the mirror of
! struct StepContext in cxx/update_step.hpp, so any stage can come from either language.
! Every floating-point operation happens in the same order as in cxx/update_step.cpp:
! the same patch decomposition, the same canonical assembly order, the same skip rules.
! Indices stored in the shared arrays (cells, particles, slots, offsets, material and body
! numbers) are C's 0-based ones; the Fortran arrays themselves are 1-based.
module mpm3d_update_step
  use, intrinsic :: iso_c_binding
  use mpm3d_material
  use mpm3d_grid, only: NODE_FIELDS, shape_linear, shape_gimp, gimp_offset
  use mpm3d_constitution, only: stress_update, burn_fraction
  implicit none
  private

  integer, parameter, public :: SCHEME_MUSL = 0, SCHEME_USL = 1, SCHEME_USF = 2
  integer, parameter, public :: REDUCE_FIELDS = 5

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
    type(c_ptr) :: partials = c_null_ptr  ! (REDUCE_FIELDS, nblock)
    real(c_double) :: result(8) = 0.0_dp  ! energy stage: kinetic, internal, momentum (3)
    real(c_double) :: origin(3) = 0.0_dp
    real(c_double) :: h = 0.0_dp, inv_h = 0.0_dp, dt = 0.0_dp, dt_int = 0.0_dp, mass_cutoff = 0.0_dp
    integer(c_int) :: np = 0, nbody = 0, nmat = 0, nnode = 0
    integer(c_int) :: nc(3) = 0, nn(3) = 0
    integer(c_int) :: patch_cells = 0, npd(3) = 0, npatch = 0, nslot = 0
    integer(c_int) :: fix(6) = 0
    integer(c_int) :: scheme = 0
    integer(c_int) :: has_body_force = 0
    integer(c_int) :: noutside = 0
    integer(c_int) :: reduce_block = 0
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
    type(c_ptr) :: cpartials = c_null_ptr  ! contact: (3,npatch) scratch of the contact-force sum
    real(c_double) :: contact_mu = 0.0_dp  ! Coulomb friction coefficient
    integer(c_int) :: shape = 0            ! 0 trilinear, 1 uGIMP
    integer(c_int) :: patch_halo = 0       ! node layers a buffer holds beyond its cells: 0, 1
    integer(c_int) :: only_comp = 0        ! 0 every particle; 1 or 2 this component only
    integer(c_int) :: contact_normbody = 0 ! normals from component 1, 2, or 0 (both)
    integer(c_int) :: ncontact = 0         ! contact stage: nodes corrected
  end type step_context

  public :: mpm3d_f_bin, mpm3d_f_p2g, mpm3d_f_forces, mpm3d_f_integrate, mpm3d_f_g2p, &
            mpm3d_f_stress, mpm3d_f_energy, mpm3d_f_contact, mpm3d_f_recontact
  public :: mpm3d_f_context_layout

contains

  ! ------------------------------------------------------------------ helpers

  ! Global node index (0-based) of the base node of a cell (0-based).
  pure integer function base_node(c, cell)
    type(step_context), intent(in) :: c
    integer, intent(in) :: cell
    integer :: i, j, k
    i = mod(cell, c%nc(1))
    j = mod(cell / c%nc(1), c%nc(2))
    k = cell / (c%nc(1) * c%nc(2))
    base_node = i + c%nn(1) * (j + c%nn(2) * k)
  end function base_node

  ! Global node index (0-based) of local node k (0..7) relative to a base node.
  pure integer function node_of(c, base, k)
    type(step_context), intent(in) :: c
    integer, intent(in) :: base, k
    node_of = base + iand(k, 1) + c%nn(1) * (iand(ishft(k, -1), 1) + c%nn(2) * iand(ishft(k, -2), 1))
  end function node_of

  ! Local node index (0-based), in the buffer of patch q, of the base node of a cell.
  pure integer function patch_base(c, q, cell)
    type(step_context), intent(in) :: c
    integer, intent(in) :: q, cell
    integer :: pc, qq, qx, qy, qz, i, j, k
    pc = c%patch_cells
    qq = pc + 1
    qx = mod(q, c%npd(1))
    qy = mod(q / c%npd(1), c%npd(2))
    qz = q / (c%npd(1) * c%npd(2))
    i = mod(cell, c%nc(1)) - qx * pc
    j = mod(cell / c%nc(1), c%nc(2)) - qy * pc
    k = cell / (c%nc(1) * c%nc(2)) - qz * pc
    patch_base = i + qq * (j + qq * k)
  end function patch_base

  pure integer function patch_local(pc, k)
    integer, intent(in) :: pc, k
    integer :: qq
    qq = pc + 1
    patch_local = iand(k, 1) + qq * (iand(ishft(k, -1), 1) + qq * iand(ishft(k, -2), 1))
  end function patch_local

  ! The patch buffers (NODE_FIELDS, patch_nodes, nslot); only called with nslot > 0.
  subroutine view_buffers(c, buf)
    type(step_context), intent(in) :: c
    real(dp), pointer, intent(out) :: buf(:,:,:)
    integer :: qq, pn
    qq = c%patch_cells + 1 + 2 * c%patch_halo
    pn = qq * qq * qq
    call c_f_pointer(c%patch_buf, buf, [NODE_FIELDS, pn, c%nslot])
  end subroutine view_buffers

  ! Patches whose buffers (halo hh) hold node n (0-based) along one axis: lo..hi.
  pure subroutine patch_range(n, pc, hh, npd, lo, hi)
    integer, intent(in) :: n, pc, hh, npd
    integer, intent(out) :: lo, hi
    integer :: t
    t = n - pc - hh
    if (t <= 0) then
      lo = 0
    else
      lo = (t + pc - 1) / pc
    end if
    hi = (n + hh) / pc
    if (hi > npd - 1) hi = npd - 1
  end subroutine patch_range

  ! GIMP stencil of particle p (1-based): cell indices ci (0-based), offsets o, weights and
  ! gradients of the 27 nodes (cxx gimp_stencil).
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
    do a = 1, 3
      o(a) = gimp_offset(lxp(a), ci(a), c%nc(a))
    end do
    call shape_gimp(lxp, o, lp * c%inv_h, c%inv_h, sn, sg)
  end subroutine gimp_stencil

  ! Offset (0-based) of stencil node k = a + 3 b + 9 c from the stencil's first node in an
  ! array of row length r0 and plane size r0 r1.
  pure integer function stencil_offset(k, r0, r1)
    integer, intent(in) :: k, r0, r1
    stencil_offset = mod(k, 3) + r0 * (mod(k / 3, 3) + r1 * (k / 9))
  end function stencil_offset

  ! Buffer node (0-based), in the buffer of patch q, of a GIMP stencil's first node.
  pure integer function gimp_patch_corner(c, q, ci, o)
    type(step_context), intent(in) :: c
    integer, intent(in) :: q, ci(3), o(3)
    integer :: pc, hh, qq, qx, qy, qz
    pc = c%patch_cells
    hh = c%patch_halo
    qq = pc + 1 + 2 * hh
    qx = mod(q, c%npd(1))
    qy = mod(q / c%npd(1), c%npd(2))
    qz = q / (c%npd(1) * c%npd(2))
    gimp_patch_corner = (ci(1) + o(1) - qx * pc + hh) + &
                        qq * ((ci(2) + o(2) - qy * pc + hh) + qq * (ci(3) + o(3) - qz * pc + hh))
  end function gimp_patch_corner

  ! Global node (0-based) of a GIMP stencil's first node.
  pure integer function gimp_corner(c, ci, o)
    type(step_context), intent(in) :: c
    integer, intent(in) :: ci(3), o(3)
    gimp_corner = (ci(1) + o(1)) + c%nn(1) * ((ci(2) + o(2)) + c%nn(2) * (ci(3) + o(3)))
  end function gimp_corner

  ! True when particle p (1-based) belongs to another component than the context's.
  logical function other_component(c, p, body, bcomp)
    type(step_context), intent(in) :: c
    integer, intent(in) :: p
    integer(c_int), intent(in) :: body(:), bcomp(:)
    other_component = .false.
    if (c%only_comp > 0) other_component = bcomp(body(p) + 1) /= c%only_comp
  end function other_component

  ! Canonical assembly: each node's value is 0.0 plus the values of the non-empty patches
  ! holding it, in ascending patch index (x fastest, then y, z). Fields first..first+count-1
  ! (0-based: 0 mass, 1-3 momentum, 4-6 force) of the buffers go to the node arrays.
  subroutine assemble(c, first, count, gmass, gmom, gforce)
    type(step_context), intent(in) :: c
    integer, intent(in) :: first, count
    real(dp), intent(inout) :: gmass(:), gmom(:,:), gforce(:,:)
    real(dp), pointer :: buf(:,:,:)
    integer, pointer :: slots(:)
    real(dp) :: acc(NODE_FIELDS)
    integer :: pc, qq, hh, i, j, k, qx, qy, qz, qx_lo, qx_hi, qy_lo, qy_hi, qz_lo, qz_hi
    integer :: q, slot, ln, n, f, field
    pc = c%patch_cells
    hh = c%patch_halo
    qq = pc + 1 + 2 * hh
    call c_f_pointer(c%patch_slot, slots, [c%npatch])
    nullify(buf)
    if (c%nslot > 0) call view_buffers(c, buf)
    do k = 0, c%nn(3) - 1
      call patch_range(k, pc, hh, c%npd(3), qz_lo, qz_hi)
      do j = 0, c%nn(2) - 1
        call patch_range(j, pc, hh, c%npd(2), qy_lo, qy_hi)
        do i = 0, c%nn(1) - 1
          call patch_range(i, pc, hh, c%npd(1), qx_lo, qx_hi)
          do f = 1, count
            acc(f) = 0.0_dp
          end do
          do qz = qz_lo, qz_hi
            do qy = qy_lo, qy_hi
              do qx = qx_lo, qx_hi
                q = qx + c%npd(1) * (qy + c%npd(2) * qz)
                slot = slots(q + 1)
                if (slot < 0) cycle
                ln = (i - qx * pc + hh) + qq * ((j - qy * pc + hh) + qq * (k - qz * pc + hh))
                do f = 1, count
                  acc(f) = acc(f) + buf(first + f, ln + 1, slot + 1)
                end do
              end do
            end do
          end do
          n = i + c%nn(1) * (j + c%nn(2) * k) + 1
          do f = 1, count
            field = first + f - 1
            if (field == 0) then
              gmass(n) = acc(f)
            else if (field <= 3) then
              gmom(field, n) = acc(f)
            else
              gforce(field - 3, n) = acc(f)
            end if
          end do
        end do
      end do
    end do
  end subroutine assemble

  ! Boundary conditions of the box faces on a nodal vector field (3,nnode):
  ! 1 fixed (all components zero), otherwise symmetry (normal component zero).
  subroutine apply_bc(c, a)
    type(step_context), intent(in) :: c
    real(dp), intent(inout) :: a(:,:)
    integer :: face, kind, axis, fixed_index, u, w, ju, jw, n
    integer :: idx(0:2)
    do face = 0, 5
      kind = c%fix(face + 1)
      if (kind == 0) cycle
      axis = face / 2
      if (mod(face, 2) == 0) then
        fixed_index = 0
      else
        fixed_index = c%nn(axis + 1) - 1
      end if
      u = mod(axis + 1, 3)
      w = mod(axis + 2, 3)
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
  end subroutine apply_bc

  ! Scatter of mass, momentum and (optionally) forces of every particle into its patch buffer.
  subroutine scatter_p2g(c, with_mass_mom, with_forces)
    type(step_context), intent(inout) :: c
    logical, intent(in) :: with_mass_mom, with_forces
    real(dp), pointer :: buf(:,:,:), lx(:,:), v(:,:), sig(:,:), mass(:), vol(:), fext(:,:), grav(:,:)
    real(dp), pointer :: psize(:)
    integer(c_int), pointer :: pstart(:), ppart(:), slots(:), cell(:), body(:)
    real(dp) :: sn(27), sg(3, 27), vs(6), fb(3), mp, volp, mn, gx, gy, gz, fx, fy, fz
    integer :: pc, qq, q, slot, idx, p, base, s, a, k, ln, nk
    integer :: ci(3), o(3)
    logical :: has_fext, body_force, gimp
    if (c%nslot <= 0) return
    pc = c%patch_cells
    qq = pc + 1 + 2 * c%patch_halo
    gimp = c%shape == 1
    if (gimp) call c_f_pointer(c%psize, psize, [c%np])
    call view_buffers(c, buf)
    call c_f_pointer(c%patch_start, pstart, [c%npatch + 1])
    call c_f_pointer(c%patch_part, ppart, [c%np])
    call c_f_pointer(c%patch_slot, slots, [c%npatch])
    call c_f_pointer(c%cell, cell, [c%np])
    call c_f_pointer(c%body, body, [c%np])
    call c_f_pointer(c%lx, lx, [3, c%np])
    call c_f_pointer(c%v, v, [3, c%np])
    call c_f_pointer(c%sig, sig, [6, c%np])
    call c_f_pointer(c%mass, mass, [c%np])
    call c_f_pointer(c%vol, vol, [c%np])
    body_force = c%has_body_force /= 0
    has_fext = c_associated(c%fext)
    if (has_fext) then
      call c_f_pointer(c%fext, fext, [3, c%np])
    else
      nullify(fext)
    end if
    if (body_force) then
      call c_f_pointer(c%gravity, grav, [3, max(c%nbody, 1)])
    else
      nullify(grav)
    end if
    do q = 0, c%npatch - 1
      slot = slots(q + 1)
      if (slot < 0) cycle
      buf(:, :, slot + 1) = 0.0_dp
      do idx = pstart(q + 1), pstart(q + 2) - 1
        p = ppart(idx + 1) + 1
        if (gimp) then
          call gimp_stencil(c, cell(p), lx(:, p), psize(p), ci, o, sn, sg)
          base = gimp_patch_corner(c, q, ci, o)
          nk = 27
        else
          call shape_linear(lx(:, p), c%inv_h, sn(1:8), sg(:, 1:8))
          base = patch_base(c, q, cell(p))
          nk = 8
        end if
        mp = mass(p)
        vs = 0.0_dp
        fb = 0.0_dp
        if (with_forces) then
          volp = vol(p)
          do s = 1, 6
            vs(s) = sig(s, p) * volp
          end do
          if (body_force) then
            do a = 1, 3
              fb(a) = mp * grav(a, body(p) + 1)
              if (has_fext) fb(a) = fb(a) + fext(a, p)
            end do
          end if
        end if
        do k = 0, nk - 1
          if (gimp) then
            ln = base + stencil_offset(k, qq, qq) + 1
          else
            ln = base + patch_local(pc, k) + 1
          end if
          if (with_mass_mom) then
            mn = mp * sn(k + 1)
            buf(1, ln, slot + 1) = buf(1, ln, slot + 1) + mn
            buf(2, ln, slot + 1) = buf(2, ln, slot + 1) + (mn * v(1, p))
            buf(3, ln, slot + 1) = buf(3, ln, slot + 1) + (mn * v(2, p))
            buf(4, ln, slot + 1) = buf(4, ln, slot + 1) + (mn * v(3, p))
          end if
          if (with_forces) then
            gx = sg(1, k + 1)
            gy = sg(2, k + 1)
            gz = sg(3, k + 1)
            fx = -(((vs(1) * gx) + (vs(6) * gy)) + (vs(5) * gz))
            fy = -(((vs(6) * gx) + (vs(2) * gy)) + (vs(4) * gz))
            fz = -(((vs(5) * gx) + (vs(4) * gy)) + (vs(3) * gz))
            if (body_force) then
              fx = (sn(k + 1) * fb(1)) + fx
              fy = (sn(k + 1) * fb(2)) + fy
              fz = (sn(k + 1) * fb(3)) + fz
            end if
            buf(5, ln, slot + 1) = buf(5, ln, slot + 1) + fx
            buf(6, ln, slot + 1) = buf(6, ln, slot + 1) + fy
            buf(7, ln, slot + 1) = buf(7, ln, slot + 1) + fz
          end if
        end do
      end do
    end do
  end subroutine scatter_p2g

  ! ------------------------------------------------------------------ the stages

  ! Bin: local coordinates, base cells, patch particle lists (ascending particle index
  ! within each patch) and buffer slots of the non-empty patches.
  subroutine mpm3d_f_bin(c) bind(C, name='mpm3d_f_bin')
    type(step_context), intent(inout) :: c
    real(dp), pointer :: x(:,:), lx(:,:)
    integer(c_int), pointer :: start(:), ppart(:), slots(:), cell(:), body(:), bcomp(:)
    integer :: pc, q, p, a, outside, nslot, i, j, k, cl
    integer :: idx(3)
    real(dp) :: t, fl, f0
    logical :: inside, filter
    pc = c%patch_cells
    filter = c%only_comp > 0     ! contact: this context's component only
    if (filter) then
      call c_f_pointer(c%body, body, [c%np])
      call c_f_pointer(c%body_comp, bcomp, [max(c%nbody, 1)])
    end if
    call c_f_pointer(c%x, x, [3, c%np])
    call c_f_pointer(c%lx, lx, [3, c%np])
    call c_f_pointer(c%patch_start, start, [c%npatch + 1])
    call c_f_pointer(c%patch_part, ppart, [c%np])
    call c_f_pointer(c%patch_slot, slots, [c%npatch])
    call c_f_pointer(c%cell, cell, [c%np])
    ! start(q + 1) is C's start[q].
    do q = 0, c%npatch
      start(q + 1) = 0
    end do
    outside = 0
    do p = 1, c%np
      if (filter) then
        if (other_component(c, p, body, bcomp)) cycle
      end if
      inside = .true.
      do a = 1, 3
        ! Cell on the deck's lattice, then in the window (the same bits for any window).
        t = (x(a, p) - c%origin(a)) / c%h
        fl = aint(t)                      ! floor(t) as a double, exactly (NaN stays NaN)
        if (fl > t) fl = fl - 1.0_dp
        f0 = real(c%cell_off(a), dp)
        if (.not. (fl >= f0 .and. fl < f0 + real(c%nc(a), dp))) then   ! also catches NaN
          inside = .false.
          exit
        end if
        idx(a) = int(fl) - c%cell_off(a)
        lx(a, p) = t - fl
      end do
      if (.not. inside) then
        cell(p) = -1
        outside = outside + 1
        cycle
      end if
      cell(p) = idx(1) + c%nc(1) * (idx(2) + c%nc(2) * idx(3))
      q = idx(1) / pc + c%npd(1) * (idx(2) / pc + c%npd(2) * (idx(3) / pc))
      start(q + 2) = start(q + 2) + 1
    end do
    nslot = 0
    do q = 0, c%npatch - 1
      if (start(q + 2) > 0) then
        slots(q + 1) = nslot
        nslot = nslot + 1
      else
        slots(q + 1) = -1
      end if
      start(q + 2) = start(q + 2) + start(q + 1)
    end do
    c%nslot = nslot
    c%noutside = outside
    ! Second pass: a stable counting sort; the end offsets serve as fill pointers.
    do q = c%npatch, 1, -1
      start(q + 1) = start(q)
    end do
    start(1) = 0
    do p = 1, c%np
      if (filter) then
        if (other_component(c, p, body, bcomp)) cycle
      end if
      cl = cell(p)
      if (cl < 0) cycle
      i = mod(cl, c%nc(1))
      j = mod(cl / c%nc(1), c%nc(2))
      k = cl / (c%nc(1) * c%nc(2))
      q = i / pc + c%npd(1) * (j / pc + c%npd(2) * (k / pc))
      ppart(start(q + 2) + 1) = p - 1
      start(q + 2) = start(q + 2) + 1
    end do
  end subroutine mpm3d_f_bin

  ! P2G: mass, momentum (and forces unless USF) into the nodes; BC on momentum.
  subroutine mpm3d_f_p2g(c) bind(C, name='mpm3d_f_p2g')
    type(step_context), intent(inout) :: c
    real(dp), pointer :: gmass(:), gmom(:,:), gforce(:,:)
    logical :: forces
    forces = c%scheme /= SCHEME_USF
    call scatter_p2g(c, .true., forces)
    call c_f_pointer(c%gmass, gmass, [c%nnode])
    call c_f_pointer(c%gmom, gmom, [3, c%nnode])
    call c_f_pointer(c%gforce, gforce, [3, c%nnode])
    if (forces) then
      call assemble(c, 0, 7, gmass, gmom, gforce)
    else
      call assemble(c, 0, 4, gmass, gmom, gforce)
    end if
    call apply_bc(c, gmom)
  end subroutine mpm3d_f_p2g

  ! Forces (USF): internal and body forces after the stress update.
  subroutine mpm3d_f_forces(c) bind(C, name='mpm3d_f_forces')
    type(step_context), intent(inout) :: c
    real(dp), pointer :: gmass(:), gmom(:,:), gforce(:,:)
    call scatter_p2g(c, .false., .true.)
    call c_f_pointer(c%gmass, gmass, [c%nnode])
    call c_f_pointer(c%gmom, gmom, [3, c%nnode])
    call c_f_pointer(c%gforce, gforce, [3, c%nnode])
    call assemble(c, 4, 3, gmass, gmom, gforce)
  end subroutine mpm3d_f_forces

  ! Integrate: p += f dt_int; boundary conditions on momentum and force.
  subroutine mpm3d_f_integrate(c) bind(C, name='mpm3d_f_integrate')
    type(step_context), intent(inout) :: c
    real(dp), pointer :: gmom(:,:), gforce(:,:)
    real(dp) :: dt
    integer :: n, a
    call c_f_pointer(c%gmom, gmom, [3, c%nnode])
    call c_f_pointer(c%gforce, gforce, [3, c%nnode])
    dt = c%dt_int
    do n = 1, c%nnode
      do a = 1, 3
        gmom(a, n) = gmom(a, n) + (gforce(a, n) * dt)
      end do
    end do
    call apply_bc(c, gmom)
    call apply_bc(c, gforce)
  end subroutine mpm3d_f_integrate

  ! G2P: particle velocity and position from the grid; MUSL: momentum remap and BC.
  subroutine mpm3d_f_g2p(c) bind(C, name='mpm3d_f_g2p')
    type(step_context), intent(inout) :: c
    real(dp), pointer :: buf(:,:,:), lx(:,:), v(:,:), x(:,:), mass(:)
    real(dp), pointer :: gmass(:), gmom(:,:), gforce(:,:), psize(:)
    integer(c_int), pointer :: pstart(:), ppart(:), slots(:), cell(:)
    real(dp) :: sn(27), sg(3, 27), acc(3), vel(3), m, r, mp, mn
    integer :: pc, qq, pn, q, slot, idx, p, base, pbase, k, n, a, ln, nk
    integer :: ci(3), o(3)
    logical :: remap, gimp
    remap = c%scheme == SCHEME_MUSL
    pc = c%patch_cells
    qq = pc + 1 + 2 * c%patch_halo
    pn = qq * qq * qq
    gimp = c%shape == 1
    if (gimp) call c_f_pointer(c%psize, psize, [c%np])
    call c_f_pointer(c%gmass, gmass, [c%nnode])
    call c_f_pointer(c%gmom, gmom, [3, c%nnode])
    call c_f_pointer(c%gforce, gforce, [3, c%nnode])
    if (c%nslot > 0) then
      call view_buffers(c, buf)
      call c_f_pointer(c%patch_start, pstart, [c%npatch + 1])
      call c_f_pointer(c%patch_part, ppart, [c%np])
      call c_f_pointer(c%patch_slot, slots, [c%npatch])
      call c_f_pointer(c%cell, cell, [c%np])
      call c_f_pointer(c%lx, lx, [3, c%np])
      call c_f_pointer(c%v, v, [3, c%np])
      call c_f_pointer(c%x, x, [3, c%np])
      call c_f_pointer(c%mass, mass, [c%np])
      do q = 0, c%npatch - 1
        slot = slots(q + 1)
        if (slot < 0) cycle
        if (remap) then
          do ln = 1, pn
            buf(2, ln, slot + 1) = 0.0_dp
            buf(3, ln, slot + 1) = 0.0_dp
            buf(4, ln, slot + 1) = 0.0_dp
          end do
        end if
        do idx = pstart(q + 1), pstart(q + 2) - 1
          p = ppart(idx + 1) + 1
          if (gimp) then
            call gimp_stencil(c, cell(p), lx(:, p), psize(p), ci, o, sn, sg)
            base = gimp_corner(c, ci, o)
            nk = 27
          else
            call shape_linear(lx(:, p), c%inv_h, sn(1:8), sg(:, 1:8))
            base = base_node(c, cell(p))
            nk = 8
          end if
          acc = 0.0_dp
          vel = 0.0_dp
          do k = 0, nk - 1
            if (gimp) then
              n = base + stencil_offset(k, c%nn(1), c%nn(2)) + 1
            else
              n = node_of(c, base, k) + 1
            end if
            m = gmass(n)
            if (.not. (m > c%mass_cutoff)) cycle
            r = sn(k + 1) / m
            do a = 1, 3
              acc(a) = acc(a) + (gforce(a, n) * r)
              vel(a) = vel(a) + (gmom(a, n) * r)
            end do
          end do
          do a = 1, 3
            v(a, p) = v(a, p) + (acc(a) * c%dt_int)
            x(a, p) = x(a, p) + (vel(a) * c%dt)
          end do
          if (remap) then
            if (gimp) then
              pbase = gimp_patch_corner(c, q, ci, o)
            else
              pbase = patch_base(c, q, cell(p))
            end if
            mp = mass(p)
            do k = 0, nk - 1
              if (gimp) then
                ln = pbase + stencil_offset(k, qq, qq) + 1
              else
                ln = pbase + patch_local(pc, k) + 1
              end if
              mn = mp * sn(k + 1)
              buf(2, ln, slot + 1) = buf(2, ln, slot + 1) + (mn * v(1, p))
              buf(3, ln, slot + 1) = buf(3, ln, slot + 1) + (mn * v(2, p))
              buf(4, ln, slot + 1) = buf(4, ln, slot + 1) + (mn * v(3, p))
            end do
          end if
        end do
      end do
    end if
    if (remap) then
      call assemble(c, 1, 3, gmass, gmom, gforce)
      call apply_bc(c, gmom)
    end if
  end subroutine mpm3d_f_g2p

  ! Stress: strain and spin increments from the grid velocity, volume, stress update.
  subroutine mpm3d_f_stress(c) bind(C, name='mpm3d_f_stress')
    type(step_context), intent(inout) :: c
    real(dp), pointer :: lx(:,:), sig(:,:), mass(:), vol(:), epeff(:), ie(:), temp(:)
    real(dp), pointer :: tlight(:), qv(:)
    real(dp), pointer :: gmass(:), gmom(:,:), psize(:)
    integer(c_int), pointer :: cell(:), mat(:), body(:), bcomp(:)
    type(material_params), pointer :: mats(:)
    real(dp) :: sn(27), sg(3, 27), lg(0:8), de(6), dw(3), dt, m, va, vol_old, vol_new, tdummy
    real(dp) :: burn, qdummy
    integer :: p, cl, base, k, n, a, b, nk
    integer :: ci(3), o(3)
    logical :: has_temp, has_tl, has_q, gimp, filter
    dt = c%dt
    gimp = c%shape == 1
    if (gimp) call c_f_pointer(c%psize, psize, [c%np])
    filter = c%only_comp > 0
    if (filter) then
      call c_f_pointer(c%body, body, [c%np])
      call c_f_pointer(c%body_comp, bcomp, [max(c%nbody, 1)])
    end if
    call c_f_pointer(c%lx, lx, [3, c%np])
    call c_f_pointer(c%sig, sig, [6, c%np])
    call c_f_pointer(c%mass, mass, [c%np])
    call c_f_pointer(c%vol, vol, [c%np])
    call c_f_pointer(c%epeff, epeff, [c%np])
    call c_f_pointer(c%ie, ie, [c%np])
    call c_f_pointer(c%cell, cell, [c%np])
    call c_f_pointer(c%mat, mat, [c%np])
    call c_f_pointer(c%gmass, gmass, [c%nnode])
    call c_f_pointer(c%gmom, gmom, [3, c%nnode])
    call c_f_pointer(c%mats, mats, [c%nmat])
    has_temp = c_associated(c%temp)
    if (has_temp) then
      call c_f_pointer(c%temp, temp, [c%np])
    else
      nullify(temp)
    end if
    has_tl = c_associated(c%tlight)
    if (has_tl) call c_f_pointer(c%tlight, tlight, [c%np])
    has_q = c_associated(c%qv)
    if (has_q) call c_f_pointer(c%qv, qv, [c%np])
    tdummy = 0.0_dp
    qdummy = 0.0_dp
    do p = 1, c%np
      cl = cell(p)
      if (cl < 0) cycle
      if (filter) then
        if (other_component(c, p, body, bcomp)) cycle
      end if
      if (gimp) then
        call gimp_stencil(c, cl, lx(:, p), psize(p), ci, o, sn, sg)
        base = gimp_corner(c, ci, o)
        nk = 27
      else
        call shape_linear(lx(:, p), c%inv_h, sn(1:8), sg(:, 1:8))
        base = base_node(c, cl)
        nk = 8
      end if
      lg = 0.0_dp             ! lg(3a+b) = d v_a / d x_b (0-based a, b)
      do k = 0, nk - 1
        if (gimp) then
          n = base + stencil_offset(k, c%nn(1), c%nn(2)) + 1
        else
          n = node_of(c, base, k) + 1
        end if
        m = gmass(n)
        if (.not. (m > c%mass_cutoff)) cycle
        do a = 0, 2
          va = gmom(a + 1, n) / m
          do b = 0, 2
            lg(3 * a + b) = lg(3 * a + b) + (va * sg(b + 1, k + 1))
          end do
        end do
      end do
      de(1) = lg(0) * dt
      de(2) = lg(4) * dt
      de(3) = lg(8) * dt
      de(4) = (0.5_dp * (lg(5) + lg(7))) * dt
      de(5) = (0.5_dp * (lg(2) + lg(6))) * dt
      de(6) = (0.5_dp * (lg(1) + lg(3))) * dt
      dw(1) = (0.5_dp * (lg(5) - lg(7))) * dt
      dw(2) = (0.5_dp * (lg(2) - lg(6))) * dt
      dw(3) = (0.5_dp * (lg(1) - lg(3))) * dt
      vol_old = vol(p)
      vol_new = vol_old * (1.0_dp + ((de(1) + de(2)) + de(3)))
      burn = 1.0_dp
      if (has_tl) burn = burn_fraction(mats(mat(p) + 1), tlight(p), c%time)
      if (has_temp .and. has_q) then
        call stress_update(mats(mat(p) + 1), de, dw, dt, mass(p), vol_old, vol_new, sig(:, p), &
                           epeff(p), ie(p), .true., temp(p), .true., qv(p), burn, c%bulk_q1, c%bulk_q2, c%h)
      else if (has_temp) then
        call stress_update(mats(mat(p) + 1), de, dw, dt, mass(p), vol_old, vol_new, sig(:, p), &
                           epeff(p), ie(p), .true., temp(p), .false., qdummy, burn, c%bulk_q1, c%bulk_q2, c%h)
      else if (has_q) then
        call stress_update(mats(mat(p) + 1), de, dw, dt, mass(p), vol_old, vol_new, sig(:, p), &
                           epeff(p), ie(p), .false., tdummy, .true., qv(p), burn, c%bulk_q1, c%bulk_q2, c%h)
      else
        call stress_update(mats(mat(p) + 1), de, dw, dt, mass(p), vol_old, vol_new, sig(:, p), &
                           epeff(p), ie(p), .false., tdummy, .false., qdummy, burn, c%bulk_q1, c%bulk_q2, c%h)
      end if
      vol(p) = vol_new
    end do
  end subroutine mpm3d_f_stress

  ! Energy: kinetic and internal energy and momentum, summed per block of reduce_block
  ! particles, then the block partials in block order.
  subroutine mpm3d_f_energy(c) bind(C, name='mpm3d_f_energy')
    type(step_context), intent(inout) :: c
    real(dp), pointer :: mass(:), v(:,:), ie(:), partials(:,:)
    real(dp) :: part(REDUCE_FIELDS), m, s
    integer :: bs, nblock, blk, last, p, f
    bs = c%reduce_block
    nblock = (c%np + bs - 1) / bs
    call c_f_pointer(c%mass, mass, [c%np])
    call c_f_pointer(c%v, v, [3, c%np])
    call c_f_pointer(c%ie, ie, [c%np])
    call c_f_pointer(c%partials, partials, [REDUCE_FIELDS, max(nblock, 1)])
    do blk = 0, nblock - 1
      part = 0.0_dp
      last = min((blk + 1) * bs, c%np)
      do p = blk * bs + 1, last
        m = mass(p)
        part(1) = part(1) + ((0.5_dp * m) * (((v(1, p) * v(1, p)) + (v(2, p) * v(2, p))) + (v(3, p) * v(3, p))))
        part(2) = part(2) + ie(p)
        part(3) = part(3) + (m * v(1, p))
        part(4) = part(4) + (m * v(2, p))
        part(5) = part(5) + (m * v(3, p))
      end do
      do f = 1, REDUCE_FIELDS
        partials(f, blk + 1) = part(f)
      end do
    end do
    do f = 1, REDUCE_FIELDS
      s = 0.0_dp
      do blk = 1, nblock
        s = s + partials(f, blk)
      end do
      c%result(f) = s
    end do
  end subroutine mpm3d_f_energy

  ! True when patch q3 (0-based coordinates) is active: it or one of its lower neighbours
  ! (halo 1: one of its 26 neighbours) holds particles (cxx owned_nodes).
  logical function patch_active(c, q3)
    type(step_context), intent(in) :: c
    integer, intent(in) :: q3(3)
    integer(c_int), pointer :: slots(:)
    integer :: ne, cx, cy, cz, px, py, pz
    call c_f_pointer(c%patch_slot, slots, [c%npatch])
    patch_active = .false.
    ne = 2 + c%patch_halo
    do cz = 0, ne - 1
      do cy = 0, ne - 1
        do cx = 0, ne - 1
          px = q3(1) - 1 + cx
          py = q3(2) - 1 + cy
          pz = q3(3) - 1 + cz
          if (px < 0 .or. py < 0 .or. pz < 0) cycle
          if (px >= c%npd(1) .or. py >= c%npd(2) .or. pz >= c%npd(3)) cycle
          if (slots(px + c%npd(1) * (py + c%npd(2) * pz) + 1) >= 0) patch_active = .true.
        end do
      end do
    end do
  end function patch_active

  ! Contact: g_i = sum_p m_p grad N_i(x_p) of the context's particles (outward) into gnormal,
  ! through the force fields of the patch buffers (cxx scatter_mass_gradient).
  subroutine scatter_mass_gradient(c)
    type(step_context), intent(inout) :: c
    real(dp), pointer :: buf(:,:,:), lx(:,:), mass(:), psize(:), gmass(:), gmom(:,:), gnormal(:,:)
    integer(c_int), pointer :: pstart(:), ppart(:), slots(:), cell(:)
    real(dp) :: sn(27), sg(3, 27), mp
    integer :: pc, qq, pn, q, slot, idx, p, base, k, ln, nk
    integer :: ci(3), o(3)
    logical :: gimp
    pc = c%patch_cells
    qq = pc + 1 + 2 * c%patch_halo
    pn = qq * qq * qq
    gimp = c%shape == 1
    call c_f_pointer(c%gmass, gmass, [c%nnode])
    call c_f_pointer(c%gmom, gmom, [3, c%nnode])
    call c_f_pointer(c%gnormal, gnormal, [3, c%nnode])
    if (c%nslot > 0) then
      call view_buffers(c, buf)
      call c_f_pointer(c%patch_start, pstart, [c%npatch + 1])
      call c_f_pointer(c%patch_part, ppart, [c%np])
      call c_f_pointer(c%patch_slot, slots, [c%npatch])
      call c_f_pointer(c%cell, cell, [c%np])
      call c_f_pointer(c%lx, lx, [3, c%np])
      call c_f_pointer(c%mass, mass, [c%np])
      if (gimp) call c_f_pointer(c%psize, psize, [c%np])
      do q = 0, c%npatch - 1
        slot = slots(q + 1)
        if (slot < 0) cycle
        do ln = 1, pn
          buf(5, ln, slot + 1) = 0.0_dp
          buf(6, ln, slot + 1) = 0.0_dp
          buf(7, ln, slot + 1) = 0.0_dp
        end do
        do idx = pstart(q + 1), pstart(q + 2) - 1
          p = ppart(idx + 1) + 1
          mp = mass(p)
          if (gimp) then
            call gimp_stencil(c, cell(p), lx(:, p), psize(p), ci, o, sn, sg)
            base = gimp_patch_corner(c, q, ci, o)
            nk = 27
          else
            call shape_linear(lx(:, p), c%inv_h, sn(1:8), sg(:, 1:8))
            base = patch_base(c, q, cell(p))
            nk = 8
          end if
          do k = 0, nk - 1
            if (gimp) then
              ln = base + stencil_offset(k, qq, qq) + 1
            else
              ln = base + patch_local(pc, k) + 1
            end if
            buf(5, ln, slot + 1) = buf(5, ln, slot + 1) + (mp * sg(1, k + 1))
            buf(6, ln, slot + 1) = buf(6, ln, slot + 1) + (mp * sg(2, k + 1))
            buf(7, ln, slot + 1) = buf(7, ln, slot + 1) + (mp * sg(3, k + 1))
          end do
        end do
      end do
    end if
    call assemble(c, 4, 3, gmass, gmom, gnormal)
  end subroutine scatter_mass_gradient

  ! Contact: multi-velocity correction between component 1 (c) and component 2 (c%other),
  ! as mpm3d_cxx_contact (see there for the algorithm): same nodes, same operations, the
  ! contact force as per-patch partials folded in patch order into result(6:8), the unit
  ! normals of the corrected nodes kept in c%gnormal (zero at the other nodes of the loop).
  subroutine mpm3d_f_contact(c) bind(C, name='mpm3d_f_contact')
    type(step_context), intent(inout), target :: c
    type(step_context), pointer :: c2
    if (.not. c_associated(c%other)) return
    call c_f_pointer(c%other, c2)
    call scatter_mass_gradient(c)
    call scatter_mass_gradient(c2)
    call contact_correct(c, .false.)
  end subroutine mpm3d_f_contact

  ! The momenta of the nodes marked in contact by mpm3d_f_contact corrected again with the
  ! kept normals, for either sign of q.n (as mpm3d_cxx_recontact): MUSL after the remap of
  ! this step, USF after the P2G of the next step.
  subroutine mpm3d_f_recontact(c) bind(C, name='mpm3d_f_recontact')
    type(step_context), intent(inout), target :: c
    if (.not. c_associated(c%other)) return
    call contact_correct(c, .true.)
  end subroutine mpm3d_f_recontact

  subroutine contact_correct(c, remap)
    type(step_context), intent(inout), target :: c
    logical, intent(in) :: remap
    type(step_context), pointer :: c2
    real(dp), pointer :: m1(:), m2(:), p1(:,:), p2(:,:), f1(:,:), f2(:,:), g1(:,:), g2(:,:), cpart(:,:)
    real(dp) :: part(3), nv(3), un(3), qv(3), t(3), len, mt, qn, tl, fr, ft, d, fc, s
    integer :: q, i, j, k, n, a, nb, ncount
    integer :: q3(3), lo(3), hi(3)
    call c_f_pointer(c%other, c2)
    call c_f_pointer(c%gmass, m1, [c%nnode])
    call c_f_pointer(c2%gmass, m2, [c%nnode])
    call c_f_pointer(c%gmom, p1, [3, c%nnode])
    call c_f_pointer(c2%gmom, p2, [3, c%nnode])
    call c_f_pointer(c%gforce, f1, [3, c%nnode])
    call c_f_pointer(c2%gforce, f2, [3, c%nnode])
    call c_f_pointer(c%gnormal, g1, [3, c%nnode])
    call c_f_pointer(c2%gnormal, g2, [3, c%nnode])
    call c_f_pointer(c%cpartials, cpart, [3, c%npatch])
    nb = c%contact_normbody
    ncount = 0
    do q = 0, c%npatch - 1
      part = 0.0_dp
      q3(1) = mod(q, c%npd(1))
      q3(2) = mod(q / c%npd(1), c%npd(2))
      q3(3) = q / (c%npd(1) * c%npd(2))
      do a = 1, 3
        lo(a) = q3(a) * c%patch_cells
        if (q3(a) == c%npd(a) - 1) then
          hi(a) = c%nn(a)
        else
          hi(a) = lo(a) + c%patch_cells
        end if
      end do
      if (patch_active(c, q3) .and. patch_active(c2, q3)) then
        do k = lo(3), hi(3) - 1
          do j = lo(2), hi(2) - 1
            do i = lo(1), hi(1) - 1
              n = i + c%nn(1) * (j + c%nn(2) * k) + 1
              if (.not. (m1(n) > c%mass_cutoff) .or. .not. (m2(n) > c%mass_cutoff)) then
                if (.not. remap) then
                  do a = 1, 3
                    g1(a, n) = 0.0_dp
                  end do
                end if
                cycle
              end if
              if (remap) then
                if (g1(1, n) == 0.0_dp .and. g1(2, n) == 0.0_dp .and. g1(3, n) == 0.0_dp) cycle
                do a = 1, 3
                  un(a) = g1(a, n)
                end do
              else
                do a = 1, 3
                  if (nb == 1) then
                    nv(a) = g1(a, n)
                  else if (nb == 2) then
                    nv(a) = -g2(a, n)
                  else
                    nv(a) = g1(a, n) - g2(a, n)
                  end if
                end do
                do a = 1, 3
                  g1(a, n) = 0.0_dp
                end do
                len = sqrt(((nv(1) * nv(1)) + (nv(2) * nv(2))) + (nv(3) * nv(3)))
                if (.not. (len > 0.0_dp)) cycle
                do a = 1, 3
                  un(a) = nv(a) / len
                end do
              end if
              mt = m1(n) + m2(n)
              do a = 1, 3
                qv(a) = ((m2(n) * p1(a, n)) - (m1(n) * p2(a, n))) / mt
              end do
              qn = ((qv(1) * un(1)) + (qv(2) * un(2))) + (qv(3) * un(3))
              if (.not. remap) then
                if (.not. (qn > 0.0_dp)) cycle
                do a = 1, 3
                  g1(a, n) = un(a)      ! in contact this step
                end do
              end if
              do a = 1, 3
                t(a) = qv(a) - (qn * un(a))
              end do
              tl = sqrt(((t(1) * t(1)) + (t(2) * t(2))) + (t(3) * t(3)))
              fr = c%contact_mu * abs(qn)
              if (tl > fr) then
                ft = fr / tl
              else
                ft = 1.0_dp
              end if
              do a = 1, 3
                d = -((qn * un(a)) + (ft * t(a)))
                p1(a, n) = p1(a, n) + d
                p2(a, n) = p2(a, n) - d
                if (.not. remap) then
                  fc = d / c%dt_int
                  f1(a, n) = f1(a, n) + fc
                  f2(a, n) = f2(a, n) - fc
                  part(a) = part(a) + fc
                end if
              end do
              ncount = ncount + 1
            end do
          end do
        end do
      else if (.not. remap .and. c%scheme == SCHEME_USF) then
        ! USF reads the marks again in the next step: no node outside the loop keeps one.
        do k = lo(3), hi(3) - 1
          do j = lo(2), hi(2) - 1
            do i = lo(1), hi(1) - 1
              n = i + c%nn(1) * (j + c%nn(2) * k) + 1
              do a = 1, 3
                g1(a, n) = 0.0_dp
              end do
            end do
          end do
        end do
      end if
      if (.not. remap) then
        do a = 1, 3
          cpart(a, q + 1) = part(a)
        end do
      end if
    end do
    call apply_bc(c, p1)
    call apply_bc(c2, p2)
    if (remap) return
    do a = 1, 3
      s = 0.0_dp
      do q = 1, c%npatch
        s = s + cpart(a, q)
      end do
      c%result(5 + a) = s
    end do
    c%ncontact = ncount
    call apply_bc(c, f1)
    call apply_bc(c2, f2)
  end subroutine contact_correct

  ! Layout of step_context and material_params as this compiler sees them (for the
  ! layout test against the C structs): sizes and a few offsets, in bytes.
  subroutine mpm3d_f_context_layout(out) bind(C, name='mpm3d_f_context_layout')
    integer(c_size_t), intent(out) :: out(13)
    type(step_context), target :: c
    type(material_params), target :: m(2)
    out(1) = c_sizeof(c)
    out(2) = transfer(c_loc(c%result), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(3) = transfer(c_loc(c%np), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(4) = transfer(c_loc(c%fix), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(5) = transfer(c_loc(c%reduce_block), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(6) = c_sizeof(m(1))
    out(7) = transfer(c_loc(m(1)%eos_e0), 0_c_intptr_t) - transfer(c_loc(m(1)), 0_c_intptr_t)
    out(8) = transfer(c_loc(m(1)%eos_type), 0_c_intptr_t) - transfer(c_loc(m(1)), 0_c_intptr_t)
    out(9) = transfer(c_loc(c%bulk_q2), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(10) = transfer(c_loc(m(1)%dp_tension), 0_c_intptr_t) - transfer(c_loc(m(1)), 0_c_intptr_t)
    out(11) = transfer(c_loc(c%cell_off), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(12) = transfer(c_loc(c%psize), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
    out(13) = transfer(c_loc(c%ncontact), 0_c_intptr_t) - transfer(c_loc(c), 0_c_intptr_t)
  end subroutine mpm3d_f_context_layout

end module mpm3d_update_step
