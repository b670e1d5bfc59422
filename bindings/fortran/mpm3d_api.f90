!> mpm3d_api: the MPM3D-CXX library for Fortran programs (docs/DESIGN.md section 5a).
!>
!> A thin ISO_C_BINDING layer over the C API (bindings/c/mpm3d.h); the names, arguments
!> and return codes are those of the C functions:
!>   - a simulation is a type(c_ptr) handle, from mpm3d_open, released by mpm3d_close;
!>   - Fortran strings are passed trimmed of trailing blanks and null-terminated;
!>   - particle arrays keep the shared layout: real(c_double) :: x(3,np), v(3,np),
!>     sig(6,np), scalars (np) (rank-1 arrays of the full size work as well);
!>   - integer functions return MPM3D_OK (0) on success, else an MPM3D_ERR_* code, and
!>     mpm3d_last_error() gives the message.
!>
!>   use mpm3d_api
!>   type(c_ptr) :: sim
!>   real(c_double), allocatable :: x(:,:)
!>   if (mpm3d_open('bar.mpm', sim) /= MPM3D_OK) stop mpm3d_last_error()
!>   ierr = mpm3d_step(sim, 100)
!>   allocate(x(3, mpm3d_num_particles(sim)))
!>   ierr = mpm3d_get_array(sim, 'position', x)
!>   call mpm3d_close(sim)
module mpm3d_api
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_f_pointer, &
                                         c_int, c_long, c_double, c_char, c_null_char, c_size_t
  implicit none
  private

  public :: c_ptr, c_null_ptr, c_associated, c_int, c_long, c_double
  public :: mpm3d_version, mpm3d_last_error, mpm3d_have_fortran_kernels, mpm3d_set_threads
  public :: mpm3d_open, mpm3d_close, mpm3d_set_kernel, mpm3d_step
  public :: mpm3d_time, mpm3d_steps, mpm3d_num_particles, mpm3d_dt, mpm3d_end_time
  public :: mpm3d_kinetic_energy, mpm3d_internal_energy, mpm3d_momentum
  public :: mpm3d_array_size, mpm3d_get_array, mpm3d_set_array, mpm3d_write_state
  public :: mpm3d_write_checkpoint, mpm3d_restart

  !> Return codes (mpm3d.h).
  integer(c_int), parameter, public :: MPM3D_OK = 0
  integer(c_int), parameter, public :: MPM3D_ERR_ARGUMENT = 1
  integer(c_int), parameter, public :: MPM3D_ERR_IO = 2
  integer(c_int), parameter, public :: MPM3D_ERR_DECK = 3
  integer(c_int), parameter, public :: MPM3D_ERR_KERNEL = 4
  integer(c_int), parameter, public :: MPM3D_ERR_HEALTH = 5
  integer(c_int), parameter, public :: MPM3D_ERR_MEMORY = 6
  integer(c_int), parameter, public :: MPM3D_ERR_INTERNAL = 7

  !> mpm3d_get_array(sim, name, dst): dst real(c_double), rank 1 or 2, contiguous.
  interface mpm3d_get_array
    module procedure get_array_1d, get_array_2d
  end interface mpm3d_get_array

  !> mpm3d_set_array(sim, name, src): src real(c_double), rank 1 or 2.
  interface mpm3d_set_array
    module procedure set_array_1d, set_array_2d
  end interface mpm3d_set_array

  ! The C functions.
  interface
    function c_version() bind(C, name="mpm3d_version") result(p)
      import :: c_ptr
      type(c_ptr) :: p
    end function
    function c_last_error() bind(C, name="mpm3d_last_error") result(p)
      import :: c_ptr
      type(c_ptr) :: p
    end function
    function c_have_fortran_kernels() bind(C, name="mpm3d_have_fortran_kernels") result(r)
      import :: c_int
      integer(c_int) :: r
    end function
    function c_set_threads(n) bind(C, name="mpm3d_set_threads") result(r)
      import :: c_int
      integer(c_int), value :: n
      integer(c_int) :: r
    end function
    function c_open(path, out) bind(C, name="mpm3d_open") result(r)
      import :: c_ptr, c_int, c_char
      character(kind=c_char), dimension(*), intent(in) :: path
      type(c_ptr), intent(out) :: out
      integer(c_int) :: r
    end function
    subroutine c_close(sim) bind(C, name="mpm3d_close")
      import :: c_ptr
      type(c_ptr), value :: sim
    end subroutine
    function c_set_kernel(sim, spec) bind(C, name="mpm3d_set_kernel") result(r)
      import :: c_ptr, c_int, c_char
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: spec
      integer(c_int) :: r
    end function
    function c_step(sim, nsteps) bind(C, name="mpm3d_step") result(r)
      import :: c_ptr, c_int
      type(c_ptr), value :: sim
      integer(c_int), value :: nsteps
      integer(c_int) :: r
    end function
    function c_time(sim) bind(C, name="mpm3d_time") result(r)
      import :: c_ptr, c_double
      type(c_ptr), value :: sim
      real(c_double) :: r
    end function
    function c_steps(sim) bind(C, name="mpm3d_steps") result(r)
      import :: c_ptr, c_long
      type(c_ptr), value :: sim
      integer(c_long) :: r
    end function
    function c_num_particles(sim) bind(C, name="mpm3d_num_particles") result(r)
      import :: c_ptr, c_int
      type(c_ptr), value :: sim
      integer(c_int) :: r
    end function
    function c_dt(sim) bind(C, name="mpm3d_dt") result(r)
      import :: c_ptr, c_double
      type(c_ptr), value :: sim
      real(c_double) :: r
    end function
    function c_end_time(sim) bind(C, name="mpm3d_end_time") result(r)
      import :: c_ptr, c_double
      type(c_ptr), value :: sim
      real(c_double) :: r
    end function
    function c_kinetic_energy(sim) bind(C, name="mpm3d_kinetic_energy") result(r)
      import :: c_ptr, c_double
      type(c_ptr), value :: sim
      real(c_double) :: r
    end function
    function c_internal_energy(sim) bind(C, name="mpm3d_internal_energy") result(r)
      import :: c_ptr, c_double
      type(c_ptr), value :: sim
      real(c_double) :: r
    end function
    function c_momentum(sim, dst) bind(C, name="mpm3d_momentum") result(r)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: sim
      real(c_double), dimension(3), intent(out) :: dst
      integer(c_int) :: r
    end function
    function c_array_size(sim, name) bind(C, name="mpm3d_array_size") result(r)
      import :: c_ptr, c_long, c_char
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: name
      integer(c_long) :: r
    end function
    function c_get_array(sim, name, dst, n) bind(C, name="mpm3d_get_array") result(r)
      import :: c_ptr, c_int, c_long, c_char, c_double
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: name
      real(c_double), dimension(*), intent(inout) :: dst
      integer(c_long), value :: n
      integer(c_int) :: r
    end function
    function c_set_array(sim, name, src, n) bind(C, name="mpm3d_set_array") result(r)
      import :: c_ptr, c_int, c_long, c_char, c_double
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: name
      real(c_double), dimension(*), intent(in) :: src
      integer(c_long), value :: n
      integer(c_int) :: r
    end function
    function c_write_state(sim, path) bind(C, name="mpm3d_write_state") result(r)
      import :: c_ptr, c_int, c_char
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: path
      integer(c_int) :: r
    end function
    function c_write_checkpoint(sim, path) bind(C, name="mpm3d_write_checkpoint") result(r)
      import :: c_ptr, c_int, c_char
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: path
      integer(c_int) :: r
    end function
    function c_restart(sim, path) bind(C, name="mpm3d_restart") result(r)
      import :: c_ptr, c_int, c_char
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: path
      integer(c_int) :: r
    end function
    function c_strlen(s) bind(C, name="strlen") result(n)
      import :: c_ptr, c_size_t
      type(c_ptr), value :: s
      integer(c_size_t) :: n
    end function
  end interface

