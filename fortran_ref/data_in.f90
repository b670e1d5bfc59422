! DataIn: reads a legacy MPM3D deck into a model_t, as cxx/input/data_in.cpp: the types, the card loop
! and its helpers; submodules data_in_cards.f90 (mate/seos/part/velo/load), data_in_finish.f90 (endi).
module mpm3d_data_in
  use, intrinsic :: iso_fortran_env, only: int64, error_unit
  use, intrinsic :: iso_c_binding, only: c_long
  use mpm3d_material
  use mpm3d_material_models
  use mpm3d_particle
  use mpm3d_ffi
  use mpm3d_particle_gen
  use mpm3d_rules, only: step_rules, rule_request, resolve_rules
  use mpm3d_update_step, only: SCHEME_MUSL, SCHEME_USL, SCHEME_USF
  implicit none
  private

  type, public :: curve_t
    character(len=4) :: var = ''
    integer :: particle = 0      ! 0-based
  end type curve_t

  type, public :: model_t
    character(len=:), allocatable :: deck_path, base_name, title
    integer :: nbmp = -1, nbco = 1, nbbo = -1, nmat = -1
    real(dp) :: endtime = 0.0_dp, outtime = 0.0_dp, rpttime = 0.0_dp, dtscale = 0.9_dp
    real(dp) :: box_lo(3) = 0.0_dp, box_hi(3) = 0.0_dp
    logical :: box_set(3) = .false.
    real(dp) :: dcell = 0.0_dp
    integer :: fix(6) = 0
    integer :: scheme = SCHEME_MUSL
    logical :: jaumann = .true., tecplot = .false., paraview = .false., has_pt2d = .false.
    real(dp) :: pt2d(6) = 0.0_dp
    type(material_params), allocatable :: mats(:)
    type(particles_t) :: particles
    integer :: nbodies = 0
    type(body_t), allocatable :: bodies(:)
    logical :: has_gravity = .false., has_loads = .false.
    integer :: nanim = 0
    character(len=4) :: anim_vars(64) = ''
    integer :: ncurves = 0
    type(curve_t), allocatable :: curves(:)
    real(dp) :: dt = 0.0_dp           ! initial time step
    real(dp) :: mass_cutoff = 0.0_dp
    integer :: regrid_every = 0       ! adaptive grid: redefine the grid every N steps (adgr)
    logical :: gimp = .false.          ! uGIMP shape functions (particles%psize set)
    logical :: bspline = .false.       ! bimp: the current version's quadratic B-splines
    logical :: sg = .false.            ! sgmp: smoothed-gradient MPM through the cell centres
    integer :: gimp_line = 0, bimp_line = 0, sgmp_line = 0  ! deck lines of gimp, bimp, sgmp
    logical :: contact = .false.       ! cont: multi-velocity contact of components 1, 2
    real(dp) :: contact_mu = 0.0_dp    ! Coulomb friction coefficient
    integer :: contact_normbody = 0    ! normals from component 1, 2, or 0 (both)
    integer :: contact_line = 0        ! deck line of the cont card
    integer :: nwarn = 0
    character(len=200) :: warnings(16) = ''
    integer :: ndeto = 0                ! detonation points (deto), at most 10
    real(dp) :: deto(3, 10) = 0.0_dp
    logical :: has_bulk = .false.       ! 'bulk q1 q2': artificial bulk viscosity
    real(dp) :: bulk_q1 = 0.0_dp, bulk_q2 = 0.0_dp
    logical :: uvf = .false.            ! volume from det(I + L dt): UVFp, or a neoh material
    logical :: current_version = .false.  ! a keyword only the current MPM3D-F90 knows: its
                                          ! behaviours (bloc x fastest, dt_per_step)
    logical :: dt_per_step = .false.    ! the current version's dt, recomputed every step
    ! The rules in force (rules.f90), resolved when the deck is read: current_version is
    ! rules%program, dt_per_step rules%time_step. deck_current: what the deck's keywords name.
    type(step_rules) :: rules
    logical :: deck_current = .false.
    real(dp) :: load_ramp_time = 0.0_dp ! QuLo: loads ramp over this time (0: off)
    real(dp) :: damping = 0.0_dp        ! Damp: -damping m v joins the body force
    logical :: dynamic_relaxation = .false.  ! drda: stop every particle when KE did not grow
    logical :: tl = .false.             ! TLmp: total Lagrangian MPM (neoh only)
    integer :: tl_line = 0              ! deck line of the TLmp card
  end type model_t

  public :: read_deck, is_output_variable, model_shape, model_fix_layers
  ! For the submodules only: gfortran gives a private module procedure local linkage, which
  ! a submodule's object file cannot call.
  public :: memory_budget, megabytes, i2s, warn, n_defined, need_counts, body_index, particle_index, &
            read_vec3

  ! Memory limit of a deck (as cxx/input/data_in.hpp): estimated bytes per particle and per grid
  ! node of a run, the hard limit of grid nodes; the budget is the machine's memory.
  real(dp), parameter :: BYTES_PER_PARTICLE = 256.0_dp, BYTES_PER_NODE = 160.0_dp
  real(dp), parameter :: MAX_NODES = 2.0e8_dp

  interface
    function c_sysconf(name) bind(C, name='sysconf') result(r)
      import :: c_long
      integer(c_long), value :: name
      integer(c_long) :: r
    end function c_sysconf
  end interface

  character(len=4), parameter :: OUTPUT_VARS(19) = [character(len=4) :: 'seqv', 'epef', 'mat', &
      'pres', 'volu', 'engk', 'engi', 'velx', 'vely', 'velz', 'cels', 'fail', 'sspd', 'damg', &
      'stsx', 'disx', 'disy', 'disz', 'spre']

  ! The cards with bodies of their own, 'mate', 'seos', 'part', 'velo', 'load' (read_card,
  ! data_in_cards.f90), and the end of the deck, 'endi' (finish, data_in_finish.f90).
  interface
    module subroutine read_card(ts, m, key, k)
      type(token_stream), intent(inout) :: ts
      type(model_t), intent(inout) :: m
      type(token_t), intent(in) :: key
      character(len=*), intent(in) :: k
    end subroutine read_card
    module subroutine finish(ts, m, line, box_line, dcell_line)
      type(token_stream), intent(in) :: ts
      type(model_t), intent(inout) :: m
      integer, intent(in) :: line, box_line(3), dcell_line
    end subroutine finish
  end interface

