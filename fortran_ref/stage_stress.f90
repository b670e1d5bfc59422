! stage_stress: the stress stage (bind(C) mpm3d_f_stress): strain rate and spin from the
! nodal velocities, the new volume, and the constitutive update (mpm3d_constitution).
module mpm3d_stage_stress
  use, intrinsic :: iso_c_binding
  use mpm3d_material
  use mpm3d_grid, only: shape_linear
  use mpm3d_constitution, only: stress_update, burn_fraction, neo_hookean, neo_hookean_tl, det_identity_plus
  use mpm3d_stage_common
  use mpm3d_stage_sg, only: sg_cell_gradients, sg_velocity_gradient
  implicit none
  private

  public :: mpm3d_f_stress

contains

  ! Stress: strain and spin increments from the grid velocity, volume, stress update.
  subroutine mpm3d_f_stress(c) bind(C, name='mpm3d_f_stress')
    type(step_context), intent(inout) :: c
    real(dp), pointer :: lx(:,:), sig(:,:), mass(:), vol(:), epeff(:), ie(:), temp(:)
    real(dp), pointer :: tlight(:), qv(:), defgrad(:,:), pk1(:,:)
    real(dp), pointer :: gmass(:), gmom(:,:), psize(:)
    integer(c_int), pointer :: cell(:), mat(:), body(:), bcomp(:)
    type(material_params), pointer :: mats(:)
    real(dp) :: sn(27), sg(3, 27), lg(0:8), de(6), dw(3), dt, m, va, vol_old, vol_new, tdummy
    real(dp) :: burn, qdummy, dl(0:8)
    integer :: p, cl, base, k, n, a, b, nk
    integer :: ci(3), o(3)
    logical :: has_temp, has_tl, has_q, wide, filter, neoh
    dt = c%clock%dt
    wide = c%method%family == TRANSFER_STENCIL27
    if (c%method%shape == 1) call c_f_pointer(c%part%psize, psize, [c%part%np])
    call view_components(c, filter, body, bcomp)
    call c_f_pointer(c%part%lx, lx, [3, c%part%np])
    call c_f_pointer(c%part%sig, sig, [6, c%part%np])
    call c_f_pointer(c%part%mass, mass, [c%part%np])
    call c_f_pointer(c%part%vol, vol, [c%part%np])
    call c_f_pointer(c%part%epeff, epeff, [c%part%np])
    call c_f_pointer(c%part%ie, ie, [c%part%np])
    call c_f_pointer(c%part%cell, cell, [c%part%np])
    call c_f_pointer(c%part%mat, mat, [c%part%np])
    call c_f_pointer(c%grid%gmass, gmass, [c%grid%nnode])
    call c_f_pointer(c%grid%gmom, gmom, [3, c%grid%nnode])
    call c_f_pointer(c%part%mats, mats, [c%part%nmat])
    has_temp = c_associated(c%part%temp)
    if (has_temp) then
      call c_f_pointer(c%part%temp, temp, [c%part%np])
    else
      nullify(temp)
    end if
    has_tl = c_associated(c%part%tlight)
    if (has_tl) call c_f_pointer(c%part%tlight, tlight, [c%part%np])
    has_q = c_associated(c%part%qv)
    if (has_q) call c_f_pointer(c%part%qv, qv, [c%part%np])
    if (c_associated(c%part%defgrad)) call c_f_pointer(c%part%defgrad, defgrad, [9, c%part%np])
    if (c%method%tl /= 0) call c_f_pointer(c%part%pk1, pk1, [9, c%part%np])
    tdummy = 0.0_dp
    qdummy = 0.0_dp
    if (c%method%family == TRANSFER_SMOOTHED_GRADIENT) call sg_cell_gradients(c)
    do p = 1, c%part%np
      cl = cell(p)
      if (cl < 0) cycle
      if (filter) then
        if (other_component(c, p, body, bcomp)) cycle
      end if
      if (c%method%family == TRANSFER_SMOOTHED_GRADIENT) then
        call sg_velocity_gradient(c, cl, lx(:, p), lg)
      else
        call particle_shape(c, wide, p, cl, lx, psize, ci, o, sn, sg, nk)
        base = stencil_first_node(c, wide, cl, ci, o)
        lg = 0.0_dp             ! lg(3a+b) = d v_a / d x_b (0-based a, b)
        do k = 0, nk - 1
          n = stencil_node(c, wide, base, k)
          m = gmass(n)
          if (.not. (m > c%grid%mass_cutoff)) cycle
          do a = 0, 2
            va = gmom(a + 1, n) / m
            do b = 0, 2
              lg(3 * a + b) = lg(3 * a + b) + (va * sg(b + 1, k + 1))
            end do
          end do
        end do
      end if
      de(1) = lg(0) * dt
      de(2) = lg(4) * dt
      de(3) = lg(8) * dt
      de(4) = (0.5_dp * (lg(5) + lg(7))) * dt
      de(5) = (0.5_dp * (lg(2) + lg(6))) * dt
      de(6) = (0.5_dp * (lg(1) + lg(3))) * dt
      dw(1) = (0.5_dp * (lg(5) - lg(7))) * dt
      dw(2) = (0.5_dp * (lg(2) - lg(6))) * dt
      dw(3) = (0.5_dp * (lg(1) - lg(3))) * dt
      vol_old = vol(p)
      if (c%method%tl /= 0) then   ! TLmp (neoh only): lg is the gradient in the reference configuration
        do k = 0, 8
          dl(k) = lg(k) * dt
        end do
        call neo_hookean_tl(mats(mat(p) + 1), dl, defgrad(:, p), mass(p), pk1(:, p), sig(:, p), vol(p), ie(p), &
                            c%rules%tl_shape /= 0)
        cycle
      end if
      neoh = mats(mat(p) + 1)%type == MAT_NEOH
      if (c%method%uvf /= 0 .or. neoh) then
        ! UVFp and neoh: the volume from the deformation, det(I + L dt)
        do k = 0, 8
          dl(k) = lg(k) * dt
        end do
        vol_new = vol_old * det_identity_plus(dl)
      else
        vol_new = vol_old * (1.0_dp + ((de(1) + de(2)) + de(3)))
      end if
      if (neoh) then
        if (has_q) then
          call neo_hookean(mats(mat(p) + 1), dl, de, defgrad(:, p), vol_old, vol_new, sig(:, p), ie(p), &
                           .true., qv(p), mass(p), dt, c%method%bulk_q1, c%method%bulk_q2, c%grid%h)
        else
          call neo_hookean(mats(mat(p) + 1), dl, de, defgrad(:, p), vol_old, vol_new, sig(:, p), ie(p), &
                           .false., qdummy, mass(p), dt, c%method%bulk_q1, c%method%bulk_q2, c%grid%h)
        end if
        vol(p) = vol_new
        cycle
      end if
      burn = 1.0_dp
      if (has_tl) burn = burn_fraction(mats(mat(p) + 1), tlight(p), c%clock%time, c%rules%burn /= 0)
      if (has_temp .and. has_q) then
        call stress_update(mats(mat(p) + 1), de, dw, dt, mass(p), vol_old, vol_new, sig(:, p), &
                           epeff(p), ie(p), .true., temp(p), .true., qv(p), burn, c%method%bulk_q1, c%method%bulk_q2, &
                           c%grid%h, c%rules)
      else if (has_temp) then
        call stress_update(mats(mat(p) + 1), de, dw, dt, mass(p), vol_old, vol_new, sig(:, p), &
                           epeff(p), ie(p), .true., temp(p), .false., qdummy, burn, c%method%bulk_q1, c%method%bulk_q2, &
                           c%grid%h, c%rules)
      else if (has_q) then
        call stress_update(mats(mat(p) + 1), de, dw, dt, mass(p), vol_old, vol_new, sig(:, p), &
                           epeff(p), ie(p), .false., tdummy, .true., qv(p), burn, c%method%bulk_q1, c%method%bulk_q2, &
                           c%grid%h, c%rules)
      else
        call stress_update(mats(mat(p) + 1), de, dw, dt, mass(p), vol_old, vol_new, sig(:, p), &
                           epeff(p), ie(p), .false., tdummy, .false., qdummy, burn, c%method%bulk_q1, c%method%bulk_q2, &
                           c%grid%h, c%rules)
      end if
      vol(p) = vol_new
    end do
  end subroutine mpm3d_f_stress

  ! The node and buffer index helpers and the views, a copy in this module so that its loops
  ! inline them.
  include 'stage_index.inc'
  include 'stage_views.inc'

end module mpm3d_stage_stress
