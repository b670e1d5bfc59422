! GridData: the background grid, its patch decomposition and the shape functions.
! Node and cell numbers are x fastest, then y, then z. The patch decomposition
! (cubes of patch_cells^3 cells) depends on the grid only, never on threads.
module mpm3d_grid
  use, intrinsic :: iso_c_binding, only: c_int, dp => c_double  ! dp: as mpm3d_material's
  implicit none
  private

  ! Fields of one node in a patch buffer: mass, momentum (3), force (3).
  integer, parameter, public :: NODE_FIELDS = 7

  ! The grid is a window of the deck's box: cells off + 0 .. off + nc - 1 of the deck's lattice
  ! (as cxx/core/grid.hpp); without the adaptive grid the window is the whole box.
  type, public :: grid_t
    real(dp) :: origin(3) = 0.0_dp     ! lower corner of the deck's box: the lattice origin
    real(dp) :: h = 0.0_dp             ! cubic cell size
    integer :: deck_nc(3) = 0          ! cells per axis of the deck's box
    integer :: off(3) = 0              ! first cell (0-based) of the window on the deck's lattice
    integer :: nc(3) = 0               ! cells per axis of the window
    integer :: nn(3) = 0               ! nodes per axis (nc + 1)
    integer :: fix(6) = 0              ! faces x0 xn y0 yn z0 zn: 0 free, 1 fixed, 2 symmetry
    real(dp) :: mass_cutoff = 0.0_dp   ! nodes lighter than this form no velocity
    real(dp), allocatable :: mass(:), mom(:,:), force(:,:)   ! (nnode) (3,nnode) (3,nnode)
    integer :: patch_cells = 4
    integer :: npd(3) = 0              ! patches per axis
    integer :: npatch = 0
    integer :: patch_halo = 0          ! node layers beyond a patch's cells: 0, 1 (GIMP)
    integer :: patch_nodes = 0         ! (patch_cells + 1 + 2 patch_halo)^3
    integer, allocatable :: patch_start(:)   ! (npatch + 1), 0-based offsets
    integer, allocatable :: patch_part(:)    ! (np), 0-based particle indices
    integer, allocatable :: patch_slot(:)    ! (npatch), 0-based slot or -1
    integer :: nslot = 0
    real(dp), allocatable :: patch_buf(:,:,:) ! (NODE_FIELDS, patch_nodes, slots)
  end type grid_t

  public :: grid_setup, grid_define, grid_set_window, grid_window_is_box, grid_nnode, shape_linear
  public :: grid_adaptive_window, grid_count_escaped, gimp_1d, shape_gimp, gimp_offset
  public :: bspline_1d, bspline_offset, shape_bspline, stencil_27

