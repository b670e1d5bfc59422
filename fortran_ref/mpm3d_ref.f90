! MPM3D (the program): the Fortran reference driver. Reads a deck with its own reader
! (mpm3d_data_in), runs the time loop of Simulation::step (cxx/solver/simulation.cpp), walking
! the same step table (cxx/stages/step_order.c), with the Fortran stage kernels (stage_*.f90,
! called by identifier through mpm3d_update_step) and writes the HDF5 state file.
!
! usage: mpm3d_ref [--steps N] [--end-time T] [--state F.h5] [--init-state F.h5]
!                  [--energies F.txt] [--patch-cells N] [--regrid-every N] [--particle-order blocks|deck] [--quiet] DECK.mpm
! --regrid-every N: the adaptive background grid (as mpm3d; default: the deck's adgr, else
! off); each regrid prints 'regrid step K window i0 i1 j0 j1 k0 k1' as mpm3d does.
! --energies writes the kinetic, internal and initial total energy, the bound of the external
! work and the momentum of the last step with 17 significant digits (exact doubles), to
! compare with mpm3d --summary.
program mpm3d_ref
  use, intrinsic :: iso_c_binding
  use, intrinsic :: iso_fortran_env, only: int64, error_unit, output_unit
  use mpm3d_material
  use mpm3d_particle
  use mpm3d_grid
  use mpm3d_ffi, only: parse_integer, parse_real, fatal
  use mpm3d_data_in
  use mpm3d_update_step
  use mpm3d_data_out
  use mpm3d_rules, only: rule_request, parse_rule_preset, add_rule_setting
  implicit none

  integer(c_int) :: step_order(MPM3D_MAX_STEP_STAGES)   ! the deck's scheme's row of the step table
  integer :: nstage                            ! stages in step_order
  type(model_t), target :: model
  type(grid_t), target :: grid, grid2          ! grid2, ctx2: contact only (component 2)
  type(step_context), target :: ctx, ctx2
  real(dp), allocatable, target :: lx(:,:), partials(:,:), gravity(:,:)
  real(dp), allocatable, target :: gnormal1(:,:), gnormal2(:,:), cpartials(:,:)   ! contact only
  real(dp), allocatable, target :: aux(:,:)   ! sgmp only: the cell centres' fields
  integer(c_int), allocatable, target :: cell(:), body_comp(:)
  character(len=:), allocatable :: deck, state_path, init_path, energy_path, err
  integer(int64) :: max_steps, steps, iv
  integer :: patch_cells, i, nargs, np, b, rc, regrid_every, halo
  type(rule_request) :: rules  ! --rules, --rule, --time-step (rules.f90)
  integer :: woff(3), wnc(3)
  real(dp) :: end_time, time, eps, kinetic, internal, rv, initial_total, momentum(3)
  real(dp) :: external_work    ! bound of the work of gravity and loads: sum |f.v| dt (health check)
  real(dp) :: kinetic_before   ! drda: the kinetic energy before the step
  logical :: quiet, order_blocks, settle, end_time_given
  character(len=4096) :: arg

  ! ---------------------------------------------------------------- command line
  deck = ''
  state_path = ''
  init_path = ''
  energy_path = ''
  max_steps = -1
  end_time = -1.0_dp
  patch_cells = 4
  order_blocks = .true.
  regrid_every = -1
  quiet = .false.
  nargs = command_argument_count()
  i = 1
  do while (i <= nargs)
    call get_command_argument(i, arg)
    select case (trim(arg))
    case ('--help', '-h')
      write (output_unit, '(a)') 'usage: mpm3d_ref [--steps N] [--end-time T] [--state F.h5] ' // &
        '[--init-state F.h5] [--energies F.txt] [--patch-cells N] [--regrid-every N] ' // &
        '[--particle-order blocks|deck] [--time-step book|current] ' // &
        '[--rules ours|original|book|current] [--rule NAME=VALUE] [--quiet] DECK.mpm'
      stop
    case ('--steps')
      call value(i, arg)
      if (.not. parse_integer(trim(arg), iv)) call usage('--steps needs an integer')
      if (iv < 0) call usage('--steps must not be negative')
      max_steps = iv
    case ('--end-time')
      call value(i, arg)
      if (.not. parse_real(trim(arg), rv)) call usage('--end-time needs a positive number')
      if (.not. (rv > 0.0_dp)) call usage('--end-time needs a positive number')
      end_time = rv
    case ('--state')
      call value(i, arg)
      state_path = trim(arg)
    case ('--init-state')
      call value(i, arg)
      init_path = trim(arg)
    case ('--energies')
      call value(i, arg)
      energy_path = trim(arg)
    case ('--patch-cells')
      call value(i, arg)
      if (.not. parse_integer(trim(arg), iv)) call usage('--patch-cells needs an integer')
      if (iv < 1 .or. iv > 64) call usage('--patch-cells must lie in 1..64')
      patch_cells = int(iv)
    case ('--regrid-every')
      call value(i, arg)
      if (.not. parse_integer(trim(arg), iv)) call usage('--regrid-every needs an integer')
      if (iv < 0 .or. iv > 1000000000_int64) call usage('--regrid-every must lie in 0..1000000000')
      regrid_every = int(iv)
    case ('--particle-order')
      call value(i, arg)
      if (trim(arg) /= 'blocks' .and. trim(arg) /= 'deck') call usage('--particle-order must be blocks or deck')
      order_blocks = trim(arg) == 'blocks'
    case ('--time-step')
      call value(i, arg)
      if (trim(arg) /= 'book' .and. trim(arg) /= 'current') call usage('--time-step must be book or current')
      call add_rule_setting(rules, 'time_step=' // trim(arg), err)
    case ('--rules')
      call value(i, arg)
      call parse_rule_preset(trim(arg), rules, err)
      if (len(err) > 0) call usage(err)
    case ('--rule')
      call value(i, arg)
      call add_rule_setting(rules, trim(arg), err)
      if (len(err) > 0) call usage(err)
    case ('--quiet', '-q')
      quiet = .true.
    case default
      if (arg(1:1) == '-') call usage('unknown option ' // trim(arg))
      if (len(deck) > 0) call usage('more than one deck given')
      deck = trim(arg)
    end select
    i = i + 1
  end do
  if (len(deck) == 0) call usage('no deck given')

  ! ---------------------------------------------------------------- set-up
  call read_deck(deck, model, rules)
  end_time_given = end_time > 0.0_dp
  if (end_time <= 0.0_dp) end_time = model%endtime
  np = model%particles%np
  if (regrid_every < 0) regrid_every = model%regrid_every
  if (model%tl .and. regrid_every > 0) &
    call fatal(deck // ": --regrid-every with 'TLmp': the reference grid of TLmp cannot move")
  if (model%sg .and. regrid_every > 0) &
    call fatal(deck // ": --regrid-every with 'sgmp': the cell-centre grid of sgmp does not move")
  ! The two contact grids share one node numbering: no adaptive window with contact (as mpm3d).
  if (model%contact) regrid_every = 0
  ! 27-node stencils and sgmp's cell centres reach one node beyond a patch's cells.
  halo = merge(1, 0, model_shape(model) /= 0 .or. model%sg)
  if (model%gimp .and. patch_cells < 2) call usage('GIMP needs patches of at least two cells')
  if (model%sg .and. patch_cells < 2) call usage('sgmp needs patches of at least two cells')
  if (model%bspline .and. patch_cells < 2) call usage('B-spline needs patches of at least two cells')
  call grid_define(grid, model%box_lo, model%box_hi, model%dcell, patch_cells, halo, err)
  if (len(err) > 0) call fatal(deck // ': ' // err)
  grid%fix = model%fix
  grid%mass_cutoff = model%mass_cutoff
  ! The storage order of the particles (as the Simulation constructor).
  call particles_order_by_blocks(model%particles, model%box_lo, model%dcell, grid%deck_nc, patch_cells, &
                                 order_blocks)
  ! The first window (the whole box without the adaptive grid), as the Simulation constructor.
  woff = 0
  wnc = grid%deck_nc
  if (regrid_every > 0) call grid_adaptive_window(grid, model%particles%x, model%particles%v, np, &
                                                  regrid_every, model%dt, woff, wnc)
  call grid_set_window(grid, woff, wnc)
  if (model%contact) then
    call grid_setup(grid2, model%box_lo, model%box_hi, model%dcell, patch_cells, halo, err)
    grid2%fix = model%fix
    grid2%mass_cutoff = model%mass_cutoff
    allocate(grid2%patch_part(np))
    grid2%patch_part = 0
  end if
  allocate(lx(3, np), cell(np), grid%patch_part(np))
  lx = 0.0_dp
  cell = -1
  grid%patch_part = 0
  allocate(gravity(3, max(model%nbodies, 1)))
  gravity = 0.0_dp
  do b = 1, model%nbodies
    gravity(:, b) = model%bodies(b)%gravity
  end do
  call bind_context()
  nstage = mpm3d_step_order(int(model%scheme, c_int), step_order)
  if (nstage < 0) call fatal(deck // ': unknown update scheme')

  ! Energies of the initial state, over the patch lists of its binning (as the C++
  ! Simulation constructor; every step bins again).
  call run_each(ST_BIN)
  call mpm3d_f_energy(ctx)
  initial_total = ctx%out%result(1) + ctx%out%result(2)
  if (.not. quiet) then
    write (output_unit, '(a)') 'mpm3d_ref: ' // model%title
    write (output_unit, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,es12.5)') '  ', np, ' particles, grid ', &
      grid%nc(1), ' x ', grid%nc(2), ' x ', grid%nc(3), ', ', grid%npatch, ' patches, dt ', model%dt
    do i = 1, model%nwarn
      write (output_unit, '(a)') '  warning: ' // trim(model%warnings(i))
    end do
  else
    ! --quiet hides progress, never warnings (as mpm3d).
    do i = 1, model%nwarn
      write (error_unit, '(a)') 'mpm3d_ref: warning: ' // trim(model%warnings(i))
    end do
  end if
  steps = 0
  if (regrid_every > 0) call note_regrid(0)
  if (len(init_path) > 0) call write_state_h5(init_path, model, 0.0_dp, 0_int64, model%dt)

  ! ---------------------------------------------------------------- time loop
  steps = 0
  time = 0.0_dp
  kinetic = ctx%out%result(1)
  internal = ctx%out%result(2)
  momentum = ctx%out%result(3:5)
  rc = 0
  external_work = 0.0_dp
  eps = 1.0e-9_dp * model%dt
  ! QuLo without --end-time: on past the end time until the load has settled (as mpm3d).
  settle = model%load_ramp_time > 0.0_dp .and. .not. end_time_given
  do while (running() .and. (max_steps < 0 .or. steps < max_steps))
    kinetic_before = kinetic
    call step()
    steps = steps + 1
    time = time + model%dt
    kinetic = ctx%out%result(1)
    internal = ctx%out%result(2)
    momentum = ctx%out%result(3:5)
    ! The energy stage's sum of |f . v| (0 without body forces) times this step's dt.
    external_work = external_work + ctx%out%result(9) * model%dt
    if (model%dt_per_step) model%dt = velocity_time_step()
    ! drda: every particle stops after a step in which the kinetic energy did not grow.
    if (model%dynamic_relaxation .and. kinetic - kinetic_before <= 0.0_dp) then
      model%particles%v = 0.0_dp
      kinetic = 0.0_dp
    end if
    if (.not. healthy()) then
      rc = 3
      exit
    end if
  end do
  if (.not. quiet) then
    write (output_unit, '(a,i0,a,es14.7,a,es14.7,a,es14.7,a,i0)') 'done: ', steps, ' steps, t ', time, &
      '  KE ', kinetic, '  IE ', internal, '  outside ', ctx%out%noutside + ctx2%out%noutside
  end if
  if (len(state_path) > 0) call write_state_h5(state_path, model, time, steps, model%dt)
  if (len(energy_path) > 0) call write_energies(energy_path)
  ! The main program's deferred-length strings outlive it (implicit SAVE) and would be
  ! reported by LeakSanitizer (make test-sanitize): free them.
  deallocate(deck, state_path, init_path, energy_path, err)
  if (rc /= 0) stop 3, quiet=.true.

contains

  ! Whether the time loop goes on (Simulation::quasi_static_done with QuLo).
  logical function running()
    if (settle) then
      running = .not. (time > model%endtime .and. kinetic / (kinetic + internal) < 0.005_dp .and. time > 100.0_dp)
    else
      running = time < end_time - eps
    end if
  end function running

  ! The current version's dt from the particle velocities (Simulation::velocity_time_step):
  ! dtscale min over the materials of h / (c + v_max).
  real(dp) function velocity_time_step() result(dt)
    real(dp) :: vmax
    integer :: p, a, k
    vmax = 0.0_dp
    do p = 1, np
      do a = 1, 3
        vmax = max(vmax, abs(model%particles%v(a, p)))
      end do
    end do
    dt = huge(1.0_dp)
    do k = 1, model%nmat
      dt = min(dt, model%dcell / (model%mats(k)%wave_speed + vmax))
    end do
    dt = dt * model%dtscale
  end function velocity_time_step

  ! Health check after a step (Simulation::health_check): non-finite energies, or a total
  ! energy above twice the initial energy plus the external work, end the run.
  logical function healthy()
    real(dp) :: total
    healthy = .true.
    if (abs(kinetic) <= huge(kinetic) .and. abs(internal) <= huge(internal)) then
      total = kinetic + internal
      if (abs(total) <= 2.0_dp * (abs(initial_total) + abs(external_work)) + 1.0e-300_dp) return
      write (error_unit, '(a,i0,a,es12.5,a,es12.5,a,es12.5,a)') 'mpm3d_ref: numerical instability at step ', &
        steps, ': total energy ', total, ' exceeds twice the initial energy ', initial_total, &
        ' plus the external work ', external_work, ' (reduce dtscale, or use MUSL)'
    else
      write (error_unit, '(a,i0,a)') 'mpm3d_ref: numerical breakdown at step ', steps, ': non-finite energy'
    end if
    healthy = .false.
  end function healthy

  subroutine write_energies(path)
    character(len=*), intent(in) :: path
    integer :: u, ios
    open (newunit=u, file=path, status='replace', action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot write ' // path)
    write (u, '(a,es25.16e3)') 'kinetic_energy ', kinetic
    write (u, '(a,es25.16e3)') 'internal_energy ', internal
    write (u, '(a,es25.16e3)') 'initial_total_energy ', initial_total
    write (u, '(a,es25.16e3)') 'external_work ', external_work
    write (u, '(a,3es25.16e3)') 'momentum ', momentum
    close (u)
  end subroutine write_energies

  subroutine usage(what)
    character(len=*), intent(in) :: what
    write (error_unit, '(a)') 'mpm3d_ref: ' // what // ' (see --help)'
    stop 2, quiet=.true.
  end subroutine usage

  subroutine value(i, arg)
    integer, intent(inout) :: i
    character(len=*), intent(inout) :: arg
    character(len=:), allocatable :: opt
    opt = trim(arg)
    if (i + 1 > command_argument_count()) call usage(opt // ' needs a value')
    i = i + 1
    call get_command_argument(i, arg)
  end subroutine value

  ! Points the step context at the model's and the grid's arrays (Simulation::bind).
  subroutine bind_context()
    integer :: a
    associate (p => model%particles)
      ctx%part%x = c_loc(p%x)
      ctx%part%v = c_loc(p%v)
      ctx%part%sig = c_loc(p%sig)
      ctx%part%mass = c_loc(p%mass)
      ctx%part%vol = c_loc(p%vol)
      ctx%part%epeff = c_loc(p%epeff)
      ctx%part%ie = c_loc(p%ie)
      ctx%part%temp = c_null_ptr
      if (allocated(p%temp)) ctx%part%temp = c_loc(p%temp)
      ctx%part%fext = c_null_ptr
      if (allocated(p%fext)) ctx%part%fext = c_loc(p%fext)
      ctx%part%tlight = c_null_ptr
      if (allocated(p%tlight)) ctx%part%tlight = c_loc(p%tlight)
      ctx%part%qv = c_null_ptr
      if (allocated(p%qv)) ctx%part%qv = c_loc(p%qv)
      ctx%part%mat = c_loc(p%mat)
      ctx%part%body = c_loc(p%body)
    end associate
    ctx%part%lx = c_loc(lx)
    ctx%part%cell = c_loc(cell)
    ctx%part%gravity = c_loc(gravity)
    ctx%part%mats = c_loc(model%mats)
    ctx%patch%patch_part = c_loc(grid%patch_part)
    ctx%patch%patch_buf = c_null_ptr
    ctx%grid%h = grid%h
    ctx%grid%inv_h = 1.0_dp / grid%h
    ctx%clock%dt = model%dt
    ctx%clock%dt_int = model%dt
    ctx%grid%mass_cutoff = grid%mass_cutoff
    ctx%part%np = np
    ctx%part%nbody = model%nbodies
    ctx%part%nmat = model%nmat
    ctx%patch%patch_cells = grid%patch_cells
    ctx%grid%fix = grid%fix
    ctx%method%scheme = model%scheme
    ctx%method%has_body_force = merge(1, 0, model%has_gravity .or. model%has_loads .or. model%damping > 0.0_dp)
    ctx%method%load_ramp_time = model%load_ramp_time
    ctx%method%damping = model%damping
    ctx%method%bulk_q1 = model%bulk_q1
    ctx%method%bulk_q2 = model%bulk_q2
    ! GIMP and B-spline: 27-node stencils, patch buffers with a halo of one node layer.
    ctx%part%psize = c_null_ptr
    if (model%gimp) ctx%part%psize = c_loc(model%particles%psize)
    ctx%method%shape = model_shape(model)
    ctx%grid%fix_layers = model_fix_layers(model)
    ! sgmp: the cell centres' scratch fields (the grid window is the whole box: no regrid).
    ctx%sgmp%aux = c_null_ptr
    ctx%method%sg = merge(1, 0, model%sg)
    ! The shape-function family, as Simulation::bind chooses it (TRANSFER_*, update_step.hpp).
    ctx%method%family = merge(2, merge(1, 0, ctx%method%shape /= 0), model%sg)
    if (model%sg) then
      allocate(aux(34, grid%nc(1) * grid%nc(2) * grid%nc(3)))
      aux = 0.0_dp
      ctx%sgmp%aux = c_loc(aux)
    end if
    ctx%part%defgrad = c_null_ptr
    if (allocated(model%particles%defgrad)) ctx%part%defgrad = c_loc(model%particles%defgrad)
    ctx%method%uvf = merge(1, 0, model%uvf)
    ctx%method%tl = merge(1, 0, model%tl)
    ctx%rules = model%rules
    ctx%part%pk1 = c_null_ptr
    if (model%tl) then
      ctx%part%xbin = c_loc(model%particles%x0)   ! the particles stay in their reference cells
      ctx%part%pk1 = c_loc(model%particles%pk1)
    else
      ctx%part%xbin = c_loc(model%particles%x)
    end if
    ctx%patch%patch_halo = grid%patch_halo
    call bind_grid()      ! before the contact copy: ctx2 starts as a copy of ctx
    if (model%contact) then
      ! Two contexts over the same particles (Simulation::bind): component 1 in ctx,
      ! component 2 in ctx2 with its own grid; the contact stage couples them.
      allocate(body_comp(max(model%nbodies, 1)), gnormal1(3, grid_nnode(grid)), &
               gnormal2(3, grid_nnode(grid)), cpartials(4, grid%npatch))
      body_comp = 1
      do a = 1, model%nbodies
        body_comp(a) = model%bodies(a)%component
      end do
      gnormal1 = 0.0_dp
      gnormal2 = 0.0_dp
      cpartials = 0.0_dp
      ctx%contact%body_comp = c_loc(body_comp)
      ctx%contact%contact_mu = model%contact_mu
      ctx%contact%contact_normbody = model%contact_normbody
      ctx%contact%cpartials = c_loc(cpartials)
      ctx2 = ctx
      ctx%contact%only_comp = 1
      ctx%contact%gnormal = c_loc(gnormal1)
      ctx%contact%other = c_loc(ctx2)
      ctx2%contact%only_comp = 2
      ctx2%contact%gnormal = c_loc(gnormal2)
      call point_at_grid(ctx2, grid2)
      ctx2%patch%patch_part = c_loc(grid2%patch_part)
      ctx2%patch%patch_buf = c_null_ptr
    end if
  end subroutine bind_context

  ! ... and at the grid's arrays, again after a regrid (Simulation::bind_grid).
  subroutine bind_grid()
    integer :: a
    call point_at_grid(ctx, grid)
    do a = 1, 3
      ctx%grid%origin(a) = grid%origin(a)
      ctx%grid%nc(a) = grid%nc(a)
      ctx%grid%nn(a) = grid%nn(a)
      ctx%patch%npd(a) = grid%npd(a)
      ctx%grid%cell_off(a) = grid%off(a)
    end do
    ctx%grid%nnode = grid_nnode(grid)
    ctx%patch%npatch = grid%npatch
    ! The energy stage's columns: one per patch and one for the particles outside the grid.
    if (allocated(partials)) then
      if (size(partials, 2) /= grid%npatch + 1) deallocate(partials)
    end if
    if (.not. allocated(partials)) then
      allocate(partials(REDUCE_FIELDS, grid%npatch + 1))
      partials = 0.0_dp
    end if
    ctx%out%partials = c_loc(partials)
  end subroutine bind_grid

  ! The node arrays and patch tables of grid g in context c.
  subroutine point_at_grid(c, g)
    type(step_context), intent(inout) :: c
    type(grid_t), intent(in), target :: g
    c%grid%gmass = c_loc(g%mass)
    c%grid%gmom = c_loc(g%mom)
    c%grid%gforce = c_loc(g%force)
    c%patch%patch_start = c_loc(g%patch_start)
    c%patch%patch_slot = c_loc(g%patch_slot)
  end subroutine point_at_grid

  ! Buffers for the non-empty patches found by the bin stage (Simulation::ensure_patch_buffers).
  subroutine ensure_patch_buffers()
    call ensure_buffers_of(grid, ctx)
    if (model%contact) call ensure_buffers_of(grid2, ctx2)
  end subroutine ensure_patch_buffers

  ! Room for c%patch%nslot patch buffers in g, grown (never shrunk) as the non-empty patches need.
  subroutine ensure_buffers_of(g, c)
    type(grid_t), intent(inout), target :: g
    type(step_context), intent(inout) :: c
    integer :: have
    have = 0
    if (allocated(g%patch_buf)) have = size(g%patch_buf, 3)
    if (have < c%patch%nslot) then
      if (allocated(g%patch_buf)) deallocate(g%patch_buf)
      allocate(g%patch_buf(NODE_FIELDS, g%patch_nodes, c%patch%nslot))
      g%patch_buf = 0.0_dp
      c%patch%patch_buf = c_loc(g%patch_buf)
    end if
  end subroutine ensure_buffers_of

  ! The adaptive grid: a new window from the particles (Simulation::regrid).
  subroutine regrid()
    call grid_adaptive_window(grid, model%particles%x, model%particles%v, np, max(regrid_every, 1), &
                              model%dt, woff, wnc)
    call grid_set_window(grid, woff, wnc)
    call bind_grid()
  end subroutine regrid

  ! The first words of mpm3d's regrid line (Simulation::note_regrid).
  subroutine note_regrid(escaped)
    integer, intent(in) :: escaped
    if (quiet) return
    write (output_unit, '(a,i0,a,6(1x,i0))', advance='no') 'regrid step ', steps, ' window', &
      grid%off(1), grid%off(1) + grid%nc(1), grid%off(2), grid%off(2) + grid%nc(2), &
      grid%off(3), grid%off(3) + grid%nc(3)
    if (escaped > 0) then
      write (output_unit, '(a,i0,a)') ' (forced: ', escaped, ' particles had left the window)'
    else
      write (output_unit, '(a)') ''
    end if
  end subroutine note_regrid

  ! One explicit step (Simulation::step): the dt of this step, then the stages of the
  ! scheme's order.
  subroutine step()
    integer :: s
    ctx%clock%dt = model%dt
    if (steps == 0) then
      ctx%clock%dt_int = 0.5_dp * model%dt      ! first step: momentum with dt/2
    else
      ctx%clock%dt_int = model%dt
    end if
    ctx%clock%time = time + model%dt      ! the end of this step (programmed burn)
    if (model%contact) then
      ctx2%clock%dt = ctx%clock%dt
      ctx2%clock%dt_int = ctx%clock%dt_int
      ctx2%clock%time = ctx%clock%time
    end if
    do s = 1, nstage
      if (mpm3d_stage_needs_contact(step_order(s)) /= 0 .and. .not. model%contact) cycle
      if (step_order(s) == ST_RECONTACT .and. ctx%rules%contact /= 0) cycle  ! rule contact=original
      if (step_order(s) == ST_BIN) then
        call bin_stage()
      else
        call run_each(step_order(s))
      end if
    end do
  end subroutine step

  ! A stage on component 1's context and, with contact, on component 2's in turn when the
  ! stage runs per component (stage_per_component).
  subroutine run_each(id)
    integer, intent(in) :: id
    call run_stage(id, ctx)
    if (model%contact .and. mpm3d_stage_per_component(id) /= 0) call run_stage(id, ctx2)
  end subroutine run_each

  ! The bin stage and what the driver does around it: the adaptive window (a scheduled
  ! regrid before; a regrid and a second binning when a particle has left the window; never
  ! with contact, which keeps the box), then buffers for the non-empty patches.
  subroutine bin_stage()
    integer :: escaped
    logical :: scheduled
    scheduled = regrid_every > 0 .and. steps > 0 .and. mod(steps, int(max(regrid_every, 1), int64)) == 0
    if (scheduled) call regrid()
    call run_each(ST_BIN)
    escaped = 0
    if (ctx%out%noutside > 0 .and. .not. grid_window_is_box(grid)) then
      ! A particle inside the deck's box has left the window: widen it and bin again.
      escaped = grid_count_escaped(grid, model%particles%x, cell, np)
      if (escaped > 0) then
        call regrid()
        call run_each(ST_BIN)
      end if
    end if
    if (scheduled .or. escaped > 0) call note_regrid(escaped)
    call ensure_patch_buffers()
  end subroutine bin_stage

end program mpm3d_ref
