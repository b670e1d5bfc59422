! DataIn: reads a legacy MPM3D deck into a model (particles generated, dt computed), with
! the rules, the particle order and the arithmetic of cxx/data_in.cpp.
module mpm3d_data_in
  use, intrinsic :: iso_fortran_env, only: int64, error_unit
  use, intrinsic :: iso_c_binding, only: c_long
  use mpm3d_material
  use mpm3d_particle
  use mpm3d_ffi
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
  end type model_t

  public :: read_deck, is_output_variable

  ! Memory limit of a deck (as cxx/data_in.hpp): estimated bytes per particle and per grid
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

  character(len=4), parameter :: OUTPUT_VARS(14) = [character(len=4) :: 'seqv', 'epef', 'mat', &
      'pres', 'volu', 'engk', 'engi', 'velx', 'vely', 'velz', 'cels', 'fail', 'sspd', 'damg']

contains

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

  ! (ieee_arithmetic is out of reach with -nostdinc: see CMakeLists.txt.) False for Inf and NaN.
  logical function is_finite(x)
    real(dp), intent(in) :: x
    is_finite = abs(x) <= huge(x)
  end function is_finite

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

  ! Reads the deck at path; input errors end the program (mpm3d_ffi: fatal).
  subroutine read_deck(path, m)
    character(len=*), intent(in) :: path
    type(model_t), intent(out) :: m
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
      case ('mate')
        call read_materials(ts, m, key)
      case ('part')
        call read_particles(ts, m, key)
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
      case ('load')
        call read_loads(ts, m, key)
      case ('velo')
        call read_velocities(ts, m, key)
      case ('seos')
        call read_eos(ts, m, key)
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
        do a = 1, 3
          xyz(a) = ts%real('a curve position')
        end do
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
        do a = 1, 3
          xyz(a) = ts%real('the detonation point')
        end do
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
      case default
        call ts%fail(key%line, "unknown keyword '" // kt // "'")
      end select
    end do
    if (.not. ended) call ts%fail(ts%line(), "end of file reached before 'endi'")
  end subroutine read_deck

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

  subroutine read_materials(ts, m, key)
    type(token_stream), intent(inout) :: ts
    type(model_t), intent(inout) :: m
    type(token_t), intent(in) :: key
    type(token_t) :: idt, typ
    integer(int64) :: num
    character(len=:), allocatable :: t, err
    integer :: line
    real(dp) :: et
    type(material_params) :: mp
    call need_counts(ts, m, key, .false., .true., .false.)
    do
      idt = ts%peek()
      num = ts%integer('a material number')
      if (num < 1 .or. num > m%nmat) &
        call ts%fail(idt%line, 'material number ' // itoa(num) // ' out of range 1..' // i2s(m%nmat))
      typ = ts%next()
      t = key4(ts%text_of(typ))
      line = typ%line
      mp = material_params()
      select case (t)
      case ('elas', 'pla1', 'pla2')
        if (t == 'elas') then
          mp%type = MAT_ELAS
        else if (t == 'pla1') then
          mp%type = MAT_PLA1
        else
          mp%type = MAT_PLA2
        end if
        mp%rho0 = ts%real('density')
        mp%young = ts%real("Young's modulus")
        mp%poisson = ts%real("Poisson's ratio")
        if (mp%type /= MAT_ELAS) mp%yield0 = ts%real('yield stress')
        if (mp%type == MAT_PLA2) then
          et = ts%real('tangent modulus')
          if (.not. (et >= 0.0_dp .and. et < mp%young)) &
            call ts%fail(line, 'tangent modulus must lie in [0, E)')
          mp%hardening = (mp%young * et) / (mp%young - et)
        end if
      case ('john', 'jcf')
        if (t == 'john') then
          mp%type = MAT_JOHN
        else
          mp%type = MAT_JCF
        end if
        mp%rho0 = ts%real('density')
        mp%young = ts%real("Young's modulus")
        mp%poisson = ts%real("Poisson's ratio")
        mp%yield0 = ts%real('A')
        mp%hardening = ts%real('B')
        mp%jc_n = ts%real('n')
        mp%jc_c = ts%real('C')
        mp%jc_m = ts%real('m')
        mp%t_room = ts%real('room temperature')
        mp%t_melt = ts%real('melting temperature')
        mp%heat_cap = ts%real('specific heat')
        mp%eps0dot = ts%real('reference strain rate')
        if (mp%type == MAT_JCF) mp%fail_strain = ts%real('failure strain')
        if (.not. (mp%t_melt > mp%t_room)) &
          call ts%fail(line, 'melting temperature must exceed room temperature')
        if (.not. (mp%heat_cap > 0.0_dp)) call ts%fail(line, 'specific heat must be positive')
      case ('sjc', 'sjcf')
        if (t == 'sjc') then
          mp%type = MAT_SJC
        else
          mp%type = MAT_SJCF
        end if
        mp%rho0 = ts%real('density')
        mp%young = ts%real("Young's modulus")
        mp%poisson = ts%real("Poisson's ratio")
        mp%yield0 = ts%real('A')
        mp%hardening = ts%real('B')
        mp%jc_n = ts%real('n')
        mp%jc_c = ts%real('C')
        mp%eps0dot = ts%real('reference strain rate')
        if (mp%type == MAT_SJCF) mp%fail_strain = ts%real('failure strain')
      case ('hiex', 'null')
        if (t == 'hiex') then
          mp%type = MAT_HIEX
        else
          mp%type = MAT_NULL
        end if
        mp%rho0 = ts%real('density')
        if (mp%type == MAT_HIEX) then
          mp%wave_speed = ts%real('the detonation velocity')
          mp%det_vel = mp%wave_speed
        else
          mp%wave_speed = ts%real('the wave speed')
        end if
      case ('dpm')
        mp%type = MAT_DPM
        mp%rho0 = ts%real('density')
        mp%young = ts%real("Young's modulus")
        mp%poisson = ts%real("Poisson's ratio")
        mp%dp_qphi = ts%real('q_phi')
        mp%dp_kphi = ts%real('k_phi')
        mp%dp_qpsi = ts%real('q_psi')
        mp%dp_tension = ts%real('the tension cut-off')
      case default
        call ts%fail(line, "unknown material type '" // ts%text_of(typ) // "'")
      end select
      if (mp%type == MAT_SJC .or. mp%type == MAT_SJCF .or. mp%type == MAT_JOHN .or. &
          mp%type == MAT_JCF) then
        if (.not. (mp%jc_n > 0.0_dp)) call ts%fail(line, 'Johnson-Cook n must be positive')
        if (mp%jc_c /= 0.0_dp .and. .not. (mp%eps0dot > 0.0_dp)) &
          call ts%fail(line, 'reference strain rate must be positive')
      end if
      if (mp%fail_strain < 0.0_dp) call ts%fail(line, 'failure strain must not be negative')
      call material_derive(mp, err)
      if (len(err) > 0) call ts%fail(line, 'material ' // itoa(num) // ': ' // err)
      if (.not. is_finite(mp%shear) .or. .not. is_finite(mp%lambda) .or. &
          .not. (mp%wave_speed > 0.0_dp) .or. .not. is_finite(mp%wave_speed)) &
        call ts%fail(line, 'material ' // itoa(num) // &
                     ': elastic constants out of range (wave speed not a positive finite number)')
      m%mats(num) = mp
      if (num == m%nmat) exit
    end do
  end subroutine read_materials

  subroutine read_eos(ts, m, key)
    type(token_stream), intent(inout) :: ts
    type(model_t), intent(inout) :: m
    type(token_t), intent(in) :: key
    type(token_t) :: at
    integer(int64) :: mid, et
    integer :: i
    call need_counts(ts, m, key, .false., .true., .false.)
    at = ts%peek()
    mid = ts%integer('a material number')
    if (mid < 1 .or. mid > m%nmat) &
      call ts%fail(at%line, 'material number ' // itoa(mid) // ' out of range 1..' // i2s(m%nmat))
    if (m%mats(mid)%type == 0) &
      call ts%fail(at%line, "'seos' for material " // itoa(mid) // " before its 'mate' card")
    et = ts%integer('an EOS type')
    if (et == 1) then
      do i = 1, 7
        m%mats(mid)%eos(i) = ts%real('an EOS coefficient')
      end do
      m%mats(mid)%eos_e0 = ts%real('E0')
    else if (et == 2) then
      do i = 1, 3
        m%mats(mid)%eos(i) = ts%real('an EOS coefficient')
      end do
      m%mats(mid)%eos_e0 = ts%real('E0')
      if (.not. (m%mats(mid)%eos(1) > 0.0_dp)) call ts%fail(key%line, 'Mie-Gruneisen c0 must be positive')
    else if (et == 3) then
      do i = 1, 5
        m%mats(mid)%eos(i) = ts%real('a JWL coefficient')
      end do
      m%mats(mid)%eos_e0 = ts%real('E0')
      if (m%mats(mid)%type /= MAT_HIEX .and. m%mats(mid)%type /= MAT_NULL) &
        call ts%fail(key%line, 'EOS type 3 (JWL) is for hiex and null materials')
      if (.not. (m%mats(mid)%eos(3) > 0.0_dp) .or. .not. (m%mats(mid)%eos(4) > 0.0_dp)) &
        call ts%fail(key%line, 'JWL R1 and R2 must be positive')
    else
      call ts%fail(key%line, 'unknown EOS type ' // itoa(et) // &
                   ' (1 linear polynomial, 2 Mie-Gruneisen, 3 JWL)')
    end if
    if (m%mats(mid)%type == MAT_DPM) call ts%fail(key%line, 'a dpm material takes no equation of state')
    m%mats(mid)%eos_type = int(et)
  end subroutine read_eos

  subroutine add_particle(ts, m, line, mat, mass, vol, x, y, z)
    type(token_stream), intent(in) :: ts
    type(model_t), intent(inout) :: m
    integer, intent(in) :: line, mat
    real(dp), intent(in) :: mass, vol, x, y, z
    integer :: p
    p = n_defined(m) + 1
    if (p > m%nbmp) call ts%fail(line, "more particles than 'nbmp' = " // i2s(m%nbmp))
    if (.not. is_finite(x) .or. .not. is_finite(y) .or. .not. is_finite(z)) &
      call ts%fail(line, 'particle position out of range')
    if (p > m%particles%np) call particles_grow(m%particles, min(m%nbmp, max(1024, 2 * m%particles%np)))
    m%particles%mass(p) = mass
    m%particles%vol(p) = vol
    m%particles%x(1, p) = x
    m%particles%x(2, p) = y
    m%particles%x(3, p) = z
    m%particles%mat(p) = mat
    m%particles%body(p) = m%nbodies - 1
    m%bodies(m%nbodies)%count = m%bodies(m%nbodies)%count + 1
  end subroutine add_particle

  integer function read_material_id(ts, m) result(id0)
    type(token_stream), intent(inout) :: ts
    type(model_t), intent(in) :: m
    type(token_t) :: at
    integer(int64) :: id
    at = ts%peek()
    id = ts%integer('a material number')
    if (id < 1 .or. id > m%nmat) &
      call ts%fail(at%line, 'material number ' // itoa(id) // ' out of range 1..' // i2s(m%nmat))
    if (m%mats(id)%type == 0) &
      call ts%fail(at%line, 'material ' // itoa(id) // " is used before its 'mate' card")
    id0 = int(id - 1)
  end function read_material_id

  ! Refuses a particle card that would generate at least count more particles than 'nbmp'
  ! leaves room for (checked before generating, so that no card loops for long).
  subroutine check_room(ts, m, line, count, what)
    type(token_stream), intent(in) :: ts
    type(model_t), intent(in) :: m
    integer, intent(in) :: line
    real(dp), intent(in) :: count
    character(len=*), intent(in) :: what
    if (real(n_defined(m), dp) + count > real(m%nbmp, dp)) &
      call ts%fail(line, what // ' of at least ' // itoa(int(count, int64)) // " particles exceeds 'nbmp' = " // &
                   i2s(m%nbmp))
  end subroutine check_room

  subroutine read_particles(ts, m, key)
    type(token_stream), intent(inout) :: ts
    type(model_t), intent(inout) :: m
    type(token_t), intent(in) :: key
    type(token_t) :: kind, ct, nt, pt
    character(len=:), allocatable :: k
    integer(int64) :: comp, n, last, i, pid, nb(3), j, l, nr, nz
    integer :: mat, a, first
    type(body_t), allocatable :: tmp(:)
    real(dp) :: rho, dpp, vol, mass, o(3), cc(3), r2, aa, bb, ccc, x, y, z
    real(dp) :: cx, cy, z0, radius, length, t
    call need_counts(ts, m, key, .true., .true., .true.)
    if (m%nbodies >= m%nbbo) &
      call ts%fail(key%line, "more particle cards than 'nbbo' = " // i2s(m%nbbo) // ' bodies')
    kind = ts%next()
    k = key4(ts%text_of(kind))
    ct = ts%peek()
    comp = ts%integer('a component number')
    if (comp < 1 .or. comp > m%nbco) &
      call ts%fail(ct%line, 'component ' // itoa(comp) // ' out of range 1..' // i2s(m%nbco))
    first = n_defined(m)
    if (m%nbodies == size(m%bodies)) then
      allocate(tmp(2 * size(m%bodies)))
      tmp(1:m%nbodies) = m%bodies(1:m%nbodies)
      call move_alloc(tmp, m%bodies)
    end if
    m%nbodies = m%nbodies + 1
    m%bodies(m%nbodies) = body_t()
    m%bodies(m%nbodies)%first = first
    m%bodies(m%nbodies)%count = 0
    m%bodies(m%nbodies)%component = int(comp)
    select case (k)
    case ('poin')
      nt = ts%peek()
      n = ts%integer('the number of points')
      if (n < 1) call ts%fail(nt%line, 'number of points must be positive')
      if (first + n > m%nbmp) &
        call ts%fail(nt%line, "'part poin' with " // itoa(n) // " points exceeds 'nbmp' = " // i2s(m%nbmp))
      last = 0
      do i = 0, n - 1
        pt = ts%peek()
        pid = ts%integer('a particle id')
        if (pid <= last) &
          call ts%fail(pt%line, 'particle ids must ascend (' // itoa(pid) // ' after ' // itoa(last) // ')')
        last = pid
        mat = read_material_id(ts, m)
        mass = ts%real('the particle mass')
        if (.not. (mass > 0.0_dp)) call ts%fail(pt%line, 'particle mass must be positive')
        vol = mass / m%mats(mat + 1)%rho0
        if (.not. (vol > 0.0_dp) .or. .not. is_finite(vol)) &
          call ts%fail(pt%line, 'particle volume (mass / density) out of range')
        x = ts%real('x')
        y = ts%real('y')
        z = ts%real('z')
        call add_particle(ts, m, pt%line, mat, mass, vol, x, y, z)
      end do
    case ('bloc', 'sphe', 'cyli')
      mat = read_material_id(ts, m)
      rho = ts%real('the density')
      dpp = ts%real('the particle spacing')
      if (.not. (rho > 0.0_dp) .or. .not. (dpp > 0.0_dp)) &
        call ts%fail(kind%line, 'density and spacing must be positive')
      ! The card's density gives the mass; the volume is mass over the material's
      ! density, as in the book version (the two densities may differ in a deck).
      mass = rho * ((dpp * dpp) * dpp)
      vol = mass / m%mats(mat + 1)%rho0
      m%bodies(m%nbodies)%spacing = dpp
      if (.not. (vol > 0.0_dp) .or. .not. (mass > 0.0_dp) .or. .not. is_finite(mass)) &
        call ts%fail(kind%line, 'particle volume (spacing^3) or mass (density * volume) out of range')
      if (k == 'bloc') then
        do a = 1, 3
          o(a) = ts%real('the block origin')
        end do
        do a = 1, 3
          nb(a) = ts%integer('a block count')
          if (nb(a) < 1 .or. nb(a) > 100000) call ts%fail(kind%line, 'block counts must be positive')
        end do
        if (first + nb(1) * nb(2) * nb(3) > m%nbmp) &
          call ts%fail(kind%line, 'block of ' // itoa(nb(1) * nb(2) * nb(3)) // &
                       " particles exceeds 'nbmp' = " // i2s(m%nbmp))
        ! Book version: x outermost, z index fastest.
        do i = 0, nb(1) - 1
          do j = 0, nb(2) - 1
            do l = 0, nb(3) - 1
              call add_particle(ts, m, kind%line, mat, mass, vol, &
                                o(1) + ((real(i, dp) + 0.5_dp) * dpp), &
                                o(2) + ((real(j, dp) + 0.5_dp) * dpp), &
                                o(3) + ((real(l, dp) + 0.5_dp) * dpp))
            end do
          end do
        end do
      else if (k == 'sphe') then
        do a = 1, 3
          cc(a) = ts%real('the sphere centre')
        end do
        nr = ts%integer('the sphere radius in spacings')
        if (nr < 1 .or. nr > 10000) call ts%fail(kind%line, 'sphere radius (in spacings) must lie in 1..10000')
        ! At least the lattice points within nr - sqrt(3)/2 of the centre lie inside.
        t = real(nr, dp) - 0.8660254_dp
        if (t > 0.0_dp) call check_room(ts, m, kind%line, aint(4.18879_dp * t * t * t), 'sphere')
        r2 = real(nr * nr, dp)
        do i = -nr, nr - 1
          do j = -nr, nr - 1
            do l = -nr, nr - 1
              aa = real(i, dp) + 0.5_dp
              bb = real(j, dp) + 0.5_dp
              ccc = real(l, dp) + 0.5_dp
              if (((aa * aa) + (bb * bb)) + (ccc * ccc) > r2) cycle
              call add_particle(ts, m, kind%line, mat, mass, vol, cc(1) + (aa * dpp), &
                                cc(2) + (bb * dpp), cc(3) + (ccc * dpp))
            end do
          end do
        end do
      else
        ! Extension: 'part cyli comID matID density dp cx cy z0 R L', a cylinder along z.
        cx = ts%real('the cylinder axis x')
        cy = ts%real('the cylinder axis y')
        z0 = ts%real('the cylinder base z')
        radius = ts%real('the cylinder radius')
        length = ts%real('the cylinder length')
        if (.not. (radius > 0.0_dp) .or. .not. (length > 0.0_dp)) &
          call ts%fail(kind%line, 'cylinder radius and length must be positive')
        t = radius / dpp
        if (.not. (t <= 100000.0_dp)) call ts%fail(kind%line, 'cylinder too large for its spacing')
        x = aint(t)                       ! ceil, exactly
        if (x < t) x = x + 1.0_dp
        if (x > 1.0e7_dp) call ts%fail(kind%line, 'cylinder too large for its spacing')
        nr = int(x, int64)
        t = length / dpp + 0.5_dp
        x = aint(t)                       ! floor, exactly
        if (x > t) x = x - 1.0_dp
        if (x > 1.0e7_dp) call ts%fail(kind%line, 'cylinder too large for its spacing')
        if (.not. (x <= 1000000.0_dp)) call ts%fail(kind%line, 'cylinder too large for its spacing')
        if (.not. (x >= 1.0_dp)) call ts%fail(kind%line, 'cylinder shorter than half a spacing')
        nz = int(x, int64)
        if (nr > 100000 .or. nz > 1000000) call ts%fail(kind%line, 'cylinder too large for its spacing')
        ! At least the columns within R/dp - sqrt(2)/2 of the axis lie inside.
        t = radius / dpp - 0.7071068_dp
        if (t > 0.0_dp) call check_room(ts, m, kind%line, aint(3.14159_dp * t * t) * real(nz, dp), 'cylinder')
        r2 = ((radius / dpp) * (radius / dpp)) * (1.0_dp + 1.0e-12_dp)
        do i = -nr, nr - 1
          do j = -nr, nr - 1
            aa = real(i, dp) + 0.5_dp
            bb = real(j, dp) + 0.5_dp
            if ((aa * aa) + (bb * bb) > r2) cycle
            do l = 0, nz - 1
              call add_particle(ts, m, kind%line, mat, mass, vol, cx + (aa * dpp), cy + (bb * dpp), &
                                z0 + ((real(l, dp) + 0.5_dp) * dpp))
            end do
          end do
        end do
      end if
    case default
      call ts%fail(kind%line, "unknown particle card '" // ts%text_of(kind) // &
                   "' (poin, bloc, sphe or cyli)")
    end select
    if (m%bodies(m%nbodies)%count == 0) call ts%fail(kind%line, 'particle card generated no particles')
  end subroutine read_particles

  subroutine read_velocities(ts, m, key)
    type(token_stream), intent(inout) :: ts
    type(model_t), intent(inout) :: m
    type(token_t), intent(in) :: key
    type(token_t) :: t
    character(len=:), allocatable :: k
    real(dp) :: v(3)
    integer :: p, ib, a, c
    call need_counts(ts, m, key, .true., .false., .false.)
    do
      t = ts%next()
      k = key4(ts%text_of(t))
      if (k == 'endv') return
      if (k == 'node') then
        p = particle_index(ts, m, t, ts%integer('a particle id'))
        if (p >= n_defined(m)) &
          call ts%fail(t%line, 'velocity for particle ' // i2s(p + 1) // ' before it is defined')
        do c = 1, 3
          v(c) = ts%real('a velocity')
        end do
        do a = 1, 3
          m%particles%v(a, p + 1) = v(a)
        end do
      else if (k == 'body') then
        ib = body_index(ts, m, t, ts%integer('a body number'))
        do c = 1, 3
          v(c) = ts%real('a velocity')
        end do
        do p = m%bodies(ib + 1)%first + 1, m%bodies(ib + 1)%first + m%bodies(ib + 1)%count
          do a = 1, 3
            m%particles%v(a, p) = v(a)
          end do
        end do
      else
        call ts%fail(t%line, "in 'velo': expected 'node', 'body' or 'endv', found '" // &
                     ts%text_of(t) // "'")
      end if
    end do
  end subroutine read_velocities

  subroutine read_loads(ts, m, key)
    type(token_stream), intent(inout) :: ts
    type(model_t), intent(inout) :: m
    type(token_t), intent(in) :: key
    type(token_t) :: t
    character(len=:), allocatable :: k
    real(dp) :: f(3)
    integer :: first, count, ib, p, a, c
    call need_counts(ts, m, key, .true., .false., .false.)
    do
      t = ts%next()
      k = key4(ts%text_of(t))
      if (k == 'endl') return
      if (k == 'node' .or. k == 'body') then
        if (.not. allocated(m%particles%fext)) then
          allocate(m%particles%fext(3, m%particles%np))
          m%particles%fext = 0.0_dp
        end if
        m%has_loads = .true.
        if (k == 'node') then
          first = particle_index(ts, m, t, ts%integer('a particle id'))
          if (first >= n_defined(m)) &
            call ts%fail(t%line, 'load on particle ' // i2s(first + 1) // ' before it is defined')
          count = 1
        else
          ib = body_index(ts, m, t, ts%integer('a body number'))
          first = m%bodies(ib + 1)%first
          count = m%bodies(ib + 1)%count
        end if
        do c = 1, 3
          f(c) = ts%real('a force')
        end do
        do p = first + 1, first + count
          do a = 1, 3
            m%particles%fext(a, p) = m%particles%fext(a, p) + f(a)
          end do
        end do
      else if (k == 'grav') then
        ib = body_index(ts, m, t, ts%integer('a body number'))
        do c = 1, 3
          f(c) = ts%real('an acceleration')
        end do
        do a = 1, 3
          m%bodies(ib + 1)%gravity(a) = f(a)
        end do
        m%has_gravity = .true.
      else
        call ts%fail(t%line, "in 'load': expected 'node', 'body', 'grav' or 'endl', found '" // &
                     ts%text_of(t) // "'")
      end if
    end do
  end subroutine read_loads

  subroutine finish(ts, m, line, box_line, dcell_line)
    type(token_stream), intent(in) :: ts
    type(model_t), intent(inout) :: m
    integer, intent(in) :: line, box_line(3), dcell_line
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
    if (m%has_bulk) then
      allocate(m%particles%qv(m%particles%np))
      m%particles%qv = 0.0_dp
    end if
    ! Initial internal energy from E0 (per unit initial volume), initial temperature.
    thermal = .false.
    do i = 1, m%nmat
      thermal = thermal .or. m%mats(i)%type == MAT_JOHN .or. m%mats(i)%type == MAT_JCF
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
        if (thermal) m%particles%temp(p) = mp%t_room
      end associate
    end do
    ! GIMP particle half-size lp: half the spacing of bloc/sphe/cyli particles, half the cube
    ! root of the volume of poin particles; at most h/2 (the 27-node stencil).
    if (m%gimp) then
      allocate(m%particles%psize(m%particles%np))
      m%particles%psize = 0.0_dp
      clamped = .false.
      do i = 1, m%nbodies
        do p = m%bodies(i)%first + 1, m%bodies(i)%first + m%bodies(i)%count
          if (m%bodies(i)%spacing > 0.0_dp) then
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
      do a = 1, 3
        n = (m%box_hi(a) - m%box_lo(a)) / m%dcell + 0.5_dp
        fl = aint(n)
        if (fl > n) fl = fl - 1.0_dp
        if (fl < 2.0_dp) call ts%fail(line, "'gimp' needs at least two cells along each axis")
      end do
    end if
    ! dt = dtscale * h / c_max (the dilatational wave speed, D for hiex, c for null), fixed
    ! for the run; with bulk viscosity dtscale h / (c_max (q2 + sqrt(1 + q2^2))).
    if (m%has_bulk) then
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
  end subroutine finish

end module mpm3d_data_in
