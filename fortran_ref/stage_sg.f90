! stage_sg: the current MPM3D-F90's smoothed-gradient MPM (sgmp) as
! cxx/transfer/smoothed_gradient.cpp (the family TRANSFER_SMOOTHED_GRADIENT), the
! same operations in the same order: the particles exchange with the cell centres (trilinear
! weights of the auxiliary cell around the nearest node), the cell centres with the corners
! of their cells (1/8 each; one-point gradients at the centre for forces and strain rates).
! The stages call it when c%method%family == TRANSFER_SMOOTHED_GRADIENT. aux(AUX_FIELDS, ncell)
! holds the cells' fields, 1-based field f + 1 for the C++ field f.
module mpm3d_stage_sg
  use, intrinsic :: iso_c_binding
  use mpm3d_material, only: dp
  use mpm3d_stage_common
  implicit none
  private

  public :: sg_p2g, sg_g2p, sg_cell_gradients, sg_velocity_gradient

  integer, parameter :: AUX_FIELDS = 34
  ! Fields (0-based as in C++): mass, momentum, body force, sigma V (Voigt; TLmp: V0 P, 9
  ! entries row by row), G2P velocity and acceleration, remapped momentum, velocity gradient.
  integer, parameter :: AUX_M = 0, AUX_P = 1, AUX_FB = 4, AUX_S = 7, AUX_V = 16, AUX_A = 19, &
                        AUX_RP = 22, AUX_L = 25
  integer, parameter :: GATHER_MASS_MOM = 1, GATHER_FORCES = 2, GATHER_REMAP = 4

