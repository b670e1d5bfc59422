! Runs a deck through the C++ library from Fortran (module mpm3d_api) and writes the final
! state; bindings/tests/compare_state.sh compares it bit for bit with `mpm3d --state`.
!   fortran_state DECK STATE.h5 [NSTEPS [KERNELS]]
! Halfway through (and before the first step) every particle array is read and written
! back, which must not change a single bit of the result.
program fortran_state
  use mpm3d_api
  implicit none
  type(c_ptr) :: sim
  character(len=4096) :: deck, state, arg, kernels
  integer :: nsteps, first, np, ios
  real(c_double) :: mom(3), dt

  if (command_argument_count() < 2) error stop 'usage: fortran_state DECK STATE.h5 [NSTEPS [KERNELS]]'
  call get_command_argument(1, deck)
  call get_command_argument(2, state)
  nsteps = 60
  if (command_argument_count() >= 3) then
    call get_command_argument(3, arg)
    read (arg, *, iostat=ios) nsteps
    if (ios /= 0 .or. nsteps < 0) error stop 'NSTEPS must be a non-negative integer'
  end if
  kernels = ''
  if (command_argument_count() >= 4) call get_command_argument(4, kernels)

  print '(2a)', 'mpm3d library ', mpm3d_version()
  call check(mpm3d_open(deck, sim), 'mpm3d_open')
  if (.not. c_associated(sim)) error stop 'mpm3d_open returned a null handle'
  if (len(mpm3d_last_error()) /= 0) error stop 'message left after a successful call'
  np = mpm3d_num_particles(sim)
  dt = mpm3d_dt(sim)
  if (np < 1 .or. .not. (dt > 0.0_c_double)) error stop 'bad particle count or time step'
  if (mpm3d_steps(sim) /= 0_c_long .or. mpm3d_time(sim) /= 0.0_c_double) error stop 'not at step 0'
  print '(a,i0,a,es12.5,a,es12.5)', 'particles ', np, '  dt ', dt, '  end time ', mpm3d_end_time(sim)

  ! Kernel selection: the default is C++; these leave the table as it is.
  call check(mpm3d_set_kernel(sim, 'cxx'), 'mpm3d_set_kernel(cxx)')
  call check(mpm3d_set_kernel(sim, 'bin=cxx,energy=cxx'), 'mpm3d_set_kernel(per stage)')
  if (len_trim(kernels) > 0) then
    if (index(kernels, 'fortran') > 0 .and. .not. mpm3d_have_fortran_kernels()) then
      print '(a)', 'SKIP: this build has no Fortran reference kernels'
      call mpm3d_close(sim)
      stop 77
    end if
    call check(mpm3d_set_kernel(sim, kernels), 'mpm3d_set_kernel('//trim(kernels)//')')
  end if

  call round_trip()
  first = nsteps / 2
  call check(mpm3d_step(sim, first), 'mpm3d_step')
  if (mpm3d_steps(sim) /= int(first, c_long)) error stop 'wrong step count after the first half'
  call round_trip()
  call check(mpm3d_step(sim, nsteps - first), 'mpm3d_step')
  if (mpm3d_steps(sim) /= int(nsteps, c_long)) error stop 'wrong step count'
  if (abs(mpm3d_time(sim) - nsteps * dt) > 1.0e-9_c_double * nsteps * dt) error stop 'time is not nsteps*dt'

  call check(mpm3d_momentum(sim, mom), 'mpm3d_momentum')
  print '(a,i0,a,es24.16)', 'steps ', mpm3d_steps(sim), '  time ', mpm3d_time(sim)
  print '(a,es24.16,a,es24.16)', 'kinetic ', mpm3d_kinetic_energy(sim), '  internal ', mpm3d_internal_energy(sim)
  print '(a,3es24.16)', 'momentum ', mom
  call check(mpm3d_write_state(sim, state), 'mpm3d_write_state')
  call mpm3d_close(sim)
  if (c_associated(sim)) error stop 'mpm3d_close left the handle set'
  print '(2a)', 'state written to ', trim(state)

contains

  subroutine check(rc, what)
    integer(c_int), intent(in) :: rc
    character(len=*), intent(in) :: what
    if (rc /= MPM3D_OK) then
      write (*, '(a,": error ",i0,": ",a)') what, rc, mpm3d_last_error()
      error stop 1
    end if
  end subroutine

  ! Reads every particle array and writes it back unchanged.
  subroutine round_trip()
    real(c_double), allocatable :: a3(:, :), a6(:, :), s(:)
    real(c_double) :: ke, ie
    character(len=16), parameter :: scalars(5) = [character(len=16) :: &
      'mass', 'volume', 'epeff', 'internal_energy', 'temperature']
    integer :: i
    ke = mpm3d_kinetic_energy(sim)
    ie = mpm3d_internal_energy(sim)
    allocate (a3(3, np), a6(6, np), s(np))
    if (mpm3d_array_size(sim, 'position') /= 3_c_long * np) error stop 'array size of position'
    if (mpm3d_array_size(sim, 'stress') /= 6_c_long * np) error stop 'array size of stress'
    call check(mpm3d_get_array(sim, 'position', a3), 'get position')
    call check(mpm3d_set_array(sim, 'position', a3), 'set position')
    call check(mpm3d_get_array(sim, 'velocity', a3), 'get velocity')
    call check(mpm3d_set_array(sim, 'velocity', a3), 'set velocity')
    call check(mpm3d_get_array(sim, 'stress', a6), 'get stress')
    call check(mpm3d_set_array(sim, 'stress', a6), 'set stress')
    do i = 1, size(scalars)
      if (trim(scalars(i)) == 'temperature' .and. mpm3d_array_size(sim, 'temperature') < 0) cycle
      call check(mpm3d_get_array(sim, scalars(i), s), 'get '//trim(scalars(i)))
      call check(mpm3d_set_array(sim, scalars(i), s), 'set '//trim(scalars(i)))
    end do
    ! Setting arrays refreshes the energies from the (unchanged) state.
    if (mpm3d_kinetic_energy(sim) /= ke .or. mpm3d_internal_energy(sim) /= ie) &
      error stop 'energies changed by an unchanged state'
  end subroutine

end program fortran_state
