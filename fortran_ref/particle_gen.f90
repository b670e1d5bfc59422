! Particle generators of the deck's 'part' cards (read by data_in.f90), as cxx/input/particle_gen.cpp:
! appending to the deck's arrays, the room checks against 'nbmp' and the lattice loops of
! bloc, sphe and cyli, with the arithmetic and the particle order of the C++.
module mpm3d_particle_gen
  use, intrinsic :: iso_fortran_env, only: int64
  use mpm3d_material, only: dp
  use mpm3d_particle
  use mpm3d_ffi, only: token_stream, itoa
  implicit none
  private

  ! The particles of one lattice card (bloc, sphe, cyli): body `body`, material `mat` (both
  ! 0-based), each of mass `mass` and volume `vol`, on the lattice of spacing `spacing`;
  ! `line`: the card's line, for errors.
  type, public :: lattice_card_t
    integer :: line = 0, body = 0, mat = 0
    real(dp) :: mass = 0.0_dp, vol = 0.0_dp, spacing = 0.0_dp
  end type lattice_card_t

  ! Every routine appends to the particle arrays p (grown as particles come, at most to nbmp)
  ! the particles of the card's body b, the last body read (b%count grows). Errors end the
  ! program with the deck's name and the card's line (ts%fail).
  public :: add_particle, check_points_room, generate_block, generate_sphere, generate_cylinder, generate_disc
  public :: is_finite   ! also the reader's test of a finite number

