! stage_energy: the energy stage (bind(C) mpm3d_f_energy): kinetic and internal energy,
! momentum and the rate of the external work bound, as one column of partial sums per patch
! (and one for the particles outside the grid) folded in column order, as mpm3d_cxx_energy.
module mpm3d_stage_energy
  use, intrinsic :: iso_c_binding
  use mpm3d_material, only: dp
  use mpm3d_stage_common
  implicit none
  private

  public :: mpm3d_f_energy

contains

  ! Energy: result(1:5) = sum_p (m_p |v_p|^2 / 2, e_p, m_p v_p), result(9) = sum_p |f_p . v_p|
  ! and result(10) = sum_p f_p . v_p with the point loads ramped as P2G applies them (QuLo)
  ! (0 without body forces). Column q+1 (q = 0..npatch-1) sums patch q's list, then (contact)
  ! component 2's list of patch q; column npatch+1 the particles outside the grid (cell < 0,
  ! the cell array shared by both components) in ascending index, scanned only when there are
  ! any. All columns first, then every column folded in column order from 0.0.
  subroutine mpm3d_f_energy(c) bind(C, name='mpm3d_f_energy')
    type(step_context), intent(inout), target :: c
    type(step_context), pointer :: c2
    real(dp), pointer :: partials(:,:), mass(:), v(:,:), ie(:), grav(:,:), fext(:,:)
    integer(c_int), pointer :: cell(:), body(:), start(:), ppart(:), start2(:), ppart2(:), order(:)
    real(dp) :: part(REDUCE_FIELDS), s(REDUCE_FIELDS)
    integer :: q, p, i, noutside
    logical :: contact, work, has_fext
    contact = c_associated(c%contact%other)
    work = c%method%has_body_force /= 0
    has_fext = c_associated(c%part%fext)
    noutside = c%out%noutside
    call c_f_pointer(c%part%mass, mass, [c%part%np])
    call c_f_pointer(c%part%v, v, [3, c%part%np])
    call c_f_pointer(c%part%ie, ie, [c%part%np])
    call c_f_pointer(c%part%body, body, [c%part%np])
    if (work) call c_f_pointer(c%part%gravity, grav, [3, max(c%part%nbody, 1)])
    if (has_fext) call c_f_pointer(c%part%fext, fext, [3, c%part%np])
    call c_f_pointer(c%part%cell, cell, [c%part%np])
    call c_f_pointer(c%patch%patch_start, start, [c%patch%npatch + 1])
    call c_f_pointer(c%patch%patch_part, ppart, [c%part%np])
    if (contact) then
      call c_f_pointer(c%contact%other, c2)
      noutside = noutside + c2%out%noutside
      call c_f_pointer(c2%patch%patch_start, start2, [c2%patch%npatch + 1])
      call c_f_pointer(c2%patch%patch_part, ppart2, [c2%part%np])
    end if
    call c_f_pointer(c%out%partials, partials, [REDUCE_FIELDS, c%patch%npatch + 1])
    do q = 0, c%patch%npatch - 1
      part = 0.0_dp
      do i = start(q + 1) + 1, start(q + 2)
        call add_particle(ppart(i) + 1)
      end do
      if (contact) then
        do i = start2(q + 1) + 1, start2(q + 2)
          call add_particle(ppart2(i) + 1)
        end do
      end if
      partials(:, q + 1) = part
    end do
    part = 0.0_dp
    if (noutside > 0) then   ! in one process's storage order (a distributed run's c%ranks%order)
      if (c_associated(c%ranks%order)) then
        call c_f_pointer(c%ranks%order, order, [c%part%np])
        do i = 1, c%part%np
          p = order(i) + 1
          if (cell(p) < 0) call add_particle(p)
        end do
      else
        do p = 1, c%part%np
          if (cell(p) < 0) call add_particle(p)
        end do
      end if
    end if
    partials(:, c%patch%npatch + 1) = part
    ! The fold, apart from the columns (a distributed run's ranks exchange them first).
    call rank_exchange(c, EXCHANGE_PARTIALS, 0, 0)
    s = 0.0_dp
    do q = 1, c%patch%npatch + 1
      s = s + partials(:, q)
    end do
    c%out%result(1:5) = s(1:5)
    c%out%result(9) = s(6)
    c%out%result(10) = s(7)

  contains

    ! Adds particle p (1-based) to part (the C++ add_particle): m |v|^2 / 2, e, m v and, with
    ! body forces, |f . v| with f = m g + f_ext (neither ramped nor damped).
    subroutine add_particle(p)
      integer, intent(in) :: p
      real(dp) :: m, f, fe, pw, sw, tr
      integer :: a
      m = mass(p)
      part(1) = part(1) + ((0.5_dp * m) * (((v(1, p) * v(1, p)) + (v(2, p) * v(2, p))) + (v(3, p) * v(3, p))))
      part(2) = part(2) + ie(p)
      part(3) = part(3) + (m * v(1, p))
      part(4) = part(4) + (m * v(2, p))
      part(5) = part(5) + (m * v(3, p))
      if (.not. work) return
      pw = 0.0_dp
      do a = 1, 3
        fe = 0.0_dp
        if (has_fext) fe = fext(a, p)
        f = (m * grav(a, body(p) + 1)) + fe
        pw = pw + (f * v(a, p))
      end do
      part(6) = part(6) + abs(pw)
      sw = pw
      tr = c%method%load_ramp_time
      if (has_fext .and. tr > 0.0_dp .and. c%clock%time < tr) then  ! QuLo: (f_ext / T) t
        sw = 0.0_dp
        do a = 1, 3
          f = (m * grav(a, body(p) + 1)) + ((fext(a, p) / tr) * c%clock%time)
          sw = sw + (f * v(a, p))
        end do
      end if
      part(7) = part(7) + sw
    end subroutine add_particle

  end subroutine mpm3d_f_energy

end module mpm3d_stage_energy