contains

  ! The eight auxiliary nodes (0-based cell indices idx) and weights w of a particle in cell
  ! cl at local coordinates lxp, corner k = a + 2 b + 4 c at k + 1; g2p: the G2P rule on
  ! held axes (cxx sg_corner_weights, with the rules sg_lower and sg_beyond).
  subroutine sg_weights(c, cl, lxp, g2p, idx, w)
    type(step_context), intent(in) :: c
    integer, intent(in) :: cl
    real(dp), intent(in) :: lxp(3)
    logical, intent(in) :: g2p
    integer, intent(out) :: idx(8)
    real(dp), intent(out) :: w(8)
    integer :: ci(3), lo(3), hi(3), ijk(3), a, al, near, last, k, n
    real(dp) :: w0(3), w1(3), wk(3), s, x, xn
    logical :: held, beyond(3)
    ci(1) = mod(cl, c%grid%nc(1))
    ci(2) = mod(cl / c%grid%nc(1), c%grid%nc(2))
    ci(3) = cl / (c%grid%nc(1) * c%grid%nc(2))
    do a = 1, 3
      s = lxp(a)
      if (s < 0.5_dp) then
        al = ci(a) - 1
        x = 2.0_dp * s
      else
        al = ci(a)
        x = 2.0_dp * (s - 1.0_dp)
      end if
      near = al + 1
      held = (c%grid%fix(2 * a - 1) /= 0 .and. near <= 1) .or. (c%grid%fix(2 * a) /= 0 .and. near >= c%grid%nn(a) - 2)
      if (held) then
        if (g2p) then
          xn = 2.0_dp * s - 1.0_dp
          if (xn < 0.0_dp) then
            x = 1.0_dp + 2.0_dp * xn
          else
            x = 2.0_dp * xn - 1.0_dp
          end if
        else
          if (x > 0.0_dp) then
            x = 1.0_dp
          else if (x < 0.0_dp) then
            x = -1.0_dp
          else
            x = 0.0_dp
          end if
        end if
      end if
      w0(a) = 0.5_dp * (1.0_dp - x)
      w1(a) = 0.5_dp * (1.0_dp + x)
      last = c%grid%nc(a) - 1
      ! Rules sg_lower=truncate (the first two centres for the outer half of a first cell) and
      ! sg_beyond=drop (no weight for a centre beyond a one-cell axis where the current
      ! program's number for it is past its last cell, below): the current program's.
      if (c%rules%sg_lower /= 0 .and. al < 0) al = 0
      beyond(a) = .false.
      if (c%rules%sg_beyond /= 0 .and. last == 0) then
        if (al < 0) w0(a) = 0.0_dp
        beyond(a) = al + 1 > last
      end if
      if (al < 0) then
        lo(a) = 0
      else if (al > last) then
        lo(a) = last
      else
        lo(a) = al
      end if
      if (al + 1 > last) then
        hi(a) = last
      else
        hi(a) = al + 1
      end if
    end do
    do k = 0, 7
      do a = 1, 3
        if (iand(ishft(k, -(a - 1)), 1) /= 0) then
          ijk(a) = hi(a)
          wk(a) = w1(a)
        else
          ijk(a) = lo(a)
          wk(a) = w0(a)
        end if
      end do
      idx(k + 1) = ijk(1) + c%grid%nc(1) * (ijk(2) + c%grid%nc(2) * ijk(3))
      w(k + 1) = (wk(1) * wk(2)) * wk(3)
      ! sg_beyond=drop: the current program numbers the centre beyond a one-cell axis as one
      ! past its last, the next row's first; past its last cell it skips it (a corner not
      ! beyond any axis numbers its own cell, always within).
      if (any(beyond)) then
        n = 0
        do a = 3, 1, -1
          if (iand(ishft(k, -(a - 1)), 1) /= 0 .and. beyond(a)) then
            n = n * c%grid%nc(a) + c%grid%nc(a)
          else
            n = n * c%grid%nc(a) + ijk(a)
          end if
        end do
        if (n >= c%grid%nc(1) * c%grid%nc(2) * c%grid%nc(3)) w(k + 1) = 0.0_dp
      end if
    end do
  end subroutine sg_weights

  subroutine view_aux(c, aux)
    type(step_context), intent(in) :: c
    real(dp), pointer, intent(out) :: aux(:,:)
    call c_f_pointer(c%sgmp%aux, aux, [AUX_FIELDS, c%grid%nc(1) * c%grid%nc(2) * c%grid%nc(3)])
  end subroutine view_aux

  ! P2G: particles -> cell centres (serial, patches in index order, each list in order),
  ! then cell centres -> nodes.
  subroutine sg_p2g(c, with_mass_mom, with_forces)
    type(step_context), intent(inout) :: c
    logical, intent(in) :: with_mass_mom, with_forces
    real(dp), pointer :: aux(:,:), lx(:,:), v(:,:), sig(:,:), mass(:), vol(:), pk1(:,:)
    integer(c_int), pointer :: pstart(:), ppart(:), cell(:)
    real(dp) :: w(8), vs(9), fb(3), mp, volp, mn
    integer :: idx8(8), q, idx, p, k, s, d, cl, ns
    logical :: with_body
    call view_aux(c, aux)
    if (with_mass_mom) aux(AUX_M + 1:AUX_M + 4, :) = 0.0_dp
    if (with_forces) aux(AUX_FB + 1:AUX_FB + 12, :) = 0.0_dp
    ! TLmp: V0 P (9 entries) in place of sigma V (6).
    ns = 6
    if (c%method%tl /= 0) then
      call c_f_pointer(c%part%pk1, pk1, [9, c%part%np])
      ns = 9
    end if
    call c_f_pointer(c%patch%patch_start, pstart, [c%patch%npatch + 1])
    call c_f_pointer(c%patch%patch_part, ppart, [c%part%np])
    call c_f_pointer(c%part%cell, cell, [c%part%np])
    call c_f_pointer(c%part%lx, lx, [3, c%part%np])
    call c_f_pointer(c%part%v, v, [3, c%part%np])
    call c_f_pointer(c%part%sig, sig, [6, c%part%np])
    call c_f_pointer(c%part%mass, mass, [c%part%np])
    call c_f_pointer(c%part%vol, vol, [c%part%np])
    with_body = c%method%has_body_force /= 0
    do q = 0, c%patch%npatch - 1
      do idx = pstart(q + 1), pstart(q + 2) - 1
        p = ppart(idx + 1) + 1
        cl = cell(p)
        call sg_weights(c, cl, lx(:, p), .false., idx8, w)
        mp = mass(p)
        vs = 0.0_dp
        fb = 0.0_dp
        if (with_forces) then
          if (c%method%tl /= 0) then
            vs = pk1(:, p)
          else
            volp = vol(p)
            do s = 1, 6
              vs(s) = sig(s, p) * volp
            end do
          end if
          if (with_body) call particle_body_force(c, p, fb)
        end if
        do k = 1, 8
          if (with_mass_mom) then
            mn = mp * w(k)
            aux(AUX_M + 1, idx8(k) + 1) = aux(AUX_M + 1, idx8(k) + 1) + mn
            do d = 1, 3
              aux(AUX_P + d, idx8(k) + 1) = aux(AUX_P + d, idx8(k) + 1) + (mn * v(d, p))
            end do
          end if
          if (with_forces) then
            if (with_body) then
              do d = 1, 3
                aux(AUX_FB + d, idx8(k) + 1) = aux(AUX_FB + d, idx8(k) + 1) + (w(k) * fb(d))
              end do
            end if
            do s = 1, ns
              aux(AUX_S + s, idx8(k) + 1) = aux(AUX_S + s, idx8(k) + 1) + (w(k) * vs(s))
            end do
          end if
        end do
      end do
    end do
    k = 0
    if (with_mass_mom) k = k + GATHER_MASS_MOM
    if (with_forces) k = k + GATHER_FORCES
    call gather_to_nodes(c, aux, k)
  end subroutine sg_p2g

  ! Every node's share of the cell centres around it, the cells in ascending order.
  subroutine gather_to_nodes(c, aux, what)
    type(step_context), intent(inout) :: c
    real(dp), intent(in) :: aux(:,:)
    integer, intent(in) :: what
    real(dp), pointer :: gmass(:), gmom(:,:), gforce(:,:)
    real(dp) :: m, pm(3), f(3), gs, gx, gy, gz, fx, fy, fz
    integer :: i, j, k, cx, cy, cz, cell, n, d
    call c_f_pointer(c%grid%gmass, gmass, [c%grid%nnode])
    call c_f_pointer(c%grid%gmom, gmom, [3, c%grid%nnode])
    call c_f_pointer(c%grid%gforce, gforce, [3, c%grid%nnode])
    gs = 0.25_dp * c%grid%inv_h
    do k = 0, c%grid%nn(3) - 1
      do j = 0, c%grid%nn(2) - 1
        do i = 0, c%grid%nn(1) - 1
          m = 0.0_dp
          pm = 0.0_dp
          f = 0.0_dp
          do cz = k - 1, k
            if (cz < 0 .or. cz >= c%grid%nc(3)) cycle
            do cy = j - 1, j
              if (cy < 0 .or. cy >= c%grid%nc(2)) cycle
              do cx = i - 1, i
                if (cx < 0 .or. cx >= c%grid%nc(1)) cycle
                cell = cx + c%grid%nc(1) * (cy + c%grid%nc(2) * cz) + 1
                if (iand(what, GATHER_MASS_MOM) /= 0) then
                  if (aux(AUX_M + 1, cell) > c%grid%mass_cutoff) then
                    m = m + (0.125_dp * aux(AUX_M + 1, cell))
                    do d = 1, 3
                      pm(d) = pm(d) + (0.125_dp * aux(AUX_P + d, cell))
                    end do
                  end if
                end if
                if (iand(what, GATHER_REMAP) /= 0) then
                  do d = 1, 3
                    pm(d) = pm(d) + (0.125_dp * aux(AUX_RP + d, cell))
                  end do
                end if
                if (iand(what, GATHER_FORCES) /= 0) then
                  gx = merge(gs, -gs, cx == i - 1)
                  gy = merge(gs, -gs, cy == j - 1)
                  gz = merge(gs, -gs, cz == k - 1)
                  if (c%method%tl /= 0) then  ! V0 P: row a gives force component a
                    fx = -(((aux(AUX_S + 1, cell) * gx) + (aux(AUX_S + 2, cell) * gy)) + (aux(AUX_S + 3, cell) * gz))
                    fy = -(((aux(AUX_S + 4, cell) * gx) + (aux(AUX_S + 5, cell) * gy)) + (aux(AUX_S + 6, cell) * gz))
                    fz = -(((aux(AUX_S + 7, cell) * gx) + (aux(AUX_S + 8, cell) * gy)) + (aux(AUX_S + 9, cell) * gz))
                  else
                    fx = -(((aux(AUX_S + 1, cell) * gx) + (aux(AUX_S + 6, cell) * gy)) + (aux(AUX_S + 5, cell) * gz))
                    fy = -(((aux(AUX_S + 6, cell) * gx) + (aux(AUX_S + 2, cell) * gy)) + (aux(AUX_S + 4, cell) * gz))
                    fz = -(((aux(AUX_S + 5, cell) * gx) + (aux(AUX_S + 4, cell) * gy)) + (aux(AUX_S + 3, cell) * gz))
                  end if
                  f(1) = f(1) + ((0.125_dp * aux(AUX_FB + 1, cell)) + fx)
                  f(2) = f(2) + ((0.125_dp * aux(AUX_FB + 2, cell)) + fy)
                  f(3) = f(3) + ((0.125_dp * aux(AUX_FB + 3, cell)) + fz)
                end if
              end do
            end do
          end do
          n = i + c%grid%nn(1) * (j + c%grid%nn(2) * k) + 1
          if (iand(what, GATHER_MASS_MOM) /= 0) gmass(n) = m
          if (iand(what, GATHER_MASS_MOM + GATHER_REMAP) /= 0) gmom(:, n) = pm
          if (iand(what, GATHER_FORCES) /= 0) gforce(:, n) = f
        end do
      end do
    end do
  end subroutine gather_to_nodes

  ! Node index (1-based) of corner k (0..7) of cell (i, j, l).
  pure integer function corner_node(c, i, j, l, k)
    type(step_context), intent(in) :: c
    integer, intent(in) :: i, j, l, k
    corner_node = (i + iand(k, 1)) + c%grid%nn(1) * ((j + iand(ishft(k, -1), 1)) + c%grid%nn(2) * (l + iand(ishft(k, -2), 1))) + 1
  end function corner_node

  ! G2P: cell-centre velocities and accelerations, the particles' update, and with remap the
  ! new momenta through the cell centres to the nodes (the caller applies the BC).
  subroutine sg_g2p(c, remap)
    type(step_context), intent(inout) :: c
    logical, intent(in) :: remap
    real(dp), pointer :: aux(:,:), lx(:,:), v(:,:), x(:,:), mass(:), gmass(:), gmom(:,:), gforce(:,:)
    integer(c_int), pointer :: pstart(:), ppart(:), cell(:)
    real(dp) :: cxx(3), vel(3), acc(3), w8(8), wc, m, r, ax, ay, az, ux, uy, uz, mp, mn
    integer :: ijk(3), i, j, l, cl, corner, n, a, d, p, k, q, idx, idx8(8)
    logical :: face
    call view_aux(c, aux)
    call c_f_pointer(c%grid%gmass, gmass, [c%grid%nnode])
    call c_f_pointer(c%grid%gmom, gmom, [3, c%grid%nnode])
    call c_f_pointer(c%grid%gforce, gforce, [3, c%grid%nnode])
    do l = 0, c%grid%nc(3) - 1
      do j = 0, c%grid%nc(2) - 1
        do i = 0, c%grid%nc(1) - 1
          ijk = [i, j, l]
          cxx = 0.0_dp
          face = .false.
          do a = 1, 3
            if (c%grid%nc(a) == 1) cycle
            if (ijk(a) == 0) cxx(a) = 1.0_dp
            if (ijk(a) == c%grid%nc(a) - 1) cxx(a) = -1.0_dp
            face = face .or. (ijk(a) == 0 .and. c%grid%fix(2 * a - 1) /= 0) .or. &
                   (ijk(a) == c%grid%nc(a) - 1 .and. c%grid%fix(2 * a) /= 0)
          end do
          vel = 0.0_dp
          acc = 0.0_dp
          do corner = 0, 7
            n = corner_node(c, i, j, l, corner)
            m = gmass(n)
            if (.not. (m > c%grid%mass_cutoff)) cycle
            wc = 0.125_dp
            if (face) then
              wc = 1.0_dp
              do a = 1, 3
                if (iand(ishft(corner, -(a - 1)), 1) /= 0) then
                  wc = wc * (0.5_dp * (1.0_dp + cxx(a)))
                else
                  wc = wc * (0.5_dp * (1.0_dp + (-cxx(a))))
                end if
              end do
            end if
            r = wc / m
            do d = 1, 3
              vel(d) = vel(d) + (gmom(d, n) * r)
              acc(d) = acc(d) + (gforce(d, n) * r)
            end do
          end do
          cl = i + c%grid%nc(1) * (j + c%grid%nc(2) * l) + 1
          aux(AUX_V + 1:AUX_V + 3, cl) = vel
          aux(AUX_A + 1:AUX_A + 3, cl) = acc
        end do
      end do
    end do
    call c_f_pointer(c%part%cell, cell, [c%part%np])
    call c_f_pointer(c%part%lx, lx, [3, c%part%np])
    call c_f_pointer(c%part%v, v, [3, c%part%np])
    call c_f_pointer(c%part%x, x, [3, c%part%np])
    call c_f_pointer(c%part%mass, mass, [c%part%np])
    do p = 1, c%part%np
      if (cell(p) < 0) cycle
      call sg_weights(c, cell(p), lx(:, p), .true., idx8, w8)
      ax = 0.0_dp
      ay = 0.0_dp
      az = 0.0_dp
      ux = 0.0_dp
      uy = 0.0_dp
      uz = 0.0_dp
      do k = 1, 8
        cl = idx8(k) + 1
        ax = ax + (w8(k) * aux(AUX_A + 1, cl))
        ay = ay + (w8(k) * aux(AUX_A + 2, cl))
        az = az + (w8(k) * aux(AUX_A + 3, cl))
        ux = ux + (w8(k) * aux(AUX_V + 1, cl))
        uy = uy + (w8(k) * aux(AUX_V + 2, cl))
        uz = uz + (w8(k) * aux(AUX_V + 3, cl))
      end do
      v(1, p) = v(1, p) + (ax * c%clock%dt_int)
      v(2, p) = v(2, p) + (ay * c%clock%dt_int)
      v(3, p) = v(3, p) + (az * c%clock%dt_int)
      x(1, p) = x(1, p) + (ux * c%clock%dt)
      x(2, p) = x(2, p) + (uy * c%clock%dt)
      x(3, p) = x(3, p) + (uz * c%clock%dt)
    end do
    if (.not. remap) return
    aux(AUX_RP + 1:AUX_RP + 3, :) = 0.0_dp
    call c_f_pointer(c%patch%patch_start, pstart, [c%patch%npatch + 1])
    call c_f_pointer(c%patch%patch_part, ppart, [c%part%np])
    do q = 0, c%patch%npatch - 1
      do idx = pstart(q + 1), pstart(q + 2) - 1
        p = ppart(idx + 1) + 1
        call sg_weights(c, cell(p), lx(:, p), .false., idx8, w8)
        mp = mass(p)
        do k = 1, 8
          cl = idx8(k) + 1
          mn = mp * w8(k)
          do d = 1, 3
            aux(AUX_RP + d, cl) = aux(AUX_RP + d, cl) + (mn * v(d, p))
          end do
        end do
      end do
    end do
    call gather_to_nodes(c, aux, GATHER_REMAP)
  end subroutine sg_g2p

  ! Stress: each cell's velocity gradient from its corners above the mass cut-off, at its
  ! centre (grad N = +-1/(4h) per axis).
  subroutine sg_cell_gradients(c)
    type(step_context), intent(inout) :: c
    real(dp), pointer :: aux(:,:), gmass(:), gmom(:,:)
    real(dp) :: lg(0:8), g(3), gs, m, va
    integer :: i, j, l, corner, n, a, b
    call view_aux(c, aux)
    call c_f_pointer(c%grid%gmass, gmass, [c%grid%nnode])
    call c_f_pointer(c%grid%gmom, gmom, [3, c%grid%nnode])
    gs = 0.25_dp * c%grid%inv_h
    do l = 0, c%grid%nc(3) - 1
      do j = 0, c%grid%nc(2) - 1
        do i = 0, c%grid%nc(1) - 1
          lg = 0.0_dp
          do corner = 0, 7
            n = corner_node(c, i, j, l, corner)
            m = gmass(n)
            if (.not. (m > c%grid%mass_cutoff)) cycle
            do a = 1, 3
              g(a) = merge(gs, -gs, iand(ishft(corner, -(a - 1)), 1) /= 0)
            end do
            do a = 0, 2
              va = gmom(a + 1, n) / m
              do b = 0, 2
                lg(3 * a + b) = lg(3 * a + b) + (va * g(b + 1))
              end do
            end do
          end do
          aux(AUX_L + 1:AUX_L + 9, i + c%grid%nc(1) * (j + c%grid%nc(2) * l) + 1) = lg
        end do
      end do
    end do
  end subroutine sg_cell_gradients

  ! The velocity gradient lg(3a+b) = dv_a/dx_b of a particle in cell cl at lxp.
  subroutine sg_velocity_gradient(c, cl, lxp, lg)
    type(step_context), intent(in) :: c
    integer, intent(in) :: cl
    real(dp), intent(in) :: lxp(3)
    real(dp), intent(out) :: lg(0:8)
    real(dp), pointer :: aux(:,:)
    real(dp) :: w8(8)
    integer :: idx8(8), k, r
    call view_aux(c, aux)
    call sg_weights(c, cl, lxp, .false., idx8, w8)
    lg = 0.0_dp
    do k = 1, 8
      do r = 0, 8
        lg(r) = lg(r) + (w8(k) * aux(AUX_L + 1 + r, idx8(k) + 1))
      end do
    end do
  end subroutine sg_velocity_gradient

end module mpm3d_stage_sg