contains

  integer function grid_nnode(g)
    type(grid_t), intent(in) :: g
    grid_nnode = g%nn(1) * g%nn(2) * g%nn(3)
  end function grid_nnode

  ! grid_define and grid_set_window over the whole box (Grid::setup); halo: node layers a
  ! patch buffer holds beyond its cells (1 with GIMP).
  subroutine grid_setup(g, lo, hi, cell, patch_cells, halo, err)
    type(grid_t), intent(inout) :: g
    real(dp), intent(in) :: lo(3), hi(3), cell
    integer, intent(in) :: patch_cells, halo
    character(len=:), allocatable, intent(out) :: err
    integer :: zero(3)
    call grid_define(g, lo, hi, cell, patch_cells, halo, err)
    if (len(err) > 0) return
    zero = 0
    call grid_set_window(g, zero, g%deck_nc)
  end subroutine grid_setup

  ! The deck's box and lattice, no allocation (Grid::define).
  subroutine grid_define(g, lo, hi, cell, patch_cells, halo, err)
    type(grid_t), intent(inout) :: g
    real(dp), intent(in) :: lo(3), hi(3), cell
    integer, intent(in) :: patch_cells, halo
    character(len=:), allocatable, intent(out) :: err
    real(dp) :: n, t
    integer :: a, qq
    err = ''
    g%h = cell
    g%patch_cells = patch_cells
    g%patch_halo = halo
    do a = 1, 3
      g%origin(a) = lo(a)
      t = (hi(a) - lo(a)) / cell + 0.5_dp
      n = aint(t)
      if (n > t) n = n - 1.0_dp      ! floor, exact
      if (.not. (n >= 1.0_dp) .or. n > 1.0e6_dp) then
        err = 'grid: bad cell count'
        return
      end if
      g%deck_nc(a) = int(n)
    end do
    qq = patch_cells + 1 + 2 * halo
    g%patch_nodes = qq * qq * qq
  end subroutine grid_define

  ! Makes cells off .. off + nc - 1 the window: counts, patches, node arrays allocated
  ! afresh at the window's size, zero (Grid::set_window).
  subroutine grid_set_window(g, off, nc)
    type(grid_t), intent(inout) :: g
    integer, intent(in) :: off(3), nc(3)
    integer :: a, nnode
    do a = 1, 3
      g%off(a) = off(a)
      g%nc(a) = nc(a)
      g%nn(a) = g%nc(a) + 1
      g%npd(a) = (g%nc(a) + g%patch_cells - 1) / g%patch_cells
    end do
    g%npatch = g%npd(1) * g%npd(2) * g%npd(3)
    nnode = grid_nnode(g)
    if (allocated(g%mass)) deallocate(g%mass, g%mom, g%force)
    allocate(g%mass(nnode), g%mom(3, nnode), g%force(3, nnode))
    g%mass = 0.0_dp
    g%mom = 0.0_dp
    g%force = 0.0_dp
    if (allocated(g%patch_start)) deallocate(g%patch_start, g%patch_slot)
    allocate(g%patch_start(g%npatch + 1), g%patch_slot(g%npatch))
    g%patch_start = 0
    g%patch_slot = -1
    g%nslot = 0
  end subroutine grid_set_window

  logical function grid_window_is_box(g)
    type(grid_t), intent(in) :: g
    grid_window_is_box = all(g%off == 0) .and. all(g%nc == g%deck_nc)
  end function grid_window_is_box

  ! The adaptive background grid's window for particles x(3,np), velocities v(3,np): the
  ! operations of adaptive_window in cxx/core/grid.cpp (extent of the particles inside the box,
  ! margin m = 1 + ceil(2 every |v|max dt / h) cells, lower end rounded down to a whole
  ! patch, clipped to the box, faces with a boundary condition kept at the box).
  subroutine grid_adaptive_window(g, x, v, np, every, dt, off, nc)
    type(grid_t), intent(in) :: g
    integer, intent(in) :: np, every
    real(dp), intent(in) :: x(3, np), v(3, np), dt
    integer, intent(out) :: off(3), nc(3)
    integer :: cmin(3), cmax(3), idx(3), p, a, m, lo, hi
    real(dp) :: vmax2, s, r
    logical :: any_in
    cmin = g%deck_nc
    cmax = -1
    vmax2 = 0.0_dp
    any_in = .false.
    do p = 1, np
      if (.not. deck_cell(g, x(:, p), idx)) cycle
      any_in = .true.
      do a = 1, 3
        if (idx(a) < cmin(a)) cmin(a) = idx(a)
        if (idx(a) > cmax(a)) cmax(a) = idx(a)
      end do
      s = ((v(1, p) * v(1, p)) + (v(2, p) * v(2, p))) + (v(3, p) * v(3, p))
      if (s > vmax2) vmax2 = s
    end do
    r = (2.0_dp * ((real(every, dp) * sqrt(vmax2)) * dt)) / g%h
    if (r < 1.0e6_dp) then
      m = 1 + ceiling(r)
    else
      m = 1 + 1000000
    end if
    do a = 1, 3
      lo = 0
      hi = g%deck_nc(a)
      if (any_in) then
        lo = cmin(a) - m
        if (lo < 0) lo = 0
        lo = (lo / g%patch_cells) * g%patch_cells
        if (g%fix(2 * a - 1) /= 0) lo = 0
        hi = cmax(a) + 1 + m
        if (hi > g%deck_nc(a)) hi = g%deck_nc(a)
        if (g%fix(2 * a) /= 0) hi = g%deck_nc(a)
      end if
      off(a) = lo
      nc(a) = hi - lo
    end do
  end subroutine grid_adaptive_window

  ! True when point xp lies in the deck's box; idx: its cell there (0-based per axis), the
  ! floor of (x - origin) / h as cxx/core/grid.cpp takes it.
  logical function deck_cell(g, xp, idx) result(inside)
    type(grid_t), intent(in) :: g
    real(dp), intent(in) :: xp(3)
    integer, intent(out) :: idx(3)
    integer :: a
    real(dp) :: t, fl
    inside = .true.
    idx = 0
    do a = 1, 3
      t = (xp(a) - g%origin(a)) / g%h
      fl = aint(t)
      if (fl > t) fl = fl - 1.0_dp
      if (.not. (fl >= 0.0_dp .and. fl < real(g%deck_nc(a), dp))) then
        inside = .false.
        return
      end if
      idx(a) = int(fl)
    end do
  end function deck_cell

  ! Particles outside the window (cell < 0) but inside the deck's box (count_escaped).
  integer function grid_count_escaped(g, x, cell, np) result(n)
    type(grid_t), intent(in) :: g
    integer, intent(in) :: np
    real(dp), intent(in) :: x(3, np)
    integer(c_int), intent(in) :: cell(np)
    integer :: p, idx(3)
    n = 0
    do p = 1, np
      if (cell(p) >= 0) cycle
      if (deck_cell(g, x(:, p), idx)) n = n + 1
    end do
  end function grid_count_escaped

  ! Trilinear shape functions of the 8 nodes of a cell at local coordinates lx in [0,1)^3.
  ! Local node k = a + 2 b + 4 c (0-based) has offset (a, b, c) and is stored at k + 1.
  ! Operation order as cxx/core/grid.hpp: N = (wx * wy) * wz, dN/dx = (gx * wy) * wz, ...
  pure subroutine shape_linear(lx, inv_h, sn, sg)
    real(dp), intent(in) :: lx(3), inv_h
    real(dp), intent(out) :: sn(8), sg(3, 8)
    real(dp) :: wx(0:1), wy(0:1), wz(0:1), gr(0:1)
    integer :: k, a, b, c
    wx(0) = 1.0_dp - lx(1)
    wx(1) = lx(1)
    wy(0) = 1.0_dp - lx(2)
    wy(1) = lx(2)
    wz(0) = 1.0_dp - lx(3)
    wz(1) = lx(3)
    gr(0) = -inv_h
    gr(1) = inv_h
    do k = 0, 7
      a = iand(k, 1)
      b = iand(ishft(k, -1), 1)
      c = iand(ishft(k, -2), 1)
      sn(k + 1) = (wx(a) * wy(b)) * wz(c)
      sg(1, k + 1) = (gr(a) * wy(b)) * wz(c)
      sg(2, k + 1) = (wx(a) * gr(b)) * wz(c)
      sg(3, k + 1) = (wx(a) * wy(b)) * gr(c)
    end do
  end subroutine shape_linear

  ! uGIMP weights of the three nodes at offsets o, o+1, o+2 (o = -1 or 0) from the base node
  ! of the particle's cell along one axis (cxx/core/grid.hpp gimp_1d, same operations): lx in
  ! [0,1) the local coordinate, l = lp/h the particle half-size in cells, r = lx - (o + k).
  pure subroutine gimp_1d(lx, o, l, inv_h, w, g)
    real(dp), intent(in) :: lx, l, inv_h
    integer, intent(in) :: o
    real(dp), intent(out) :: w(3), g(3)
    real(dp) :: r, a, s, d, t
    integer :: k
    do k = 0, 2
      r = lx - real(o + k, dp)
      a = abs(r)
      s = 0.0_dp
      d = 0.0_dp
      if (a < l) then
        s = 1.0_dp - ((r * r) + (l * l)) / (2.0_dp * l)
        d = -(r / l)
      else if (a <= 1.0_dp - l) then
        s = 1.0_dp - a
        if (r > 0.0_dp) then
          d = -1.0_dp
        else
          d = 1.0_dp
        end if
      else if (a < 1.0_dp + l) then
        t = (1.0_dp + l) - a
        s = (t * t) / (4.0_dp * l)
        if (r > 0.0_dp) then
          d = -(t / (2.0_dp * l))
        else
          d = t / (2.0_dp * l)
        end if
      end if
      w(k + 1) = s
      g(k + 1) = d * inv_h
    end do
  end subroutine gimp_1d

  ! The current version's quadratic B-spline weights of the three nodes at offsets o, o+1,
  ! o+2 from the base node of the particle's cell (cxx/core/grid.hpp bspline_1d, same
  ! operations): (1-s)^2/2, 1/2 + s - s^2, s^2/2 on the nodes base-1, base, base+1, s in
  ! [0,1) the local coordinate; o = 0 in the grid's first cell drops the node base-1.
  pure subroutine bspline_1d(s, o, inv_h, w, g)
    real(dp), intent(in) :: s, inv_h
    integer, intent(in) :: o
    real(dp), intent(out) :: w(3), g(3)
    real(dp) :: n, d, t
    integer :: k, m
    do k = 0, 2
      m = o + k
      n = 0.0_dp
      d = 0.0_dp
      if (m == -1) then
        t = 1.0_dp - s
        n = 0.5_dp * (t * t)
        d = -t
      else if (m == 0) then
        n = (0.5_dp + s) - s * s
        d = 1.0_dp - 2.0_dp * s
      else if (m == 1) then
        n = 0.5_dp * (s * s)
        d = s
      end if
      w(k + 1) = n
      g(k + 1) = d * inv_h
    end do
  end subroutine bspline_1d

  ! Stencil offset of one axis with B-splines (cxx bspline_offset): base-1 .. base+1, or
  ! base .. base+2 in the grid's first cell (cell index i, 0-based).
  pure integer function bspline_offset(i) result(o)
    integer, intent(in) :: i
    if (i > 0) then
      o = -1
    else
      o = 0
    end if
  end function bspline_offset

  ! uGIMP shape functions of the 27 stencil nodes (shape_27).
  pure subroutine shape_gimp(lx, o, l, inv_h, sn, sg)
    real(dp), intent(in) :: lx(3), l, inv_h
    integer, intent(in) :: o(3)
    real(dp), intent(out) :: sn(27), sg(3, 27)
    real(dp) :: wx(3), wy(3), wz(3), gx(3), gy(3), gz(3)
    call gimp_1d(lx(1), o(1), l, inv_h, wx, gx)
    call gimp_1d(lx(2), o(2), l, inv_h, wy, gy)
    call gimp_1d(lx(3), o(3), l, inv_h, wz, gz)
    call shape_27(wx, wy, wz, gx, gy, gz, sn, sg)
  end subroutine shape_gimp

  ! The current version's quadratic B-spline shape functions of the 27 nodes (shape_27).
  pure subroutine shape_bspline(lx, o, inv_h, sn, sg)
    real(dp), intent(in) :: lx(3), inv_h
    integer, intent(in) :: o(3)
    real(dp), intent(out) :: sn(27), sg(3, 27)
    real(dp) :: wx(3), wy(3), wz(3), gx(3), gy(3), gz(3)
    call bspline_1d(lx(1), o(1), inv_h, wx, gx)
    call bspline_1d(lx(2), o(2), inv_h, wy, gy)
    call bspline_1d(lx(3), o(3), inv_h, wz, gz)
    call shape_27(wx, wy, wz, gx, gy, gz, sn, sg)
  end subroutine shape_bspline

  ! Tensor products of the 27 stencil nodes from the 1-D weights w and derivatives g: local
  ! node k = a + 3 b + 9 c (0-based, stored at k + 1) at offset (o(1) + a, o(2) + b,
  ! o(3) + c) from the cell's base node.
  pure subroutine shape_27(wx, wy, wz, gx, gy, gz, sn, sg)
    real(dp), intent(in) :: wx(3), wy(3), wz(3), gx(3), gy(3), gz(3)
    real(dp), intent(out) :: sn(27), sg(3, 27)
    integer :: a, b, c, k
    do c = 1, 3
      do b = 1, 3
        do a = 1, 3
          k = a + 3 * (b - 1) + 9 * (c - 1)
          sn(k) = (wx(a) * wy(b)) * wz(c)
          sg(1, k) = (gx(a) * wy(b)) * wz(c)
          sg(2, k) = (wx(a) * gy(b)) * wz(c)
          sg(3, k) = (wx(a) * wy(b)) * gz(c)
        end do
      end do
    end do
  end subroutine shape_27

  ! Stencil offset of one axis (cxx/core/grid.hpp gimp_offset): -1 in the lower half of the
  ! cell, 0 in the upper half, shifted inwards at the ends of the grid (cell i of nc).
  pure integer function gimp_offset(lx, i, nc) result(o)
    real(dp), intent(in) :: lx
    integer, intent(in) :: i, nc
    if (lx < 0.5_dp) then
      o = -1
    else
      o = 0
    end if
    if (i + o < 0) o = 0
    if (i + o + 2 > nc) o = -1
  end function gimp_offset

  ! The 27-node shape functions in one place (as stencil_27, cxx/core/grid.hpp): shape 1
  ! uGIMP (particle half-size lp_cells, in cells), 2 quadratic B-spline; the offsets o of the
  ! stencil of a particle in cell ci at local coordinates lx, its weights and gradients.
  pure subroutine stencil_27(shape, ci, lx, nc, lp_cells, inv_h, o, sn, sg)
    integer, intent(in) :: shape, ci(3), nc(3)
    real(dp), intent(in) :: lx(3), lp_cells, inv_h
    integer, intent(out) :: o(3)
    real(dp), intent(out) :: sn(27), sg(3, 27)
    integer :: a
    if (shape == 2) then
      do a = 1, 3
        o(a) = bspline_offset(ci(a))
      end do
      call shape_bspline(lx, o, inv_h, sn, sg)
      return
    end if
    do a = 1, 3
      o(a) = gimp_offset(lx(a), ci(a), nc(a))
    end do
    call shape_gimp(lx, o, lp_cells, inv_h, sn, sg)
  end subroutine stencil_27

end module mpm3d_grid
