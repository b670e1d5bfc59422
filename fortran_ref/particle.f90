! ParticleData: particles as one array per field (structure of arrays), the layout shared
! with the C++ side: x(3,np), v(3,np), sig(6,np) in Voigt order xx yy zz yz xz xy,
! scalars (np). Material and body numbers are stored 0-based, as in C++.
module mpm3d_particle
  use, intrinsic :: iso_c_binding, only: c_int, dp => c_double  ! dp: as mpm3d_material's
  use, intrinsic :: iso_fortran_env, only: int64
  implicit none
  private

  type, public :: body_t
    integer :: first = 0       ! deck number of the first particle (0-based): the deck
    integer :: count = 0       ! numbers first .. first + count - 1, not the storage order (id)
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
    real(dp), allocatable :: defgrad(:,:)  ! (9,np) only with neoh: F - I, row-major
    real(dp), allocatable :: x0(:,:)       ! (3,np) reference positions, TLmp only
    real(dp), allocatable :: pk1(:,:)      ! (9,np) V0 P, TLmp only
    integer(c_int), allocatable :: id(:)  ! deck number (0-based) of each stored particle
  end type particles_t

  public :: particles_resize, particles_grow, particles_order_by_blocks, particles_deck_order

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
    if (allocated(p%defgrad)) deallocate(p%defgrad)
    if (allocated(p%x0)) deallocate(p%x0)
    if (allocated(p%pk1)) deallocate(p%pk1)
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

  ! The solver's storage order (as order_by_blocks in cxx/core/particle.cpp, so both languages
  ! store the particles alike and their sums agree in bits): sorted by the block of
  ! block_cells**3 cells of the deck's lattice (origin lo, cell h, nc cells per axis) that
  ! holds each particle, blocks x fastest and z slowest, deck order within a block. The
  ! keys block * np + deck number are unique, so any sort gives the same order. Sets id and
  ! permutes every particle array. order_blocks false: deck order (id only).
  subroutine particles_order_by_blocks(p, lo, h, nc, block_cells, order_blocks)
    type(particles_t), intent(inout) :: p
    real(dp), intent(in) :: lo(3), h
    integer, intent(in) :: nc(3), block_cells
    logical, intent(in) :: order_blocks
    integer(int64), allocatable :: key(:)
    integer, allocatable :: from(:)
    integer(int64) :: nb(3), bl(3), ic
    real(dp) :: t
    integer :: i, a, n
    n = p%np
    if (allocated(p%id)) deallocate(p%id)
    allocate(p%id(n))
    do i = 1, n
      p%id(i) = i - 1
    end do
    if (.not. order_blocks .or. n == 0) return
    do a = 1, 3
      nb(a) = (max(nc(a), 1) - 1) / block_cells + 1
    end do
    allocate(key(n), from(n))
    do i = 1, n
      do a = 1, 3
        ! The cell as the bin stage finds it, clamped into the lattice (NaN: cell 0).
        t = (p%x(a, i) - lo(a)) / h
        if (t >= 0.0_dp .and. t < real(nc(a), dp)) then
          ic = int(t, int64)
        else if (t >= real(nc(a), dp)) then
          ic = nc(a) - 1
        else
          ic = 0
        end if
        bl(a) = ic / block_cells
      end do
      key(i) = (bl(1) + nb(1) * (bl(2) + nb(2) * bl(3))) * int(n, int64) + (i - 1)
    end do
    call sort_int64(key)
    do i = 1, n
      from(i) = int(mod(key(i), int(n, int64))) + 1
    end do
    ! Gathers through the vector subscript from (the right side is evaluated before the
    ! assignment, so each array is permuted whole).
    p%x = p%x(:, from)
    p%v = p%v(:, from)
    p%sig = p%sig(:, from)
    p%mass = p%mass(from)
    p%vol = p%vol(from)
    p%epeff = p%epeff(from)
    p%ie = p%ie(from)
    p%mat = p%mat(from)
    p%body = p%body(from)
    if (allocated(p%temp)) p%temp = p%temp(from)
    if (allocated(p%fext)) p%fext = p%fext(:, from)
    if (allocated(p%tlight)) p%tlight = p%tlight(from)
    if (allocated(p%qv)) p%qv = p%qv(from)
    if (allocated(p%psize)) p%psize = p%psize(from)
    if (allocated(p%defgrad)) p%defgrad = p%defgrad(:, from)
    if (allocated(p%x0)) p%x0 = p%x0(:, from)
    if (allocated(p%pk1)) p%pk1 = p%pk1(:, from)
    p%id = p%id(from)
  end subroutine particles_order_by_blocks

  ! Stored index (1-based) of each deck particle: the inverse of id, for the outputs.
  subroutine particles_deck_order(p, at)
    type(particles_t), intent(in) :: p
    integer, allocatable, intent(out) :: at(:)
    integer :: i
    allocate(at(p%np))
    do i = 1, p%np
      if (allocated(p%id)) then
        at(p%id(i) + 1) = i
      else
        at(i) = i
      end if
    end do
  end subroutine particles_deck_order

  ! Ascending sort of distinct keys (bottom-up merge sort).
  subroutine sort_int64(a)
    integer(int64), intent(inout) :: a(:)
    integer(int64), allocatable :: w(:)
    integer :: n, width, lo, mid, hi, i, j, k
    n = size(a)
    allocate(w(n))
    width = 1
    do while (width < n)
      lo = 1
      do while (lo <= n)
        mid = min(lo + width - 1, n)
        hi = min(lo + 2 * width - 1, n)
        i = lo
        j = mid + 1
        do k = lo, hi
          if (i <= mid .and. (j > hi .or. a(min(i, n)) <= a(min(j, n)))) then
            w(k) = a(i)
            i = i + 1
          else
            w(k) = a(j)
            j = j + 1
          end if
        end do
        lo = lo + 2 * width
      end do
      a = w
      width = 2 * width
    end do
  end subroutine sort_int64

end module mpm3d_particle