contains

  ! A Fortran string, trailing blanks removed, as a null-terminated C string.
  pure function c_string(s) result(cs)
    character(len=*), intent(in) :: s
    character(kind=c_char, len=len_trim(s) + 1) :: cs
    cs = trim(s) // c_null_char
  end function

  ! A null-terminated C string as a Fortran string ('' for a null pointer).
  function f_string(p) result(s)
    type(c_ptr), intent(in) :: p
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: chars(:)
    integer :: i, n
    if (.not. c_associated(p)) then
      s = ''
      return
    end if
    n = int(c_strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate (character(len=n) :: s)
    do i = 1, n
      s(i:i) = chars(i)
    end do
  end function

  !> Library version, e.g. '0.1.0'.
  function mpm3d_version() result(v)
    character(len=:), allocatable :: v
    v = f_string(c_version())
  end function

  !> Message of the last failed call in this thread ('' after a successful call).
  function mpm3d_last_error() result(msg)
    character(len=:), allocatable :: msg
    msg = f_string(c_last_error())
  end function

  !> .true. when the library has the Fortran reference kernels.
  logical function mpm3d_have_fortran_kernels()
    mpm3d_have_fortran_kernels = c_have_fortran_kernels() /= 0
  end function

  !> OpenMP threads of later steps (process-wide).
  integer(c_int) function mpm3d_set_threads(n)
    integer, intent(in) :: n
    mpm3d_set_threads = c_set_threads(int(n, c_int))
  end function

  !> Reads a deck; sim is c_null_ptr on failure.
  integer(c_int) function mpm3d_open(deck, sim)
    character(len=*), intent(in) :: deck
    type(c_ptr), intent(out) :: sim
    sim = c_null_ptr
    mpm3d_open = c_open(c_string(deck), sim)
  end function

  !> Releases the simulation; sim becomes c_null_ptr.
  subroutine mpm3d_close(sim)
    type(c_ptr), intent(inout) :: sim
    call c_close(sim)
    sim = c_null_ptr
  end subroutine

  !> 'cxx', 'fortran' or 'stage=lang,...' (as --kernel / --kernels).
  integer(c_int) function mpm3d_set_kernel(sim, spec)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: spec
    mpm3d_set_kernel = c_set_kernel(sim, c_string(spec))
  end function

  !> Advances nsteps steps.
  integer(c_int) function mpm3d_step(sim, nsteps)
    type(c_ptr), intent(in) :: sim
    integer, intent(in) :: nsteps
    mpm3d_step = c_step(sim, int(nsteps, c_int))
  end function

  real(c_double) function mpm3d_time(sim)
    type(c_ptr), intent(in) :: sim
    mpm3d_time = c_time(sim)
  end function

  integer(c_long) function mpm3d_steps(sim)
    type(c_ptr), intent(in) :: sim
    mpm3d_steps = c_steps(sim)
  end function

  integer(c_int) function mpm3d_num_particles(sim)
    type(c_ptr), intent(in) :: sim
    mpm3d_num_particles = c_num_particles(sim)
  end function

  real(c_double) function mpm3d_dt(sim)
    type(c_ptr), intent(in) :: sim
    mpm3d_dt = c_dt(sim)
  end function

  real(c_double) function mpm3d_end_time(sim)
    type(c_ptr), intent(in) :: sim
    mpm3d_end_time = c_end_time(sim)
  end function

  real(c_double) function mpm3d_kinetic_energy(sim)
    type(c_ptr), intent(in) :: sim
    mpm3d_kinetic_energy = c_kinetic_energy(sim)
  end function

  real(c_double) function mpm3d_internal_energy(sim)
    type(c_ptr), intent(in) :: sim
    mpm3d_internal_energy = c_internal_energy(sim)
  end function

  !> Total momentum.
  integer(c_int) function mpm3d_momentum(sim, mom)
    type(c_ptr), intent(in) :: sim
    real(c_double), intent(out) :: mom(3)
    mpm3d_momentum = c_momentum(sim, mom)
  end function

  !> Number of values of a particle array (-1 for an unknown name).
  integer(c_long) function mpm3d_array_size(sim, name)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: name
    mpm3d_array_size = c_array_size(sim, c_string(name))
  end function

  integer(c_int) function get_array_1d(sim, name, dst) result(r)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: name
    real(c_double), contiguous, intent(inout) :: dst(:)
    r = c_get_array(sim, c_string(name), dst, int(size(dst), c_long))
  end function

  integer(c_int) function get_array_2d(sim, name, dst) result(r)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: name
    real(c_double), contiguous, intent(inout) :: dst(:, :)
    r = c_get_array(sim, c_string(name), dst, int(size(dst), c_long))
  end function

  integer(c_int) function set_array_1d(sim, name, src) result(r)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: name
    real(c_double), contiguous, intent(in) :: src(:)
    r = c_set_array(sim, c_string(name), src, int(size(src), c_long))
  end function

  integer(c_int) function set_array_2d(sim, name, src) result(r)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: name
    real(c_double), contiguous, intent(in) :: src(:, :)
    r = c_set_array(sim, c_string(name), src, int(size(src), c_long))
  end function

  !> Writes the HDF5 state file (as mpm3d --state).
  integer(c_int) function mpm3d_write_state(sim, path)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: path
    mpm3d_write_state = c_write_state(sim, c_string(path))
  end function

  !> Writes a checkpoint (HDF5, atomically): everything a later step needs.
  integer(c_int) function mpm3d_write_checkpoint(sim, path)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: path
    mpm3d_write_checkpoint = c_write_checkpoint(sim, c_string(path))
  end function

  !> Loads a checkpoint into a handle opened from the same deck.
  integer(c_int) function mpm3d_restart(sim, path)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: path
    mpm3d_restart = c_restart(sim, c_string(path))
  end function

end module mpm3d_api
