! stage_p2g: particle to grid (bind(C) mpm3d_f_p2g, and mpm3d_f_forces for USF): the
! scatter into the patch buffers, trilinear or GIMP, and the canonical patch assembly into
! the nodes; also the scatter of the mass gradients the contact stage needs.
module mpm3d_stage_p2g
  use, intrinsic :: iso_c_binding
  use mpm3d_material, only: dp
  use mpm3d_grid, only: NODE_FIELDS, shape_linear
  use mpm3d_stage_common
  use mpm3d_stage_sg, only: sg_p2g
  implicit none
  private

  public :: mpm3d_f_p2g, mpm3d_f_forces
  ! Also used by G2P (the MUSL remap) and by contact (the mass gradients).
  public :: assemble, scatter_mass_gradient

contains

  ! P2G: mass, momentum (and forces unless USF) into the nodes; BC on momentum.
  subroutine mpm3d_f_p2g(c) bind(C, name='mpm3d_f_p2g')
    type(step_context), intent(inout) :: c
    real(dp), pointer :: gmass(:), gmom(:,:), gforce(:,:)
    logical :: forces
    forces = c%method%scheme /= SCHEME_USF
    call c_f_pointer(c%grid%gmass, gmass, [c%grid%nnode])
    call c_f_pointer(c%grid%gmom, gmom, [3, c%grid%nnode])
    call c_f_pointer(c%grid%gforce, gforce, [3, c%grid%nnode])
    if (c%method%family == TRANSFER_SMOOTHED_GRADIENT) then
      call sg_p2g(c, .true., forces)
      call apply_bc(c, gmom)
      return
    end if
    call scatter_p2g(c, .true., forces)
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
    if (c%method%family == TRANSFER_SMOOTHED_GRADIENT) then
      call sg_p2g(c, .false., .true.)
      return
    end if
    call scatter_p2g(c, .false., .true.)
    call c_f_pointer(c%grid%gmass, gmass, [c%grid%nnode])
    call c_f_pointer(c%grid%gmom, gmom, [3, c%grid%nnode])
    call c_f_pointer(c%grid%gforce, gforce, [3, c%grid%nnode])
    call assemble(c, 4, 3, gmass, gmom, gforce)
  end subroutine mpm3d_f_forces

  ! Scatter of mass, momentum and (optionally) forces of every particle into its patch buffer.
  subroutine scatter_p2g(c, with_mass_mom, with_forces)
    type(step_context), intent(inout) :: c
    logical, intent(in) :: with_mass_mom, with_forces
    real(dp), pointer :: buf(:,:,:), lx(:,:), v(:,:), sig(:,:), mass(:), vol(:)
    real(dp), pointer :: psize(:)
    integer(c_int), pointer :: pstart(:), ppart(:), slots(:), cell(:)
    real(dp) :: sn(27), sg(3, 27), vs(9), fb(3), mp, volp, mn, gx, gy, gz, fx, fy, fz
    real(dp), pointer :: pk1(:,:)
    ! The stress times the volume as a 3x3 matrix (row i: force component i): sigma V from
    ! the Voigt stress, or V0 P under TLmp (as p2g_particle, cxx/transfer/transfer_common.hpp).
    integer, parameter :: VOIGT(9) = [1, 6, 5, 6, 2, 4, 5, 4, 3]
    integer :: pc, qq, q, slot, idx, p, base, s, k, ln, nk
    integer :: ci(3), o(3)
    logical :: body_force, wide
    if (c%patch%nslot <= 0) return
    pc = c%patch%patch_cells
    qq = pc + 1 + 2 * c%patch%patch_halo
    wide = c%method%family == TRANSFER_STENCIL27
    if (c%method%shape == 1) call c_f_pointer(c%part%psize, psize, [c%part%np])
    call view_buffers(c, buf)
    call c_f_pointer(c%patch%patch_start, pstart, [c%patch%npatch + 1])
    call c_f_pointer(c%patch%patch_part, ppart, [c%part%np])
    call c_f_pointer(c%patch%patch_slot, slots, [c%patch%npatch])
    call c_f_pointer(c%part%cell, cell, [c%part%np])
    call c_f_pointer(c%part%lx, lx, [3, c%part%np])
    call c_f_pointer(c%part%v, v, [3, c%part%np])
    call c_f_pointer(c%part%sig, sig, [6, c%part%np])
    call c_f_pointer(c%part%mass, mass, [c%part%np])
    call c_f_pointer(c%part%vol, vol, [c%part%np])
    body_force = c%method%has_body_force /= 0
    if (c%method%tl /= 0) call c_f_pointer(c%part%pk1, pk1, [9, c%part%np])
    do q = 0, c%patch%npatch - 1
      slot = slots(q + 1)
      if (slot < 0) cycle
      buf(:, :, slot + 1) = 0.0_dp
      do idx = pstart(q + 1), pstart(q + 2) - 1
        p = ppart(idx + 1) + 1
        call particle_shape(c, wide, p, cell(p), lx, psize, ci, o, sn, sg, nk)
        base = stencil_first_local(c, wide, q, cell(p), ci, o)
        mp = mass(p)
        vs = 0.0_dp
        fb = 0.0_dp
        if (with_forces) then
          volp = vol(p)
          do s = 1, 9
            if (c%method%tl /= 0) then
              vs(s) = pk1(s, p)
            else
              vs(s) = sig(VOIGT(s), p) * volp
            end if
          end do
          if (body_force) call particle_body_force(c, p, fb)
        end if
        do k = 0, nk - 1
          ln = stencil_local(c, wide, base, k)
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
            fx = -(((vs(1) * gx) + (vs(2) * gy)) + (vs(3) * gz))
            fy = -(((vs(4) * gx) + (vs(5) * gy)) + (vs(6) * gz))
            fz = -(((vs(7) * gx) + (vs(8) * gy)) + (vs(9) * gz))
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
    call rank_exchange(c, EXCHANGE_BUFFERS, first, count)   ! ghost patches' buffers (ranks)
    pc = c%patch%patch_cells
    hh = c%patch%patch_halo
    qq = pc + 1 + 2 * hh
    call c_f_pointer(c%patch%patch_slot, slots, [c%patch%npatch])
    nullify(buf)
    if (c%patch%nslot > 0) call view_buffers(c, buf)
    do k = 0, c%grid%nn(3) - 1
      call patch_range(k, pc, hh, c%patch%npd(3), qz_lo, qz_hi)
      do j = 0, c%grid%nn(2) - 1
        call patch_range(j, pc, hh, c%patch%npd(2), qy_lo, qy_hi)
        do i = 0, c%grid%nn(1) - 1
          call patch_range(i, pc, hh, c%patch%npd(1), qx_lo, qx_hi)
          do f = 1, count
            acc(f) = 0.0_dp
          end do
          do qz = qz_lo, qz_hi
            do qy = qy_lo, qy_hi
              do qx = qx_lo, qx_hi
                q = qx + c%patch%npd(1) * (qy + c%patch%npd(2) * qz)
                slot = slots(q + 1)
                if (slot < 0) cycle
                ln = (i - qx * pc + hh) + qq * ((j - qy * pc + hh) + qq * (k - qz * pc + hh))
                do f = 1, count
                  acc(f) = acc(f) + buf(first + f, ln + 1, slot + 1)
                end do
              end do
            end do
          end do
          n = i + c%grid%nn(1) * (j + c%grid%nn(2) * k) + 1
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

  ! Contact: g_i = sum_p m_p grad N_i(x_p) of the context's particles (outward) into gnormal,
  ! through the force fields of the patch buffers (cxx scatter_mass_gradient).
  subroutine scatter_mass_gradient(c)
    type(step_context), intent(inout) :: c
    real(dp), pointer :: buf(:,:,:), lx(:,:), mass(:), psize(:), gmass(:), gmom(:,:), gnormal(:,:)
    integer(c_int), pointer :: pstart(:), ppart(:), slots(:), cell(:)
    real(dp) :: sn(27), sg(3, 27), mp
    integer :: pc, qq, pn, q, slot, idx, p, base, k, ln, nk
    integer :: ci(3), o(3)
    logical :: wide
    pc = c%patch%patch_cells
    qq = pc + 1 + 2 * c%patch%patch_halo
    pn = qq * qq * qq
    wide = c%method%family == TRANSFER_STENCIL27
    call c_f_pointer(c%grid%gmass, gmass, [c%grid%nnode])
    call c_f_pointer(c%grid%gmom, gmom, [3, c%grid%nnode])
    call c_f_pointer(c%contact%gnormal, gnormal, [3, c%grid%nnode])
    if (c%patch%nslot > 0) then
      call view_buffers(c, buf)
      call c_f_pointer(c%patch%patch_start, pstart, [c%patch%npatch + 1])
      call c_f_pointer(c%patch%patch_part, ppart, [c%part%np])
      call c_f_pointer(c%patch%patch_slot, slots, [c%patch%npatch])
      call c_f_pointer(c%part%cell, cell, [c%part%np])
      call c_f_pointer(c%part%lx, lx, [3, c%part%np])
      call c_f_pointer(c%part%mass, mass, [c%part%np])
      if (c%method%shape == 1) call c_f_pointer(c%part%psize, psize, [c%part%np])
      do q = 0, c%patch%npatch - 1
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
          call particle_shape(c, wide, p, cell(p), lx, psize, ci, o, sn, sg, nk)
          base = stencil_first_local(c, wide, q, cell(p), ci, o)
          do k = 0, nk - 1
            ln = stencil_local(c, wide, base, k)
            buf(5, ln, slot + 1) = buf(5, ln, slot + 1) + (mp * sg(1, k + 1))
            buf(6, ln, slot + 1) = buf(6, ln, slot + 1) + (mp * sg(2, k + 1))
            buf(7, ln, slot + 1) = buf(7, ln, slot + 1) + (mp * sg(3, k + 1))
          end do
        end do
      end do
    end if
    call assemble(c, 4, 3, gmass, gmom, gnormal)
  end subroutine scatter_mass_gradient

  ! The node and buffer index helpers, a copy in this module so that its loops inline them.
  include 'stage_index.inc'

end module mpm3d_stage_p2g
