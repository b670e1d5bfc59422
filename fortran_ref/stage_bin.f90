! stage_bin: the bin stage (bind(C) mpm3d_f_bin): particles to cells and patches, the
! patch particle lists and the buffer slots of the non-empty patches.
module mpm3d_stage_bin
  use, intrinsic :: iso_c_binding
  use mpm3d_material, only: dp
  use mpm3d_stage_common
  implicit none
  private

  public :: mpm3d_f_bin

contains

  ! Bin: local coordinates, base cells, patch particle lists (ascending particle index
  ! within each patch) and buffer slots of the non-empty patches. Prebinned particles (a
  ! distributed run's) are binned again: the same values.
  subroutine mpm3d_f_bin(c) bind(C, name='mpm3d_f_bin')
    type(step_context), intent(inout) :: c
    real(dp), pointer :: x(:,:), lx(:,:)
    integer(c_int), pointer :: start(:), ppart(:), slots(:), cell(:), body(:), bcomp(:), order(:)
    integer :: pc, q, p, a, outside, nslot, i, j, k, cl, n
    integer :: idx(3)
    real(dp) :: t, fl, f0
    logical :: inside, filter, has_order
    pc = c%patch%patch_cells
    call view_components(c, filter, body, bcomp)     ! contact: this context's component only
    call c_f_pointer(c%part%xbin, x, [3, c%part%np])   ! the reference positions under TLmp
    call c_f_pointer(c%part%lx, lx, [3, c%part%np])
    call view_patch_lists(c, start, ppart, slots, cell)
    ! start(q + 1) is C's start[q].
    do q = 0, c%patch%npatch
      start(q + 1) = 0
    end do
    outside = 0
    do p = 1, c%part%np
      if (filter) then
        if (other_component(c, p, body, bcomp)) cycle
      end if
      inside = .true.
      do a = 1, 3
        ! Cell on the deck's lattice, then in the window (the same bits for any window).
        t = (x(a, p) - c%grid%origin(a)) / c%grid%h
        fl = aint(t)                      ! floor(t) as a double, exactly (NaN stays NaN)
        if (fl > t) fl = fl - 1.0_dp
        f0 = real(c%grid%cell_off(a), dp)
        if (.not. (fl >= f0 .and. fl < f0 + real(c%grid%nc(a), dp))) then   ! also catches NaN
          inside = .false.
          exit
        end if
        idx(a) = int(fl) - c%grid%cell_off(a)
        lx(a, p) = t - fl
      end do
      if (.not. inside) then
        cell(p) = -1
        outside = outside + 1
        cycle
      end if
      ! Rule tl_shape=centre, trilinear TLmp: the particle at its reference cell's centre (the
      ! current program never sets these natural coordinates; they stay 0).
      if (c%method%tl /= 0 .and. c%rules%tl_shape /= 0 .and. c%method%family == TRANSFER_TRILINEAR) lx(:, p) = 0.5_dp
      cell(p) = idx(1) + c%grid%nc(1) * (idx(2) + c%grid%nc(2) * idx(3))
      q = idx(1) / pc + c%patch%npd(1) * (idx(2) / pc + c%patch%npd(2) * (idx(3) / pc))
      start(q + 2) = start(q + 2) + 1
    end do
    nslot = 0
    do q = 0, c%patch%npatch - 1
      if (start(q + 2) > 0) then
        slots(q + 1) = nslot
        nslot = nslot + 1
      else
        slots(q + 1) = -1
      end if
      start(q + 2) = start(q + 2) + start(q + 1)
    end do
    c%patch%nslot = nslot
    c%out%noutside = outside
    ! Second pass: a stable counting sort; the end offsets serve as fill pointers. The
    ! particles go in one process's storage order (a distributed run's c%ranks%order).
    do q = c%patch%npatch, 1, -1
      start(q + 1) = start(q)
    end do
    start(1) = 0
    has_order = c_associated(c%ranks%order)
    if (has_order) call c_f_pointer(c%ranks%order, order, [c%part%np])
    do n = 1, c%part%np
      p = n
      if (has_order) p = order(n) + 1
      if (filter) then
        if (other_component(c, p, body, bcomp)) cycle
      end if
      cl = cell(p)
      if (cl < 0) cycle
      i = mod(cl, c%grid%nc(1))
      j = mod(cl / c%grid%nc(1), c%grid%nc(2))
      k = cl / (c%grid%nc(1) * c%grid%nc(2))
      q = i / pc + c%patch%npd(1) * (j / pc + c%patch%npd(2) * (k / pc))
      ppart(start(q + 2) + 1) = p - 1
      start(q + 2) = start(q + 2) + 1
    end do
  end subroutine mpm3d_f_bin

  ! The views of the context's arrays, a copy in this module so that its loops inline them.
  include 'stage_views.inc'

end module mpm3d_stage_bin
