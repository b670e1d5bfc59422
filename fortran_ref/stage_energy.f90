! stage_energy: the energy stage (bind(C) mpm3d_f_energy): kinetic and internal energy and
! momentum, in the fixed block order of the C++ reduction.
module mpm3d_stage_energy
  use, intrinsic :: iso_c_binding
  use mpm3d_material, only: dp
  use mpm3d_stage_common
  implicit none
  private

  public :: mpm3d_f_energy

contains

  ! Energy: kinetic and internal energy and momentum, summed per block of reduce_block
  ! particles, then the block partials in block order.
  subroutine mpm3d_f_energy(c) bind(C, name='mpm3d_f_energy')
    type(step_context), intent(inout) :: c
    real(dp), pointer :: mass(:), v(:,:), ie(:), partials(:,:)
    real(dp) :: part(REDUCE_FIELDS), m, s
    integer :: bs, nblock, blk, last, p, f
    bs = c%reduce_block
    nblock = (c%np + bs - 1) / bs
    call c_f_pointer(c%mass, mass, [c%np])
    call c_f_pointer(c%v, v, [3, c%np])
    call c_f_pointer(c%ie, ie, [c%np])
    call c_f_pointer(c%partials, partials, [REDUCE_FIELDS, max(nblock, 1)])
    do blk = 0, nblock - 1
      part = 0.0_dp
      last = min((blk + 1) * bs, c%np)
      do p = blk * bs + 1, last
        m = mass(p)
        part(1) = part(1) + ((0.5_dp * m) * (((v(1, p) * v(1, p)) + (v(2, p) * v(2, p))) + (v(3, p) * v(3, p))))
        part(2) = part(2) + ie(p)
        part(3) = part(3) + (m * v(1, p))
        part(4) = part(4) + (m * v(2, p))
        part(5) = part(5) + (m * v(3, p))
      end do
      do f = 1, REDUCE_FIELDS
        partials(f, blk + 1) = part(f)
      end do
    end do
    do f = 1, REDUCE_FIELDS
      s = 0.0_dp
      do blk = 1, nblock
        s = s + partials(f, blk)
      end do
      c%result(f) = s
    end do
  end subroutine mpm3d_f_energy

end module mpm3d_stage_energy