contains

  ! (ieee_arithmetic is out of reach with -nostdinc: see CMakeLists.txt.) False for Inf and NaN.
  logical function is_finite(x)
    real(dp), intent(in) :: x
    is_finite = abs(x) <= huge(x)
  end function is_finite

  ! Particles defined so far, all cards: the card's body is the last one.
  integer function n_defined(b)
    type(body_t), intent(in) :: b
    n_defined = b%first + b%count
  end function n_defined

  ! Appends one particle of body ibody and material mat (0-based) at (x, y, z).
  subroutine add_particle(ts, p, b, nbmp, line, ibody, mat, mass, vol, x, y, z)
    type(token_stream), intent(in) :: ts
    type(particles_t), intent(inout) :: p
    type(body_t), intent(inout) :: b
    integer, intent(in) :: nbmp, line, ibody, mat
    real(dp), intent(in) :: mass, vol, x, y, z
    integer :: q
    q = n_defined(b) + 1
    if (q > nbmp) call ts%fail(line, "more particles than 'nbmp' = " // itoa(int(nbmp, int64)))
    if (.not. is_finite(x) .or. .not. is_finite(y) .or. .not. is_finite(z)) &
      call ts%fail(line, 'particle position out of range')
    if (q > p%np) call particles_grow(p, min(nbmp, max(1024, 2 * p%np)))
    p%mass(q) = mass
    p%vol(q) = vol
    p%x(1, q) = x
    p%x(2, q) = y
    p%x(3, q) = z
    p%mat(q) = mat
    p%body(q) = ibody
    b%count = b%count + 1
  end subroutine add_particle

  ! Refuses a particle card that would generate at least count more particles than 'nbmp'
  ! leaves room for (checked before generating, so that no card loops for long).
  subroutine check_room(ts, b, nbmp, line, count, what)
    type(token_stream), intent(in) :: ts
    type(body_t), intent(in) :: b
    integer, intent(in) :: nbmp, line
    real(dp), intent(in) :: count
    character(len=*), intent(in) :: what
    if (real(n_defined(b), dp) + count > real(nbmp, dp)) &
      call ts%fail(line, what // ' of at least ' // itoa(int(count, int64)) // " particles exceeds 'nbmp' = " // &
                   itoa(int(nbmp, int64)))
  end subroutine check_room

  ! 'part poin': refuses n points when 'nbmp' leaves no room for them.
  subroutine check_points_room(ts, b, nbmp, line, n)
    type(token_stream), intent(in) :: ts
    type(body_t), intent(in) :: b
    integer, intent(in) :: nbmp, line
    integer(int64), intent(in) :: n
    if (n_defined(b) + n > nbmp) &
      call ts%fail(line, "'part poin' with " // itoa(n) // " points exceeds 'nbmp' = " // itoa(int(nbmp, int64)))
  end subroutine check_points_room

  ! 'part bloc': nb(1) x nb(2) x nb(3) particles at o + (i + 1/2) dp; x index outermost, z
  ! fastest (the book version). Counts in 1..100000 (checked by the reader).
  ! nr > 0 ('part blod', the current version): without the particles inside the hole of
  ! radius nr dp around the axis through (hx, hy) along z (as cxx/input/particle_gen.cpp).
  subroutine generate_block(ts, p, b, nbmp, c, o, nb, x_fastest, hx, hy, nr)
    type(token_stream), intent(in) :: ts
    type(particles_t), intent(inout) :: p
    type(body_t), intent(inout) :: b
    integer, intent(in) :: nbmp
    type(lattice_card_t), intent(in) :: c
    real(dp), intent(in) :: o(3)
    integer(int64), intent(in) :: nb(3)
    logical, intent(in) :: x_fastest   ! the current version's order (the book: z fastest)
    real(dp), intent(in) :: hx, hy
    integer(int64), intent(in) :: nr
    integer(int64) :: i, j, l, k
    real(dp) :: dpp, r2, x, y
    if (nr == 0 .and. n_defined(b) + nb(1) * nb(2) * nb(3) > nbmp) &
      call ts%fail(c%line, 'block of ' // itoa(nb(1) * nb(2) * nb(3)) // &
                   " particles exceeds 'nbmp' = " // itoa(int(nbmp, int64)))
    dpp = c%spacing
    r2 = (real(nr, dp) * dpp) * (real(nr, dp) * dpp)
    ! Particle k of the card: the book numbers z fastest (x outermost), the current version
    ! x fastest (z outermost).
    do k = 0, nb(1) * nb(2) * nb(3) - 1
      if (x_fastest) then
        i = mod(k, nb(1))
        j = mod(k / nb(1), nb(2))
        l = k / (nb(1) * nb(2))
      else
        l = mod(k, nb(3))
        j = mod(k / nb(3), nb(2))
        i = k / (nb(3) * nb(2))
      end if
      x = o(1) + ((real(i, dp) + 0.5_dp) * dpp)
      y = o(2) + ((real(j, dp) + 0.5_dp) * dpp)
      if (nr > 0) then
        if (((x - hx) * (x - hx)) + ((y - hy) * (y - hy)) < r2) cycle
      end if
      call add_particle(ts, p, b, nbmp, c%line, c%body, c%mat, c%mass, c%vol, x, y, &
                        o(3) + ((real(l, dp) + 0.5_dp) * dpp))
    end do
  end subroutine generate_block

  ! 'part sphe': the lattice points cc + (i + 1/2, j + 1/2, l + 1/2) dp, i, j, l in
  ! -nr .. nr-1, within nr spacings of the centre. nr in 1..10000 (checked by the reader).
  subroutine generate_sphere(ts, p, b, nbmp, c, cc, nr)
    type(token_stream), intent(in) :: ts
    type(particles_t), intent(inout) :: p
    type(body_t), intent(inout) :: b
    integer, intent(in) :: nbmp
    type(lattice_card_t), intent(in) :: c
    real(dp), intent(in) :: cc(3)
    integer(int64), intent(in) :: nr
    integer(int64) :: i, j, l
    real(dp) :: dpp, t, r2, aa, bb, ccc
    dpp = c%spacing
    ! At least the lattice points within nr - sqrt(3)/2 of the centre lie inside.
    t = real(nr, dp) - 0.8660254_dp
    if (t > 0.0_dp) call check_room(ts, b, nbmp, c%line, aint(4.18879_dp * t * t * t), 'sphere')
    r2 = real(nr * nr, dp)
    do i = -nr, nr - 1
      do j = -nr, nr - 1
        do l = -nr, nr - 1
          aa = real(i, dp) + 0.5_dp
          bb = real(j, dp) + 0.5_dp
          ccc = real(l, dp) + 0.5_dp
          if (((aa * aa) + (bb * bb)) + (ccc * ccc) > r2) cycle
          call add_particle(ts, p, b, nbmp, c%line, c%body, c%mat, c%mass, c%vol, cc(1) + (aa * dpp), &
                            cc(2) + (bb * dpp), cc(3) + (ccc * dpp))
        end do
      end do
    end do
  end subroutine generate_sphere

  ! 'part cyli' (extension): a cylinder along z, axis through (cx, cy), from z0 to
  ! z0 + length, of the given radius, on the lattice; radius and length positive (checked by
  ! the reader).
  subroutine generate_cylinder(ts, p, b, nbmp, c, cx, cy, z0, radius, length)
    type(token_stream), intent(in) :: ts
    type(particles_t), intent(inout) :: p
    type(body_t), intent(inout) :: b
    integer, intent(in) :: nbmp
    type(lattice_card_t), intent(in) :: c
    real(dp), intent(in) :: cx, cy, z0, radius, length
    integer(int64) :: i, j, l, nr, nz
    real(dp) :: dpp, t, x, r2, aa, bb
    dpp = c%spacing
    t = radius / dpp
    if (.not. (t <= 100000.0_dp)) call ts%fail(c%line, 'cylinder too large for its spacing')
    x = aint(t)                       ! ceil, exactly
    if (x < t) x = x + 1.0_dp
    if (x > 1.0e7_dp) call ts%fail(c%line, 'cylinder too large for its spacing')
    nr = int(x, int64)
    t = length / dpp + 0.5_dp
    x = aint(t)                       ! floor, exactly
    if (x > t) x = x - 1.0_dp
    if (x > 1.0e7_dp) call ts%fail(c%line, 'cylinder too large for its spacing')
    if (.not. (x <= 1000000.0_dp)) call ts%fail(c%line, 'cylinder too large for its spacing')
    if (.not. (x >= 1.0_dp)) call ts%fail(c%line, 'cylinder shorter than half a spacing')
    nz = int(x, int64)
    if (nr > 100000 .or. nz > 1000000) call ts%fail(c%line, 'cylinder too large for its spacing')
    ! At least the columns within R/dp - sqrt(2)/2 of the axis lie inside.
    t = radius / dpp - 0.7071068_dp
    if (t > 0.0_dp) call check_room(ts, b, nbmp, c%line, aint(3.14159_dp * t * t) * real(nz, dp), 'cylinder')
    r2 = ((radius / dpp) * (radius / dpp)) * (1.0_dp + 1.0e-12_dp)
    do i = -nr, nr - 1
      do j = -nr, nr - 1
        aa = real(i, dp) + 0.5_dp
        bb = real(j, dp) + 0.5_dp
        if ((aa * aa) + (bb * bb) > r2) cycle
        do l = 0, nz - 1
          call add_particle(ts, p, b, nbmp, c%line, c%body, c%mat, c%mass, c%vol, cx + (aa * dpp), cy + (bb * dpp), &
                            z0 + ((real(l, dp) + 0.5_dp) * dpp))
        end do
      end do
    end do
  end subroutine generate_cylinder

  ! 'part cicl' (the current version): a disc one particle thick in the plane z0 + dp/2, the
  ! points (x0 + (i + 1/2) dp, y0 + (j + 1/2) dp), i, j in -nr .. nr-1, closer than nr dp.
  subroutine generate_disc(ts, p, b, nbmp, c, o, nr)
    type(token_stream), intent(in) :: ts
    type(particles_t), intent(inout) :: p
    type(body_t), intent(inout) :: b
    integer, intent(in) :: nbmp
    type(lattice_card_t), intent(in) :: c
    real(dp), intent(in) :: o(3)
    integer(int64), intent(in) :: nr
    integer(int64) :: i, j
    real(dp) :: dpp, r2, x, y
    dpp = c%spacing
    r2 = (real(nr, dp) * dpp) * (real(nr, dp) * dpp)
    do i = -nr, nr - 1
      do j = -nr, nr - 1
        x = o(1) + ((real(i, dp) + 0.5_dp) * dpp)
        y = o(2) + ((real(j, dp) + 0.5_dp) * dpp)
        if (.not. (((x - o(1)) * (x - o(1))) + ((y - o(2)) * (y - o(2))) < r2)) cycle
        call add_particle(ts, p, b, nbmp, c%line, c%body, c%mat, c%mass, c%vol, x, y, o(3) + 0.5_dp * dpp)
      end do
    end do
  end subroutine generate_disc

end module mpm3d_particle_gen