contains

  ! Shape functions of the stages (step_context%shape): 0 trilinear, 1 uGIMP, 2 B-spline.
  pure integer function model_shape(m)
    type(model_t), intent(in) :: m
    model_shape = 0
    if (m%gimp) then
      model_shape = 1
    else if (m%bspline) then
      model_shape = 2
    end if
  end function model_shape

  ! Node layers held on a fixed or symmetric face (cxx Model::fix_layers): two for the
  ! current version with 27-node stencils or sgmp, else one.
  pure integer function model_fix_layers(m)
    type(model_t), intent(in) :: m
    model_fix_layers = 1
    if (m%current_version .and. (model_shape(m) /= 0 .or. m%sg)) model_fix_layers = 2
  end function model_fix_layers

  ! The machine's physical memory in bytes (glibc: _SC_PHYS_PAGES = 85, _SC_PAGESIZE = 30).
  real(dp) function memory_budget()
    integer(c_long) :: pages, page
    pages = c_sysconf(85_c_long)
    page = c_sysconf(30_c_long)
    if (pages > 0 .and. page > 0) then
      memory_budget = real(pages, dp) * real(page, dp)
    else
      memory_budget = 1.0e18_dp
    end if
  end function memory_budget

  function megabytes(bytes) result(s)
    real(dp), intent(in) :: bytes
    character(len=:), allocatable :: s
    s = itoa(int(bytes / 1048576.0_dp + 0.5_dp, int64)) // ' MB'
  end function megabytes

  logical function is_output_variable(name)
    character(len=*), intent(in) :: name
    integer :: i
    is_output_variable = .false.
    if (len(name) > 4) return
    do i = 1, size(OUTPUT_VARS)
      if (name == trim(OUTPUT_VARS(i))) is_output_variable = .true.
    end do
  end function is_output_variable

  function i2s(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    s = itoa(int(i, int64))
  end function i2s

  subroutine warn(m, what)
    type(model_t), intent(inout) :: m
    character(len=*), intent(in) :: what
    if (m%nwarn < size(m%warnings)) then
      m%nwarn = m%nwarn + 1
      m%warnings(m%nwarn) = what
    end if
  end subroutine warn

  ! Whether a token after the title line is a keyword only the current MPM3D-F90 knows (as
  ! kCurrentKeywords, cxx/input/data_in.cpp).
  logical function has_current_keyword(ts) result(found)
    type(token_stream), intent(in) :: ts
    character(len=4), parameter :: KEYS(15) = [character(len=4) :: 'neoh', 'uvfp', 'vsin', 'qulo', &
        'damp', 'smoo', 'bimp', 'sgmp', 'tlmp', 'drda', 'blod', 'cicl', 'ksin', 'nuli', 'clay']
    integer :: i, first
    character(len=:), allocatable :: k
    found = .false.
    first = 1
    if (ts%ntok > 0) then
      if (key4(ts%text_of(ts%tok(1))) == 'mpm3') then   ! the title line is free text
        do while (first <= ts%ntok)
          if (ts%tok(first)%line /= ts%tok(1)%line) exit
          first = first + 1
        end do
      end if
    end if
    do i = first, ts%ntok
      k = key4(ts%text_of(ts%tok(i)))
      if (any(KEYS == k)) then
        found = .true.
        return
      end if
    end do
  end function has_current_keyword

  ! Reads the deck at path; input errors end the program (mpm3d_ffi: fatal).
  subroutine read_deck(path, m, rules)
    character(len=*), intent(in) :: path
    type(model_t), intent(out) :: m
    type(rule_request), intent(in), optional :: rules   ! --rules and --rule (default: ours)
    type(token_stream) :: ts
    type(token_t) :: key, t
    character(len=:), allocatable :: k, kt
    integer(int64) :: n, v, pid
    integer :: a, f, p, found
    real(dp) :: xyz(3), tol
    logical :: ended, on
    type(curve_t) :: cv
    integer :: box_line(3), dcell_line   ! where the box and the cell size were set

    call ts_open(ts, path)
    m%deck_current = has_current_keyword(ts)
    if (present(rules)) then
      m%rules = resolve_rules(rules, m%deck_current)
    else
      m%rules = resolve_rules(rule_request(), m%deck_current)
    end if
    m%current_version = m%rules%program == 1
    m%dt_per_step = m%rules%time_step == 1
    ts%single_reals = m%rules%deck_reals == 1
    m%deck_path = path
    m%title = ''
    allocate(m%bodies(4), m%curves(4))
    ended = .false.
    box_line = 0
    dcell_line = 0
    do while (.not. ts%at_end())
      key = ts%next()
      kt = ts%text_of(key)
      k = key4(kt)
      select case (k)
      case ('mpm3')
        m%title = ts%rest_of_line(key)
      case ('nbmp', 'nbco', 'nbbo', 'nmat')
        n = ts%integer(kt)
        if (n < 1 .or. n > 200000000_int64) &
          call ts%fail(key%line, "'" // kt // "' must be a count in 1..200000000, got " // itoa(n))
        if (k == 'nbmp') then
          if (m%nbmp >= 0) call ts%fail(key%line, "'nbmp' given twice")
          tol = real(n, dp) * BYTES_PER_PARTICLE
          if (tol > memory_budget()) &
            call ts%fail(key%line, "'nbmp' = " // itoa(n) // ' particles need about ' // megabytes(tol) // &
                         ', more than the ' // megabytes(memory_budget()) // ' of memory available')
          m%nbmp = int(n)
          call particles_resize(m%particles, 0)   ! grows as the particle cards generate particles
        else if (k == 'nbco') then
          if (n > 2) call ts%fail(key%line, "'nbco' must be 1 or 2")
          m%nbco = int(n)
        else if (k == 'nbbo') then
          m%nbbo = int(n)
        else
          if (n > 1000) call ts%fail(key%line, "'nmat' too large")
          m%nmat = int(n)
          if (allocated(m%mats)) deallocate(m%mats)
          allocate(m%mats(n))
        end if
      case ('endt')
        m%endtime = ts%real('the end time')
        if (.not. (m%endtime > 0.0_dp)) call ts%fail(key%line, 'end time must be positive')
        m%outtime = m%endtime
      case ('grid')
        do a = 1, 3
          m%box_lo(a) = ts%real('the grid box')
          m%box_hi(a) = ts%real('the grid box')
          m%box_set(a) = .true.
          box_line(a) = key%line
          if (.not. (m%box_hi(a) > m%box_lo(a))) &
            call ts%fail(key%line, "'grid': maximum must exceed minimum along " // achar(iachar('x') + a - 1))
        end do
      case ('spx', 'spy', 'spz')
        a = iachar(k(3:3)) - iachar('x') + 1
        m%box_lo(a) = ts%real('the box minimum')
        m%box_hi(a) = ts%real('the box maximum')
        m%box_set(a) = .true.
        box_line(a) = key%line
        if (.not. (m%box_hi(a) > m%box_lo(a))) &
          call ts%fail(key%line, "'" // kt // "': maximum must exceed minimum")
      case ('dcel')
        m%dcell = ts%real('the cell size')
        if (.not. (m%dcell > 0.0_dp)) call ts%fail(key%line, 'cell size must be positive')
        dcell_line = key%line
      case ('dtsc')
        m%dtscale = ts%real('the time-step scale')
        if (.not. (m%dtscale > 0.0_dp) .or. m%dtscale > 2.5_dp) &
          call ts%fail(key%line, 'time-step scale must lie in (0, 2.5]')
      case ('outt')
        m%outtime = ts%real('the output interval')
        if (.not. (m%outtime > 0.0_dp)) call ts%fail(key%line, 'output interval must be positive')
      case ('rptt')
        m%rpttime = ts%real('the report interval')
        if (.not. (m%rpttime > 0.0_dp)) call ts%fail(key%line, 'report interval must be positive')
      case ('adgr')      ! extension: adaptive background grid every N steps
        n = ts%integer('the regrid interval')
        if (n < 0 .or. n > 1000000000_int64) &
          call ts%fail(key%line, "'adgr' needs a step interval, 0 (off) or more")
        m%regrid_every = int(n)
      case ('fixe')
        do f = 1, 6
          v = ts%integer('a face condition')
          if (v < 0 .or. v > 2) &
            call ts%fail(key%line, 'face conditions are 0 (free), 1 (fixed) or 2 (symmetry)')
          m%fix(f) = int(v)
        end do
      case ('mate', 'seos', 'pmin', 'part', 'velo', 'load')
        call read_card(ts, m, key, k)
      case ('musl', 'usf', 'usl')
        if (on_off(ts, key)) then
          if (k == 'musl') then
            m%scheme = SCHEME_MUSL
          else if (k == 'usf') then
            m%scheme = SCHEME_USF
          else
            m%scheme = SCHEME_USL
          end if
        end if
      case ('jaum')
        m%jaumann = on_off(ts, key)
        if (.not. m%jaumann) &
          call warn(m, 'jaum off: stresses are rotated with the Jaumann rate all the same')
      case ('outr')
        if (m%nanim < size(m%anim_vars)) m%nanim = m%nanim + 1
        m%anim_vars(m%nanim) = output_var(ts, key%line)
      case ('curv')
        cv%var = output_var(ts, key%line)
        pid = 1
        if (.not. ts%at_end()) then
          t = ts%peek()
          if (t%line == key%line) then
            if (parse_integer(ts%text_of(t), pid)) then
              t = ts%next()
            else
              pid = 1
            end if
          end if
        end if
        call need_counts(ts, m, key, .true., .false., .false.)
        cv%particle = particle_index(ts, m, key, pid)
        call add_curve(m, cv)
      case ('curx')
        cv%var = output_var(ts, key%line)
        xyz = read_vec3(ts, 'a curve position')
        if (n_defined(m) == 0) call ts%fail(key%line, "'curx' must follow the particle cards")
        tol = 0.25_dp * m%dcell
        found = -1
        do p = 1, n_defined(m)
          if (abs(m%particles%x(1, p) - xyz(1)) <= tol .and. abs(m%particles%x(2, p) - xyz(2)) <= tol &
              .and. abs(m%particles%x(3, p) - xyz(3)) <= tol) then
            found = p - 1
            exit
          end if
        end do
        if (found < 0) call ts%fail(key%line, "'curx': no particle within 0.25 h of the point")
        cv%particle = found
        call add_curve(m, cv)
      case ('pt2d')
        do a = 1, 6
          m%pt2d(a) = ts%real('the pt2d box')
        end do
        m%has_pt2d = .true.
      case ('tecp', 'para')
        on = .true.
        if (.not. ts%at_end()) then
          t = ts%peek()
          if (key4(ts%text_of(t)) == 'on' .or. key4(ts%text_of(t)) == 'off') on = on_off(ts, key)
        end if
        if (k == 'tecp') then
          m%tecplot = on
        else
          m%paraview = on
        end if
      case ('deto')
        xyz = read_vec3(ts, 'the detonation point')
        if (m%ndeto >= 10) call ts%fail(key%line, "at most 10 detonation points ('deto')")
        m%ndeto = m%ndeto + 1
        m%deto(:, m%ndeto) = xyz
      case ('bulk')
        m%bulk_q1 = ts%real('q1')
        m%bulk_q2 = ts%real('q2')
        if (.not. (m%bulk_q1 >= 0.0_dp) .or. .not. (m%bulk_q2 >= 0.0_dp)) &
          call ts%fail(key%line, 'bulk viscosity coefficients must not be negative')
        m%has_bulk = .true.
      case ('gimp')
        m%gimp = .true.
        m%gimp_line = key%line
      case ('bimp')
        m%bspline = .true.
        m%bimp_line = key%line
      case ('smoo')  ! the current version's smoothed pressure: an output of mpm3d only
      case ('qulo')
        m%load_ramp_time = ts%real('the load ramp time')
        if (.not. (m%load_ramp_time > 0.0_dp)) call ts%fail(key%line, "'QuLo': the load ramp time must be positive")
      case ('damp')
        m%damping = ts%real('the damping coefficient')
        if (.not. (m%damping >= 0.0_dp)) &
          call ts%fail(key%line, "'Damp': the damping coefficient must not be negative")
      case ('tlmp')  ! total Lagrangian MPM (the current version)
        m%tl = .true.
        m%tl_line = key%line
      case ('drda')  ! dynamic-relaxation damping (the current version)
        m%dynamic_relaxation = .true.
      case ('uvfp')  ! the current version's volume update from F
        m%uvf = .true.
      case ('cont')
        if (ts%at_end()) call ts%fail(key%line, "'cont' needs 'lagr mu normbody'")
        t = ts%next()
        if (key4(ts%text_of(t)) /= 'lagr') &
          call ts%fail(t%line, "'cont': only 'lagr' (multi-velocity grid contact) is supported, found '" // &
                       ts%text_of(t) // "'")
        m%contact_mu = ts%real('the friction coefficient')
        if (.not. (m%contact_mu >= 0.0_dp)) &
          call ts%fail(key%line, "'cont': friction coefficient must not be negative")
        t = ts%peek()
        n = ts%integer('the normal body (0, 1 or 2)')
        if (n < 0 .or. n > 2) call ts%fail(t%line, "'cont': normal body must be 0 (average), 1 or 2")
        m%contact_normbody = int(n)
        m%contact = .true.
        m%contact_line = key%line
      case ('endi')
        ended = .true.
        call finish(ts, m, key%line, box_line, dcell_line)
        exit
      case ('sgmp')
        m%sg = .true.
        m%sgmp_line = key%line
      case default
        ! As cxx/input/data_in.cpp: a number where a keyword belongs ends a card that is too long.
        if (parse_real(ts%text_of(key), xyz(1))) call ts%fail(key%line, "'" // ts%text_of(key) // &
          "' is a number where a card's keyword was expected: the card before it has more numbers than it " // &
          "takes (docs/DECK_FORMAT.md lists each card's; a null material takes density, bulk modulus and " // &
          "viscosity in a current deck, density and wave speed in a book deck)")
        call ts%fail(key%line, "unknown keyword '" // kt // "'")
      end select
    end do
    if (.not. ended) call ts%fail(ts%line(), "end of file reached before 'endi'")
  end subroutine read_deck

  ! Three reals in a row (a vector), what naming them in the messages.
  function read_vec3(ts, what) result(v)
    type(token_stream), intent(inout) :: ts
    character(len=*), intent(in) :: what
    real(dp) :: v(3)
    integer :: a
    do a = 1, 3
      v(a) = ts%real(what)
    end do
  end function read_vec3

  ! Particles defined so far.
  integer function n_defined(m)
    type(model_t), intent(in) :: m
    if (m%nbodies == 0) then
      n_defined = 0
    else
      n_defined = m%bodies(m%nbodies)%first + m%bodies(m%nbodies)%count
    end if
  end function n_defined

  subroutine add_curve(m, cv)
    type(model_t), intent(inout) :: m
    type(curve_t), intent(in) :: cv
    type(curve_t), allocatable :: tmp(:)
    if (m%ncurves == size(m%curves)) then
      allocate(tmp(2 * size(m%curves)))
      tmp(1:m%ncurves) = m%curves(1:m%ncurves)
      call move_alloc(tmp, m%curves)
    end if
    m%ncurves = m%ncurves + 1
    m%curves(m%ncurves) = cv
  end subroutine add_curve

  logical function on_off(ts, key)
    type(token_stream), intent(inout) :: ts
    type(token_t), intent(in) :: key
    type(token_t) :: t
    character(len=:), allocatable :: k
    if (ts%at_end()) call ts%fail(key%line, "'" // ts%text_of(key) // "' needs 'on' or 'off'")
    t = ts%next()
    k = key4(ts%text_of(t))
    if (k == 'on') then
      on_off = .true.
    else if (k == 'off') then
      on_off = .false.
    else
      on_off = .false.
      call ts%fail(t%line, "'" // ts%text_of(key) // "' needs 'on' or 'off', found '" // &
                   ts%text_of(t) // "'")
    end if
  end function on_off

  subroutine need_counts(ts, m, key, particles, materials, bodies)
    type(token_stream), intent(in) :: ts
    type(model_t), intent(in) :: m
    type(token_t), intent(in) :: key
    logical, intent(in) :: particles, materials, bodies
    if (particles .and. m%nbmp < 0) &
      call ts%fail(key%line, "'" // ts%text_of(key) // "' before 'nbmp' (number of particles)")
    if (materials .and. m%nmat < 0) &
      call ts%fail(key%line, "'" // ts%text_of(key) // "' before 'nmat' (number of materials)")
    if (bodies .and. m%nbbo < 0) &
      call ts%fail(key%line, "'" // ts%text_of(key) // "' before 'nbbo' (number of bodies)")
  end subroutine need_counts

  function output_var(ts, line) result(v)
    type(token_stream), intent(inout) :: ts
    integer, intent(in) :: line
    character(len=4) :: v
    type(token_t) :: t
    character(len=:), allocatable :: s
    if (ts%at_end()) call ts%fail(line, 'missing output variable name')
    t = ts%next()
    s = lower(ts%text_of(t))
    if (len(s) > 4) s = s(1:4)
    if (.not. is_output_variable(s)) &
      call ts%fail(t%line, "unknown output variable '" // ts%text_of(t) // "'")
    v = s
  end function output_var

  integer function body_index(ts, m, at, ib)
    type(token_stream), intent(in) :: ts
    type(model_t), intent(in) :: m
    type(token_t), intent(in) :: at
    integer(int64), intent(in) :: ib
    if (ib < 1 .or. ib > m%nbodies) &
      call ts%fail(at%line, 'body ' // itoa(ib) // ' does not exist (' // i2s(m%nbodies) // &
                   ' bodies defined so far)')
    body_index = int(ib - 1)
  end function body_index

  integer function particle_index(ts, m, at, pid)
    type(token_stream), intent(in) :: ts
    type(model_t), intent(in) :: m
    type(token_t), intent(in) :: at
    integer(int64), intent(in) :: pid
    if (pid < 1 .or. pid > m%nbmp) &
      call ts%fail(at%line, 'particle ' // itoa(pid) // ' out of range 1..' // i2s(m%nbmp))
    particle_index = int(pid - 1)
  end function particle_index

end module mpm3d_data_in
