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

  public :: particles_resize

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

end module mpm3d_particle
