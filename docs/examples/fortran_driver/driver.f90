! A Fortran program driving MPM3D-CXX through the mpm3d_api module:
!   driver DECK [NSTEPS [KERNELS]]
! opens the deck, runs NSTEPS steps (default 100, or fewer to the deck's end time) and
! prints the time, the energies and the position of the first particle every tenth of
! the run.
program driver
  use mpm3d_api
  implicit none
  type(c_ptr) :: sim
  character(len=1024) :: deck, arg
  integer :: nsteps, chunk, done, n, ios
  real(c_double), allocatable :: x(:, :)

  if (command_argument_count() < 1) then
    print '(a)', 'usage: driver DECK [NSTEPS [KERNELS]]'
    stop 2
  end if
  call get_command_argument(1, deck)
  nsteps = 100
  if (command_argument_count() >= 2) then
    call get_command_argument(2, arg)
    read (arg, *, iostat=ios) nsteps
    if (ios /= 0 .or. nsteps < 0) then
      print '(2a)', 'driver: NSTEPS must be a non-negative integer, got ', trim(arg)
      stop 2
    end if
  end if

  if (mpm3d_open(deck, sim) /= MPM3D_OK) then
    print '(2a)', 'driver: ', mpm3d_last_error()
    stop 1
  end if
  if (command_argument_count() >= 3) then
    call get_command_argument(3, arg)
    if (mpm3d_set_kernel(sim, arg) /= MPM3D_OK) then
      print '(2a)', 'driver: ', mpm3d_last_error()
      stop 1
    end if
  end if

  ! Not past the deck's end time.
  nsteps = min(nsteps, int(mpm3d_end_time(sim) / mpm3d_dt(sim) + 0.5d0))
  allocate (x(3, mpm3d_num_particles(sim)))
  print '(a,a,i0,a,es11.4)', 'MPM3D-CXX ', mpm3d_version()//': ', mpm3d_num_particles(sim), &
    ' particles, dt ', mpm3d_dt(sim)
  print '(a6,a13,2a13,3a11)', 'step', 'time', 'kinetic', 'internal', 'x1', 'y1', 'z1'
  call report()
  chunk = max(1, nsteps / 10)
  done = 0
  do while (done < nsteps)
    n = min(chunk, nsteps - done)
    if (mpm3d_step(sim, n) /= MPM3D_OK) then
      print '(2a)', 'driver: ', mpm3d_last_error()
      call mpm3d_close(sim)
      stop 1
    end if
    done = done + n
    call report()
  end do
  call mpm3d_close(sim)

contains

  subroutine report()
    if (mpm3d_get_array(sim, 'position', x) /= MPM3D_OK) then
      print '(2a)', 'driver: ', mpm3d_last_error()
      stop 1
    end if
    print '(i6,es13.5,2es13.5,3f11.6)', mpm3d_steps(sim), mpm3d_time(sim), &
      mpm3d_kinetic_energy(sim), mpm3d_internal_energy(sim), x(:, 1)
  end subroutine

end program driver
