! The end of a deck ('endi'), as cxx/input/data_in_finish.cpp: the checks of the whole deck, then
! lighting times, initial energies and temperatures, GIMP sizes, dt, mass cut-off, base name.
submodule (mpm3d_data_in) mpm3d_data_in_finish
  implicit none

contains

  module procedure finish
    integer :: i, a, p, slash, dot, k, at
    real(dp) :: n, fl, c_max, rho_sum, dmin, dx, dy, dz, d, lp, nodes, need
    logical :: thermal, hiex, clamped
    character(len=:), allocatable :: base
    character(len=32) :: buf
    if (m%nbmp < 0) call ts%fail(line, "no 'nbmp' (number of particles) before 'endi'")
    if (m%nmat < 0) call ts%fail(line, "no 'nmat' (number of materials) before 'endi'")
    if (n_defined(m) /= m%nbmp) &
      call ts%fail(line, "'nbmp' = " // i2s(m%nbmp) // ' but the particle cards define ' // i2s(n_defined(m)))
    if (m%nbbo >= 0 .and. m%nbodies /= m%nbbo) &
      call ts%fail(line, "'nbbo' = " // i2s(m%nbbo) // ' but ' // i2s(m%nbodies) // ' particle cards were read')
    do i = 1, m%nmat
      if (m%mats(i)%type == 0) call ts%fail(line, 'material ' // i2s(i) // " has no 'mate' card")
    end do
    do a = 1, 3
      if (.not. m%box_set(a)) &
        call ts%fail(line, 'no grid box along ' // achar(iachar('x') + a - 1) // ' (spx/spy/spz or grid)')
    end do
    if (.not. (m%dcell > 0.0_dp)) call ts%fail(line, "no cell size ('dcel')")
    if (.not. (m%endtime > 0.0_dp)) call ts%fail(line, "no end time ('endt')")
    if (m%contact .and. m%nbco /= 2) call ts%fail(m%contact_line, "'cont' needs two components ('nbco 2')")
    if (m%contact .and. m%scheme == SCHEME_USL) call warn(m, &
      'cont with USL: bodies rebounding from a contact vibrate in free flight, and USL ' // &
      '(light nodes in the strain rate) tends to diverge there; MUSL or USF are safer')
    if (m%rpttime <= 0.0_dp) m%rpttime = m%outtime
    ! Grid size: whole cells per axis, the node count and the memory of the run.
    nodes = 1.0_dp
    do a = 1, 3
      at = max(box_line(a), dcell_line)
      n = (m%box_hi(a) - m%box_lo(a)) / m%dcell + 0.5_dp
      fl = aint(n)
      if (fl > n) fl = fl - 1.0_dp
      if (.not. (fl >= 1.0_dp)) &
        call ts%fail(at, 'grid box along ' // achar(iachar('x') + a - 1) // ' is shorter than half a cell')
      if (.not. (fl <= 1.0e6_dp)) &
        call ts%fail(at, 'grid box along ' // achar(iachar('x') + a - 1) // ' has more than 1000000 cells')
      nodes = nodes * (fl + 1.0_dp)
    end do
    at = max(maxval(box_line), dcell_line)
    if (nodes > MAX_NODES) &
      call ts%fail(at, 'grid of ' // itoa(int(nodes, int64)) // ' nodes exceeds the limit of ' // &
                   itoa(int(MAX_NODES, int64)))
    need = nodes * BYTES_PER_NODE + real(m%nbmp, dp) * BYTES_PER_PARTICLE
    if (need > memory_budget()) &
      call ts%fail(at, 'grid of ' // itoa(int(nodes, int64)) // ' nodes and ' // i2s(m%nbmp) // &
                   ' particles need about ' // megabytes(need) // ', more than the ' // &
                   megabytes(memory_budget()) // ' of memory available')
    do a = 1, 3
      n = (m%box_hi(a) - m%box_lo(a)) / m%dcell
      fl = aint(n + 0.5_dp)
      if (fl > n + 0.5_dp) fl = fl - 1.0_dp
      if (abs(n - fl) > 1.0e-6_dp * n) then
        write (buf, '(i0)') int(fl, int64)
        call warn(m, 'box length along ' // achar(iachar('x') + a - 1) // &
                  ' is not a whole number of cells; rounded to ' // trim(buf))
      end if
    end do
    ! Explosives: every hiex and null material needs an EOS, hiex a detonation point.
    hiex = .false.
    do i = 1, m%nmat
      if ((m%mats(i)%type == MAT_HIEX .or. m%mats(i)%type == MAT_NULL) .and. &
          m%mats(i)%eos_type == EOS_NONE) &
        call ts%fail(line, 'material ' // i2s(i) // ' (' // trim(material_keyword(m%mats(i)%type)) // &
                     ") needs an equation of state ('seos')")
      if (m%mats(i)%type == MAT_HIEX) then
        if (m%ndeto == 0) &
          call ts%fail(line, 'material ' // i2s(i) // " (hiex) needs a detonation point ('deto')")
        m%mats(i)%burn_width = 1.5_dp * m%dcell
        hiex = .true.
      end if
    end do
    if (m%ndeto > 0 .and. .not. hiex) call warn(m, "'deto' points given but no hiex material: ignored")
    if (hiex) then
      ! Lighting time: distance from the initial position to the nearest detonation point / D.
      allocate(m%particles%tlight(m%particles%np))
      m%particles%tlight = 0.0_dp
      do p = 1, m%particles%np
        associate (mp => m%mats(m%particles%mat(p) + 1))
          if (mp%type /= MAT_HIEX) cycle
          dmin = 0.0_dp
          do k = 1, m%ndeto
            dx = m%particles%x(1, p) - m%deto(1, k)
            dy = m%particles%x(2, p) - m%deto(2, k)
            dz = m%particles%x(3, p) - m%deto(3, k)
            d = sqrt(((dx * dx) + (dy * dy)) + (dz * dz))
            if (k == 1 .or. d < dmin) dmin = d
          end do
          m%particles%tlight(p) = dmin / mp%det_vel
        end associate
      end do
    end if
    ! Rule null_eos=wave_speed: the current program's set-up overwrites the first EOS coefficient
    ! of every null material with the null's wave speed (Mie-Gruneisen: its linear term's rho0 c0^2).
    if (m%rules%null_eos == 1) then
      do i = 1, m%nmat
        if (m%mats(i)%type == MAT_NULL .and. m%mats(i)%eos_type /= EOS_NONE) then
          if (m%mats(i)%eos_type == EOS_MIE_GRUNEISEN) then
            m%mats(i)%eos_k1 = m%mats(i)%wave_speed
          else
            m%mats(i)%eos(1) = m%mats(i)%wave_speed
          end if
        end if
      end do
    end if
    ! neoh: each particle carries F - I (zero at the start); the volume follows det F.
    if (any(m%mats(1:m%nmat)%type == MAT_NEOH)) then
      m%uvf = .true.
      allocate(m%particles%defgrad(9, m%particles%np))
      m%particles%defgrad = 0.0_dp
    end if
    if (m%tl) then
      ! The combinations the current version's TLmp does not have are refused.
      do i = 1, m%nmat
        if (m%mats(i)%type /= MAT_NEOH) call ts%fail(m%tl_line, "'TLmp' with a " // &
          trim(material_keyword(m%mats(i)%type)) // ' material: total Lagrangian MPM takes neoh materials only')
      end do
      if (m%gimp) call ts%fail(m%tl_line, &
        "'TLmp' with 'gimp': total Lagrangian MPM takes the trilinear shape functions only")
      if (m%bspline) call ts%fail(m%tl_line, &
        "'TLmp' with 'bimp': total Lagrangian MPM takes the trilinear shape functions only")
      if (m%contact) call ts%fail(m%tl_line, "'TLmp' with 'cont': total Lagrangian MPM has one velocity field")
      if (m%regrid_every > 0) call ts%fail(m%tl_line, "'TLmp' with 'adgr': the reference grid of TLmp cannot move")
      allocate(m%particles%pk1(9, m%particles%np), m%particles%x0(3, m%particles%np))
      m%particles%pk1 = 0.0_dp
      m%particles%x0 = m%particles%x
    end if
    ! The current version has bulk viscosity on by default (1.5, 0.06), applied to the stress.
    ! Rule bulk_book=ignore: the book program reads 'bulk' and does not apply it.
    if (m%has_bulk .and. .not. m%current_version .and. m%rules%bulk_book == 1) then
      m%has_bulk = .false.
      m%bulk_q1 = 0.0_dp
      m%bulk_q2 = 0.0_dp
    end if
    if (m%current_version .and. .not. m%has_bulk) then
      m%has_bulk = .true.
      m%bulk_q1 = 1.5_dp
      m%bulk_q2 = 0.06_dp
    end if
    if (m%has_bulk) then
      allocate(m%particles%qv(m%particles%np))
      m%particles%qv = 0.0_dp
    end if
    ! Initial internal energy from E0 (per unit initial volume), initial temperature.
    thermal = .false.
    do i = 1, m%nmat
      thermal = thermal .or. material_is_thermal(m%mats(i)%type)
    end do
    if (thermal) then
      allocate(m%particles%temp(m%particles%np))
      m%particles%temp = 0.0_dp
    end if
    c_max = 0.0_dp
    rho_sum = 0.0_dp
    do i = 1, m%nmat
      c_max = max(c_max, m%mats(i)%wave_speed)
      rho_sum = rho_sum + m%mats(i)%rho0
    end do
    do p = 1, m%particles%np
      associate (mp => m%mats(m%particles%mat(p) + 1))
        if (mp%eos_type /= EOS_NONE) m%particles%ie(p) = mp%eos_e0 * (m%particles%mass(p) / mp%rho0)
        if (thermal) then  ! rule start_temp
          if (m%rules%start_temp == 1) then
            m%particles%temp(p) = 293.0_dp
          else
            m%particles%temp(p) = mp%t_room
          end if
        end if
      end associate
    end do
    if (m%gimp .and. m%bspline) call ts%fail(max(m%gimp_line, m%bimp_line), &
      "'gimp' with 'bimp': a deck takes one kind of shape functions")
    if (m%sg) then
      ! What the current version's sgmp does not combine with, or we have not built, is refused.
      if (m%gimp) call ts%fail(max(m%gimp_line, m%sgmp_line), &
        "'sgmp' with 'gimp': smoothed-gradient MPM takes the trilinear shape functions only")
      if (m%bspline) call ts%fail(max(m%bimp_line, m%sgmp_line), &
        "'sgmp' with 'bimp': smoothed-gradient MPM takes the trilinear shape functions only")
      if (m%contact) call ts%fail(max(m%contact_line, m%sgmp_line), &
        "'sgmp' with 'cont': smoothed-gradient MPM has one velocity field here")
      if (m%regrid_every > 0) call ts%fail(m%sgmp_line, "'sgmp' with 'adgr': the cell-centre grid of sgmp does not move")
    end if
    if (m%bspline) call two_cells_each_axis(ts, m, m%bimp_line, 'bimp')
    ! GIMP particle half-size lp. Current-version decks: a quarter cell for every particle,
    ! as the current program, whose GIMP weights are written for particles half a cell wide
    ! whatever their volume. Book decks: half the spacing of bloc/sphe/cyli particles, half
    ! the cube root of the volume of poin particles; at most h/2 (the 27-node stencil).
    if (m%gimp) then
      allocate(m%particles%psize(m%particles%np))
      m%particles%psize = 0.0_dp
      clamped = .false.
      do i = 1, m%nbodies
        do p = m%bodies(i)%first + 1, m%bodies(i)%first + m%bodies(i)%count
          if (m%current_version) then
            lp = 0.25_dp * m%dcell
          else if (m%bodies(i)%spacing > 0.0_dp) then
            lp = 0.5_dp * m%bodies(i)%spacing
          else
            lp = 0.5_dp * (m%particles%vol(p) ** (1.0_dp / 3.0_dp))
          end if
          if (lp > 0.5_dp * m%dcell) then
            lp = 0.5_dp * m%dcell
            clamped = .true.
          end if
          m%particles%psize(p) = lp
        end do
      end do
      if (clamped) call warn(m, 'gimp: particles larger than the cell size take half a cell as their half-size')
      call two_cells_each_axis(ts, m, m%gimp_line, 'gimp')
    end if
    if (m%sg) call sgmp_held_cells(ts, m)
    call outside_grid(m)
    ! dt = dtscale * h / c_max (the dilatational wave speed, D for hiex, c for null), fixed
    ! for the run; with bulk viscosity dtscale h / (c_max (q2 + sqrt(1 + q2^2))).
    if (m%has_bulk .and. .not. m%current_version) then   ! the current version's dt has no q term
      m%dt = (m%dtscale * m%dcell) / (c_max * (m%bulk_q2 + sqrt(1.0_dp + (m%bulk_q2 * m%bulk_q2))))
    else
      m%dt = (m%dtscale * m%dcell) / c_max
    end if
    if (.not. (m%dt > 0.0_dp) .or. .not. is_finite(m%dt)) &
      call ts%fail(max(dcell_line, line), 'time step dtscale * dcel / wave speed is not a positive finite number')
    m%mass_cutoff = (1.0e-5_dp * (rho_sum / real(m%nmat, dp))) * ((m%dcell * m%dcell) * m%dcell)
    ! Base name: the deck's file name up to its first '.'.
    base = m%deck_path
    slash = index(base, '/', back=.true.)
    if (slash > 0) base = base(slash + 1:)
    dot = index(base, '.')
    if (dot > 1) base = base(1:dot - 1)
    if (len(base) == 0) then
      m%base_name = 'mpm3d'
    else
      m%base_name = base
    end if
  end procedure finish

  ! The cells of the grid along axis a (the box length rounded to whole cells).
  real(dp) function cells_along(m, a) result(fl)
    type(model_t), intent(in) :: m
    integer, intent(in) :: a
    real(dp) :: n
    n = (m%box_hi(a) - m%box_lo(a)) / m%dcell + 0.5_dp
    fl = aint(n)
    if (fl > n) fl = fl - 1.0_dp
  end function cells_along

  ! A 27-node stencil (gimp, bimp, asked for at `line`) needs two cells along each axis.
  subroutine two_cells_each_axis(ts, m, line, keyword)
    type(token_stream), intent(in) :: ts
    type(model_t), intent(in) :: m
    integer, intent(in) :: line
    character(len=*), intent(in) :: keyword
    integer :: a
    character(len=1) :: axis
    do a = 1, 3
      if (cells_along(m, a) >= 2.0_dp) cycle
      axis = achar(iachar('x') + a - 1)
      call ts%fail(line, "'" // keyword // "' needs at least two cells along each axis (its 27-node stencil reaches " // &
        "the cells beside a particle's own): the grid has " // i2s(int(cells_along(m, a))) // " cell along " // &
        axis // "; make sp" // axis // " span two cells or more (a plane-strain model keeps its symmetric faces)")
    end do
  end subroutine two_cells_each_axis

  ! sgmp's particles between the two node layers of a held lower face (cxx sgmp_held_cells):
  ! refused by our rules, a warning under the original's (sg_lower=truncate).
  subroutine sgmp_held_cells(ts, m)
    type(token_stream), intent(in) :: ts
    type(model_t), intent(inout) :: m
    integer :: p, a
    integer(int64) :: count
    real(dp) :: s
    character(len=1) :: axis
    character(len=:), allocatable :: what, keep, held
    logical :: fixed
    what = ''
    do a = 1, 3
      if (m%fix(2 * a - 1) == 0 .or. cells_along(m, a) < 2.0_dp) cycle
      count = 0
      do p = 1, m%particles%np
        s = (m%particles%x(a, p) - m%box_lo(a)) / m%dcell
        if (s >= 0.0_dp .and. s < 1.0_dp) count = count + 1
      end do
      if (count == 0) cycle
      axis = achar(iachar('x') + a - 1)
      fixed = m%fix(2 * a - 1) == 1
      if (fixed) then
        held = 'fixed'
        keep = 'still'
      else
        held = 'symmetric'
        keep = 'from moving along ' // axis
      end if
      if (len(what) > 0) what = what // '; '
      what = what // itoa(count) // ' particles lie in the first cell along ' // axis // &
        ', between the two node layers sgmp holds at the ' // held // ' lower ' // &
        axis // ' face, which keep them ' // keep // ': add one cell outside that face (lower the first value of sp' // &
        axis // ' by dcel)'
    end do
    if (len(what) == 0) return
    what = what // ", as the current MPM3D-F90's ChangeLog asks for sgmp"
    if (m%rules%sg_lower == 0) call ts%fail(m%sgmp_line, what // &
      '; --rule sg_lower=truncate (in --rules original) runs the deck as that program does')
    call warn(m, what)
  end subroutine sgmp_held_cells

  ! Particles outside the grid at the start are named (a warning before the first step).
  subroutine outside_grid(m)
    type(model_t), intent(inout) :: m
    integer :: p, a, first
    integer(int64) :: count
    real(dp) :: v
    logical :: in
    count = 0
    first = 0
    do p = 1, m%particles%np
      in = .true.
      do a = 1, 3
        v = (m%particles%x(a, p) - m%box_lo(a)) / m%dcell
        in = in .and. v >= 0.0_dp .and. v < cells_along(m, a)
      end do
      if (in) cycle
      count = count + 1
      if (count == 1) first = p
    end do
    if (count > 0) call warn(m, itoa(count) // ' particles lie outside the grid at the start (the first: particle ' // &
      i2s(first) // '): they stay frozen where they are for the whole run; widen the box (spx, spy, spz) to ' // &
      'hold them')
  end subroutine outside_grid

end submodule mpm3d_data_in_finish
