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
  use mpm3d_grid, only: NODE_FIELDS, shape_linear
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
  end type step_context

  public :: mpm3d_f_bin, mpm3d_f_p2g, mpm3d_f_forces, mpm3d_f_integrate, mpm3d_f_g2p, &
            mpm3d_f_stress, mpm3d_f_energy
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
    integer :: pn
    pn = (c%patch_cells + 1) * (c%patch_cells + 1) * (c%patch_cells + 1)
    call c_f_pointer(c%patch_buf, buf, [NODE_FIELDS, pn, c%nslot])
  end subroutine view_buffers

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
    integer :: pc, qq, i, j, k, qx, qy, qz, qx_lo, qx_hi, qy_lo, qy_hi, qz_lo, qz_hi
    integer :: q, slot, ln, n, f, field
    pc = c%patch_cells
    qq = pc + 1
    call c_f_pointer(c%patch_slot, slots, [c%npatch])
    nullify(buf)
    if (c%nslot > 0) call view_buffers(c, buf)
    do k = 0, c%nn(3) - 1
      if (k > 0 .and. mod(k, pc) == 0) then
        qz_lo = k / pc - 1
      else
        qz_lo = k / pc
      end if
      qz_hi = k / pc
      if (qz_hi > c%npd(3) - 1) qz_hi = c%npd(3) - 1
      if (qz_lo > qz_hi) qz_lo = qz_hi
      do j = 0, c%nn(2) - 1
        if (j > 0 .and. mod(j, pc) == 0) then
          qy_lo = j / pc - 1
        else
          qy_lo = j / pc
        end if
        qy_hi = j / pc
        if (qy_hi > c%npd(2) - 1) qy_hi = c%npd(2) - 1
        if (qy_lo > qy_hi) qy_lo = qy_hi
        do i = 0, c%nn(1) - 1
          if (i > 0 .and. mod(i, pc) == 0) then
            qx_lo = i / pc - 1
          else
            qx_lo = i / pc
          end if
          qx_hi = i / pc
          if (qx_hi > c%npd(1) - 1) qx_hi = c%npd(1) - 1
          if (qx_lo > qx_hi) qx_lo = qx_hi
          do f = 1, count
            acc(f) = 0.0_dp
          end do
          do qz = qz_lo, qz_hi
            do qy = qy_lo, qy_hi
              do qx = qx_lo, qx_hi
                q = qx + c%npd(1) * (qy + c%npd(2) * qz)
                slot = slots(q + 1)
                if (slot < 0) cycle
                ln = (i - qx * pc) + qq * ((j - qy * pc) + qq * (k - qz * pc))
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
    integer(c_int), pointer :: pstart(:), ppart(:), slots(:), cell(:), body(:)
    real(dp) :: sn(8), sg(3, 8), vs(6), fb(3), mp, volp, mn, gx, gy, gz, fx, fy, fz
    integer :: pc, q, slot, idx, p, base, s, a, k, ln
    logical :: has_fext, body_force
    if (c%nslot <= 0) return
    pc = c%patch_cells
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
        call shape_linear(lx(:, p), c%inv_h, sn, sg)
        base = patch_base(c, q, cell(p))
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
        do k = 0, 7
          ln = base + patch_local(pc, k) + 1
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
    integer(c_int), pointer :: start(:), ppart(:), slots(:), cell(:)
    integer :: pc, q, p, a, outside, nslot, i, j, k, cl
    integer :: idx(3)
    real(dp) :: t, fl, f0
    logical :: inside
    pc = c%patch_cells
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
    real(dp), pointer :: gmass(:), gmom(:,:), gforce(:,:)
    integer(c_int), pointer :: pstart(:), ppart(:), slots(:), cell(:)
    real(dp) :: sn(8), sg(3, 8), acc(3), vel(3), m, r, mp, mn
    integer :: pc, pn, q, slot, idx, p, base, pbase, k, n, a, ln
    logical :: remap
    remap = c%scheme == SCHEME_MUSL
    pc = c%patch_cells
    pn = (pc + 1) * (pc + 1) * (pc + 1)
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
          call shape_linear(lx(:, p), c%inv_h, sn, sg)
          base = base_node(c, cell(p))
          acc = 0.0_dp
          vel = 0.0_dp
          do k = 0, 7
            n = node_of(c, base, k) + 1
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
            pbase = patch_base(c, q, cell(p))
            mp = mass(p)
            do k = 0, 7
              ln = pbase + patch_local(pc, k) + 1
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
    real(dp), pointer :: gmass(:), gmom(:,:)
    integer(c_int), pointer :: cell(:), mat(:)
    type(material_params), pointer :: mats(:)
    real(dp) :: sn(8), sg(3, 8), lg(0:8), de(6), dw(3), dt, m, va, vol_old, vol_new, tdummy
    real(dp) :: burn, qdummy
    integer :: p, cl, base, k, n, a, b
    logical :: has_temp, has_tl, has_q
    dt = c%dt
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
      call shape_linear(lx(:, p), c%inv_h, sn, sg)
      base = base_node(c, cl)
      lg = 0.0_dp             ! lg(3a+b) = d v_a / d x_b (0-based a, b)
      do k = 0, 7
        n = node_of(c, base, k) + 1
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

  ! Layout of step_context and material_params as this compiler sees them (for the
  ! layout test against the C structs): sizes and a few offsets, in bytes.
  subroutine mpm3d_f_context_layout(out) bind(C, name='mpm3d_f_context_layout')
    integer(c_size_t), intent(out) :: out(11)
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
  end subroutine mpm3d_f_context_layout

end module mpm3d_update_step
