! ParticleData: particles as one array per field (structure of arrays), the layout shared
! with the C++ side: x(3,np), v(3,np), sig(6,np) in Voigt order xx yy zz yz xz xy,
! scalars (np). Material and body numbers are stored 0-based, as in C++.
module mpm3d_particle
  use, intrinsic :: iso_c_binding, only: c_int
  use mpm3d_material, only: dp
  implicit none
  private

  type, public :: body_t
    integer :: first = 0       ! first particle (0-based)
    integer :: count = 0       ! particles in the body
    integer :: component = 1   ! contact component (1-based, as in the deck)
    real(dp) :: spacing = 0.0_dp   ! particle spacing of bloc/sphe/cyli cards; 0 for poin
    real(dp) :: gravity(3) = 0.0_dp
  end type body_t

  type, public :: particles_t
    integer :: np = 0
    real(dp), allocatable :: x(:,:), v(:,:), sig(:,:)
    real(dp), allocatable :: mass(:), vol(:), epeff(:), ie(:)
    integer(c_int), allocatable :: mat(:), body(:)   ! 0-based
    real(dp), allocatable :: temp(:)    ! only with thermal Johnson-Cook
    real(dp), allocatable :: fext(:,:)  ! only with point/body loads
    real(dp), allocatable :: tlight(:)  ! only with hiex: lighting time
    real(dp), allocatable :: qv(:)      ! only with 'bulk': bulk viscosity pressure
    real(dp), allocatable :: psize(:)   ! only with gimp: particle half-size lp
  end type particles_t

  public :: particles_resize, particles_grow

contains

  subroutine particles_resize(p, n)
    type(particles_t), intent(inout) :: p
    integer, intent(in) :: n
    p%np = n
    if (allocated(p%x)) deallocate(p%x, p%v, p%sig, p%mass, p%vol, p%epeff, p%ie, p%mat, p%body)
    if (allocated(p%temp)) deallocate(p%temp)
    if (allocated(p%fext)) deallocate(p%fext)
    if (allocated(p%tlight)) deallocate(p%tlight)
    if (allocated(p%qv)) deallocate(p%qv)
    if (allocated(p%psize)) deallocate(p%psize)
    allocate(p%x(3, n), p%v(3, n), p%sig(6, n), p%mass(n), p%vol(n), p%epeff(n), p%ie(n), &
             p%mat(n), p%body(n))
    p%x = 0.0_dp
    p%v = 0.0_dp
    p%sig = 0.0_dp
    p%mass = 0.0_dp
    p%vol = 0.0_dp
    p%epeff = 0.0_dp
    p%ie = 0.0_dp
    p%mat = 0
    p%body = 0
  end subroutine particles_resize

  ! Grows the arrays to n particles, keeping the first np and zeroing the rest (fext too
  ! when allocated): the reader grows them as the particle cards generate particles.
  subroutine particles_grow(p, n)
    type(particles_t), intent(inout) :: p
    integer, intent(in) :: n
    integer :: k
    k = p%np
    call grow2(p%x, 3)
    call grow2(p%v, 3)
    call grow2(p%sig, 6)
    if (allocated(p%fext)) call grow2(p%fext, 3)
    call grow1(p%mass)
    call grow1(p%vol)
    call grow1(p%epeff)
    call grow1(p%ie)
    call growi(p%mat)
    call growi(p%body)
    p%np = n
  contains
    subroutine grow2(a, rows)
      real(dp), allocatable, intent(inout) :: a(:,:)
      integer, intent(in) :: rows
      real(dp), allocatable :: t(:,:)
      allocate(t(rows, n))
      t = 0.0_dp
      if (allocated(a)) t(:, 1:k) = a(:, 1:k)
      call move_alloc(t, a)
    end subroutine grow2
    subroutine grow1(a)
      real(dp), allocatable, intent(inout) :: a(:)
      real(dp), allocatable :: t(:)
      allocate(t(n))
      t = 0.0_dp
      if (allocated(a)) t(1:k) = a(1:k)
      call move_alloc(t, a)
    end subroutine grow1
    subroutine growi(a)
      integer(c_int), allocatable, intent(inout) :: a(:)
      integer(c_int), allocatable :: t(:)
      allocate(t(n))
      t = 0
      if (allocated(a)) t(1:k) = a(1:k)
      call move_alloc(t, a)
    end subroutine growi
  end subroutine particles_grow

end module mpm3d_particle
