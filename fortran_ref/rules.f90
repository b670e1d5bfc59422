! The rules (cxx/core/rules.hpp): every place where mpm3d deliberately differs from the
! original programs, as a named rule with two values (0 ours, 1 the original's), held in
! step_rules (the C struct StepRules, a group of step_context) and chosen once when the deck
! is read. The same names, values and presets as the C++ table; the rules.* tests run both
! programs under each.
module mpm3d_rules
  use, intrinsic :: iso_c_binding, only: c_int
  implicit none
  private

  integer, parameter, public :: RULE_COUNT = 18

  ! struct StepRules, member for member (0 is always ours).
  type, bind(C), public :: step_rules
    integer(c_int) :: program = 0        ! 0 the book program's conventions, 1 the current program's
    integer(c_int) :: time_step = 0      ! 0 the initial dt kept, 1 recomputed every step
    integer(c_int) :: bulk_book = 0      ! book program: 0 'bulk' applied, 1 read and ignored
    integer(c_int) :: bulk_switch = 0    ! bulk viscosity where 0 the volume shrinks, 1 the mean stress is compressive
    integer(c_int) :: bulk_linear = 0    ! 0 every material with its wave speed, 1 the current program's materials
    integer(c_int) :: burn = 0           ! 0 ramp over 1.5 cells, 1 step at the lighting time
    integer(c_int) :: dp_return = 0      ! Drucker-Prager: 0 onto the yield surface, 1 the original's branches
    integer(c_int) :: deck_reals = 0     ! 0 double, 1 rounded to single precision
    integer(c_int) :: tl_shape = 0       ! TLmp: 0 at the reference position, 1 at the cell's centre
    integer(c_int) :: sg_lower = 0       ! sgmp auxiliary cell at a lower face: 0 nearest, 1 truncated
    integer(c_int) :: sg_beyond = 0      ! sgmp weights beyond a one-layer grid: 0 nearest centre, 1 dropped
    integer(c_int) :: fluid_viscous = 0  ! viscous null: 0 2 mu dev(D), 1 2 mu D
    integer(c_int) :: bulk_work = 0      ! work of q: 0 by the mean of the old and new q, 1 by the new q
    integer(c_int) :: pressure_q = 0     ! output pres: 0 with q in it, 1 without (mpm3d's writers only)
    integer(c_int) :: clay_return = 0    ! clay: 0 return solved (Newton), 1 the newest program's linearised step
    integer(c_int) :: null_eos = 0       ! null's EOS: 0 as the deck gives it, 1 first coefficient := wave speed
    integer(c_int) :: start_temp = 0     ! particles' starting temperature: 0 the card's room temperature, 1 293
    integer(c_int) :: contact = 0        ! contact: 0 ours (recontact; force d / dt_int), 1 once, force d / dt
  end type step_rules

  ! The --rules preset and the --rule settings (rule, value), in order; the last wins.
  integer, parameter, public :: PRESET_OURS = 0, PRESET_ORIGINAL = 1, PRESET_BOOK = 2, PRESET_CURRENT = 3
  type, public :: rule_request
    integer :: preset = PRESET_OURS
    integer :: nset = 0
    integer :: set_rule(64) = 0, set_value(64) = 0
  end type rule_request

  character(len=13), parameter :: rule_name(RULE_COUNT) = [character(len=13) :: &
    'program', 'time_step', 'bulk_book', 'bulk_switch', 'bulk_linear', 'burn', 'dp_return', &
    'deck_reals', 'tl_shape', 'sg_lower', 'sg_beyond', 'fluid_viscous', &
    'bulk_work', 'pressure_q', 'clay_return', 'null_eos', 'start_temp', 'contact']
  character(len=10), parameter :: value0(RULE_COUNT) = [character(len=10) :: &
    'book', 'book', 'apply', 'volume', 'all', 'ramp', 'surface', 'double', 'particle', 'nearest', &
    'nearest', 'deviator', 'mean', 'in', 'solved', 'deck', 'room', 'twice']
  character(len=10), parameter :: value1(RULE_COUNT) = [character(len=10) :: &
    'current', 'current', 'ignore', 'stress', 'original', 'step', 'original', 'single', 'centre', &
    'truncate', 'drop', 'full', 'new', 'out', 'linear', 'wave_speed', '293', 'original']
  ! The book program's and the current program's value of each rule.
  integer, parameter :: book_value(RULE_COUNT) = [0, 0, 1, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 1, 0, 1, 1]
  integer, parameter :: current_value(RULE_COUNT) = [1, 1, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1]

  public :: parse_rule_preset, add_rule_setting, resolve_rules

contains

  ! "ours", "original", "book", "current"; err is '' or the message.
  subroutine parse_rule_preset(name, req, err)
    character(len=*), intent(in) :: name
    type(rule_request), intent(inout) :: req
    character(len=:), allocatable, intent(out) :: err
    err = ''
    select case (name)
    case ('ours')
      req%preset = PRESET_OURS
    case ('original')
      req%preset = PRESET_ORIGINAL
    case ('book')
      req%preset = PRESET_BOOK
    case ('current')
      req%preset = PRESET_CURRENT
    case default
      err = "--rules must be ours, original, book or current, got '" // name // "'"
    end select
  end subroutine parse_rule_preset

  ! Adds "NAME=VALUE" to the request; err is '' or the message.
  subroutine add_rule_setting(req, setting, err)
    type(rule_request), intent(inout) :: req
    character(len=*), intent(in) :: setting
    character(len=:), allocatable, intent(out) :: err
    integer :: eq, i
    character(len=:), allocatable :: name, val
    err = ''
    eq = index(setting, '=')
    if (eq == 0) then
      name = setting
      val = ''
    else
      name = setting(1:eq - 1)
      val = setting(eq + 1:)
    end if
    do i = 1, RULE_COUNT
      if (name /= trim(rule_name(i))) cycle
      if (val /= trim(value0(i)) .and. val /= trim(value1(i))) then
        err = '--rule ' // name // ' must be ' // trim(value0(i)) // ' or ' // trim(value1(i)) // &
              ", got '" // val // "'"
        return
      end if
      if (req%nset >= size(req%set_rule)) then
        err = '--rule given too often'
        return
      end if
      req%nset = req%nset + 1
      req%set_rule(req%nset) = i
      req%set_value(req%nset) = merge(1, 0, val == trim(value1(i)))
      return
    end do
    err = "--rule needs NAME=VALUE with NAME one of the rules (see mpm3d --help), got '" // setting // "'"
  end subroutine add_rule_setting

  ! The rules of a run of a deck whose keywords name the current program (deck_current) or
  ! the book's (resolve_rules in cxx/core/rules.cpp). time_step follows the program unless set.
  function resolve_rules(req, deck_current) result(r)
    type(rule_request), intent(in) :: req
    logical, intent(in) :: deck_current
    type(step_rules) :: r
    integer :: v(RULE_COUNT), program, i
    logical :: time_step_set
    v = 0
    program = merge(1, 0, deck_current)
    if (req%preset == PRESET_BOOK) program = 0
    if (req%preset == PRESET_CURRENT) program = 1
    if (req%preset /= PRESET_OURS) v = merge(current_value, book_value, program == 1)
    v(1) = program
    time_step_set = .false.
    do i = 1, req%nset
      v(req%set_rule(i)) = req%set_value(i)
      time_step_set = time_step_set .or. req%set_rule(i) == 2
    end do
    if (.not. time_step_set) v(2) = v(1)
    r = step_rules(v(1), v(2), v(3), v(4), v(5), v(6), v(7), v(8), v(9), v(10), v(11), v(12), v(13), v(14), &
                   v(15), v(16), v(17), v(18))
  end function resolve_rules

end module mpm3d_rules
