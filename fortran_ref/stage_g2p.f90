! stage_g2p: grid to particle (bind(C) mpm3d_f_g2p): particle velocities and positions from
! the nodes, trilinear or GIMP; MUSL also remaps the momenta to the nodes.
module mpm3d_stage_g2p
  use, intrinsic :: iso_c_binding
  use mpm3d_material, only: dp
  use mpm3d_grid, only: shape_linear
  use mpm3d_stage_common
  use mpm3d_stage_p2g, only: assemble
  use mpm3d_stage_sg, only: sg_g2p
  implicit none
  private

  public :: mpm3d_f_g2p

contains

  ! G2P: particle velocity and position from the grid; MUSL: momentum remap and BC.
  subroutine mpm3d_f_g2p(c) bind(C, name='mpm3d_f_g2p')
    type(step_context), intent(inout) :: c
    real(dp), pointer :: buf(:,:,:), lx(:,:), v(:,:), x(:,:), mass(:)
    real(dp), pointer :: gmass(:), gmom(:,:), gforce(:,:), psize(:)
    integer(c_int), pointer :: pstart(:), ppart(:), slots(:), cell(:)
    real(dp) :: sn(27), sg(3, 27), acc(3), vel(3), m, r, mp, mn
    integer :: pc, qq, pn, q, slot, idx, p, base, pbase, k, n, a, ln, nk
    integer :: ci(3), o(3)
    logical :: remap, wide
    remap = c%method%scheme == SCHEME_MUSL
    if (c%method%family == TRANSFER_SMOOTHED_GRADIENT) then
      call sg_g2p(c, remap)
      if (remap) then
        call c_f_pointer(c%grid%gmom, gmom, [3, c%grid%nnode])
        call apply_bc(c, gmom)
      end if
      return
    end if
    pc = c%patch%patch_cells
    qq = pc + 1 + 2 * c%patch%patch_halo
    pn = qq * qq * qq
    wide = c%method%family == TRANSFER_STENCIL27
    if (c%method%shape == 1) call c_f_pointer(c%part%psize, psize, [c%part%np])
    call c_f_pointer(c%grid%gmass, gmass, [c%grid%nnode])
    call c_f_pointer(c%grid%gmom, gmom, [3, c%grid%nnode])
    call c_f_pointer(c%grid%gforce, gforce, [3, c%grid%nnode])
    if (c%patch%nslot > 0) then
      call view_buffers(c, buf)
      call view_patch_lists(c, pstart, ppart, slots, cell)
      call c_f_pointer(c%part%lx, lx, [3, c%part%np])
      call c_f_pointer(c%part%v, v, [3, c%part%np])
      call c_f_pointer(c%part%x, x, [3, c%part%np])
      call c_f_pointer(c%part%mass, mass, [c%part%np])
      do q = 0, c%patch%npatch - 1
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
          call particle_shape(c, wide, p, cell(p), lx, psize, ci, o, sn, sg, nk)
          base = stencil_first_node(c, wide, cell(p), ci, o)
          acc = 0.0_dp
          vel = 0.0_dp
          do k = 0, nk - 1
            n = stencil_node(c, wide, base, k)
            m = gmass(n)
            if (.not. (m > c%grid%mass_cutoff)) cycle
            r = sn(k + 1) / m
            do a = 1, 3
              acc(a) = acc(a) + (gforce(a, n) * r)
              vel(a) = vel(a) + (gmom(a, n) * r)
            end do
          end do
          do a = 1, 3
            v(a, p) = v(a, p) + (acc(a) * c%clock%dt_int)
            x(a, p) = x(a, p) + (vel(a) * c%clock%dt)
          end do
          if (remap) then
            pbase = stencil_first_local(c, wide, q, cell(p), ci, o)
            mp = mass(p)
            do k = 0, nk - 1
              ln = stencil_local(c, wide, pbase, k)
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

  ! The node and buffer index helpers and the views, a copy in this module so that its loops
  ! inline them.
  include 'stage_index.inc'
  include 'stage_views.inc'

end module mpm3d_stage_g2p
