! stage_grid: the grid update: integration of the nodal momenta (bind(C) mpm3d_f_integrate)
! and the multi-velocity contact between two components (mpm3d_f_contact, mpm3d_f_recontact).
module mpm3d_stage_grid
  use, intrinsic :: iso_c_binding
  use mpm3d_material, only: dp
  use mpm3d_stage_common
  use mpm3d_stage_p2g, only: scatter_mass_gradient
  implicit none
  private

  public :: mpm3d_f_integrate, mpm3d_f_contact, mpm3d_f_recontact

contains

  ! Integrate: p += f dt_int; boundary conditions on momentum and force.
  subroutine mpm3d_f_integrate(c) bind(C, name='mpm3d_f_integrate')
    type(step_context), intent(inout) :: c
    real(dp), pointer :: gmom(:,:), gforce(:,:)
    real(dp) :: dt
    integer :: n, a
    call c_f_pointer(c%grid%gmom, gmom, [3, c%grid%nnode])
    call c_f_pointer(c%grid%gforce, gforce, [3, c%grid%nnode])
    dt = c%clock%dt_int
    do n = 1, c%grid%nnode
      do a = 1, 3
        gmom(a, n) = gmom(a, n) + (gforce(a, n) * dt)
      end do
    end do
    call apply_bc(c, gmom)
    call apply_bc(c, gforce)
  end subroutine mpm3d_f_integrate

  ! Contact: multi-velocity correction between component 1 (c) and component 2 (c%contact%other),
  ! as mpm3d_cxx_contact (see there for the algorithm): same nodes, same operations, the
  ! contact force as per-patch partials folded in patch order into result(6:8), the unit
  ! normals of the corrected nodes kept in c%contact%gnormal (zero at the other nodes of the loop).
  subroutine mpm3d_f_contact(c) bind(C, name='mpm3d_f_contact')
    type(step_context), intent(inout), target :: c
    type(step_context), pointer :: c2
    if (.not. c_associated(c%contact%other)) return
    call c_f_pointer(c%contact%other, c2)
    call scatter_mass_gradient(c)
    call scatter_mass_gradient(c2)
    call contact_correct(c, .false.)
  end subroutine mpm3d_f_contact

  ! The momenta of the nodes marked in contact by mpm3d_f_contact corrected again with the
  ! kept normals, for either sign of q.n (as mpm3d_cxx_recontact): MUSL after the remap of
  ! this step, USF after the P2G of the next step.
  subroutine mpm3d_f_recontact(c) bind(C, name='mpm3d_f_recontact')
    type(step_context), intent(inout), target :: c
    if (.not. c_associated(c%contact%other)) return
    call contact_correct(c, .true.)
  end subroutine mpm3d_f_recontact

  ! The correction of both stages: remap false, mpm3d_f_contact (marks the nodes, adds the
  ! contact forces); remap true, mpm3d_f_recontact (the marked nodes' momenta only).
  subroutine contact_correct(c, remap)
    type(step_context), intent(inout), target :: c
    logical, intent(in) :: remap
    type(step_context), pointer :: c2
    real(dp), pointer :: m1(:), m2(:), p1(:,:), p2(:,:), f1(:,:), f2(:,:), g1(:,:), g2(:,:), cpart(:,:)
    real(dp) :: part(3), nv(3), un(3), qv(3), t(3), len, mt, qn, tl, fr, ft, d, fc, s(4), dt_force
    integer :: q, i, j, k, n, a, nb, ncount
    integer :: q3(3), lo(3), hi(3)
    call c_f_pointer(c%contact%other, c2)
    call c_f_pointer(c%grid%gmass, m1, [c%grid%nnode])
    call c_f_pointer(c2%grid%gmass, m2, [c%grid%nnode])
    call c_f_pointer(c%grid%gmom, p1, [3, c%grid%nnode])
    call c_f_pointer(c2%grid%gmom, p2, [3, c%grid%nnode])
    call c_f_pointer(c%grid%gforce, f1, [3, c%grid%nnode])
    call c_f_pointer(c2%grid%gforce, f2, [3, c%grid%nnode])
    call c_f_pointer(c%contact%gnormal, g1, [3, c%grid%nnode])
    call c_f_pointer(c2%contact%gnormal, g2, [3, c%grid%nnode])
    call c_f_pointer(c%contact%cpartials, cpart, [4, c%patch%npatch])
    nb = c%contact%contact_normbody
    ! Rule contact=original: the force by the full dt also in the first step (of half dt).
    if (c%rules%contact /= 0) then
      dt_force = c%clock%dt
    else
      dt_force = c%clock%dt_int
    end if
    do q = 0, c%patch%npatch - 1
      part = 0.0_dp
      ncount = 0
      q3(1) = mod(q, c%patch%npd(1))
      q3(2) = mod(q / c%patch%npd(1), c%patch%npd(2))
      q3(3) = q / (c%patch%npd(1) * c%patch%npd(2))
      do a = 1, 3
        lo(a) = q3(a) * c%patch%patch_cells
        if (q3(a) == c%patch%npd(a) - 1) then
          hi(a) = c%grid%nn(a)
        else
          hi(a) = lo(a) + c%patch%patch_cells
        end if
      end do
      if (patch_active(c, q3) .and. patch_active(c2, q3)) then
        do k = lo(3), hi(3) - 1
          do j = lo(2), hi(2) - 1
            do i = lo(1), hi(1) - 1
              n = i + c%grid%nn(1) * (j + c%grid%nn(2) * k) + 1
              if (.not. (m1(n) > c%grid%mass_cutoff) .or. .not. (m2(n) > c%grid%mass_cutoff)) then
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
              fr = c%contact%contact_mu * abs(qn)
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
                  fc = d / dt_force
                  f1(a, n) = f1(a, n) + fc
                  f2(a, n) = f2(a, n) - fc
                  part(a) = part(a) + fc
                end if
              end do
              ncount = ncount + 1
            end do
          end do
        end do
      else if (.not. remap .and. c%method%scheme == SCHEME_USF) then
        ! USF reads the marks again in the next step: no node outside the loop keeps one.
        do k = lo(3), hi(3) - 1
          do j = lo(2), hi(2) - 1
            do i = lo(1), hi(1) - 1
              n = i + c%grid%nn(1) * (j + c%grid%nn(2) * k) + 1
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
        cpart(4, q + 1) = real(ncount, dp)
      end if
    end do
    call apply_bc(c, p1)
    call apply_bc(c2, p2)
    if (remap) return
    ! The per-patch force and count folded in patch order (cxx contact_correct), after a
    ! distributed run's ranks exchanged their columns.
    call rank_exchange(c, EXCHANGE_CONTACT, 0, 0)
    s = 0.0_dp
    do q = 1, c%patch%npatch
      do a = 1, 4
        s(a) = s(a) + cpart(a, q)
      end do
    end do
    do a = 1, 3
      c%out%result(5 + a) = s(a)
    end do
    c%contact%ncontact = int(s(4))
    call apply_bc(c, f1)
    call apply_bc(c2, f2)
  end subroutine contact_correct

  ! True when patch q3 (0-based coordinates) is active: it or one of its lower neighbours
  ! (halo 1: one of its 26 neighbours) holds particles (cxx owned_nodes).
  logical function patch_active(c, q3)
    type(step_context), intent(in) :: c
    integer, intent(in) :: q3(3)
    integer(c_int), pointer :: slots(:)
    integer :: ne, cx, cy, cz, px, py, pz
    call c_f_pointer(c%patch%patch_slot, slots, [c%patch%npatch])
    patch_active = .false.
    ne = 2 + c%patch%patch_halo
    do cz = 0, ne - 1
      do cy = 0, ne - 1
        do cx = 0, ne - 1
          px = q3(1) - 1 + cx
          py = q3(2) - 1 + cy
          pz = q3(3) - 1 + cz
          if (px < 0 .or. py < 0 .or. pz < 0) cycle
          if (px >= c%patch%npd(1) .or. py >= c%patch%npd(2) .or. pz >= c%patch%npd(3)) cycle
          if (slots(px + c%patch%npd(1) * (py + c%patch%npd(2) * pz) + 1) >= 0) patch_active = .true.
        end do
      end do
    end do
  end function patch_active

end module mpm3d_stage_grid
