! DataOut (part): the HDF5 state file, with the datasets, shapes, types and attributes of
! write_state_h5 in cxx/io/data_out.cpp. Fortran arrays x(3,np) are written with their
! dimensions reversed, so the file holds (np,3) in C order, exactly as the C++ writes it.
module mpm3d_data_out
  use, intrinsic :: iso_c_binding
  use, intrinsic :: iso_fortran_env, only: int64, error_unit
  use hdf5
  use mpm3d_material, only: dp
  use mpm3d_data_in, only: model_t
  use mpm3d_particle, only: particles_deck_order
  implicit none
  private

  public :: write_state_h5

  ! Dataset creation properties without modification times (as H5Untimed in
  ! cxx/io/h5_quiet.hpp): the same state gives the same bytes.
  integer(hid_t) :: untimed_dataset

  interface
    integer(c_int) function c_rename(from, to) bind(C, name='rename')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: from(*), to(*)
    end function c_rename
    integer(c_int) function c_remove(path) bind(C, name='remove')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
    end function c_remove
  end interface

contains

  subroutine check(st, what)
    integer, intent(in) :: st
    character(len=*), intent(in) :: what
    if (st < 0) then
      write (error_unit, '(a)') 'mpm3d_ref: HDF5: cannot write ' // what
      stop 1, quiet=.true.
    end if
  end subroutine check

  ! A dataset of type dtype over space (closed here) in g, holding data.
  subroutine write_dataset(g, name, dtype, space, data)
    integer(hid_t), intent(in) :: g, dtype, space
    character(len=*), intent(in) :: name
    type(c_ptr), intent(in) :: data
    integer(hid_t) :: ds
    integer :: st
    call h5dcreate_f(g, name, dtype, space, ds, st, dcpl_id=untimed_dataset)
    call check(st, name)
    call h5dwrite_f(ds, dtype, data, st)
    call check(st, name)
    call h5dclose_f(ds, st)
    call h5sclose_f(space, st)
  end subroutine write_dataset

  subroutine write_real(g, name, data, rows, cols)
    integer(hid_t), intent(in) :: g
    character(len=*), intent(in) :: name
    type(c_ptr), intent(in) :: data      ! rows * max(cols, 1) doubles
    integer, intent(in) :: rows, cols     ! cols 0: a vector
    integer(hsize_t) :: dims(2)
    integer(hid_t) :: space
    integer :: st
    if (cols > 0) then
      dims = [int(cols, hsize_t), int(rows, hsize_t)]   ! Fortran order of a C (rows, cols)
      call h5screate_simple_f(2, dims, space, st)
    else
      dims = [int(rows, hsize_t), 0_hsize_t]
      call h5screate_simple_f(1, dims(1:1), space, st)
    end if
    call check(st, name)
    call write_dataset(g, name, H5T_NATIVE_DOUBLE, space, data)
  end subroutine write_real

  subroutine write_int(g, name, data, rows)
    integer(hid_t), intent(in) :: g
    character(len=*), intent(in) :: name
    type(c_ptr), intent(in) :: data      ! rows ints
    integer, intent(in) :: rows
    integer(hsize_t) :: dims(1)
    integer(hid_t) :: space
    integer :: st
    dims = [int(rows, hsize_t)]
    call h5screate_simple_f(1, dims, space, st)
    call check(st, name)
    call write_dataset(g, name, h5kind_to_type(c_int, H5_INTEGER_KIND), space, data)
  end subroutine write_int

  subroutine write_attr(g, name, itype, ptr)
    integer(hid_t), intent(in) :: g, itype
    character(len=*), intent(in) :: name
    type(c_ptr), intent(in) :: ptr
    integer(hid_t) :: space, a
    integer :: st
    call h5screate_f(H5S_SCALAR_F, space, st)
    call check(st, name)
    call h5acreate_f(g, name, itype, space, a, st)
    call check(st, name)
    call h5awrite_f(a, itype, ptr, st)
    call check(st, name)
    call h5aclose_f(a, st)
    call h5sclose_f(space, st)
  end subroutine write_attr

  ! Writes the particle state (docs/DESIGN.md section 6) to a temporary file, then renames it.
  subroutine write_state_h5(path, m, time, step, dt)
    character(len=*), intent(in) :: path
    type(model_t), intent(in), target :: m
    real(dp), intent(in) :: time, dt
    integer(int64), intent(in) :: step
    real(dp), allocatable, target :: rho(:), x(:,:), v(:,:), sig(:,:), s1(:)
    integer(c_int), allocatable, target :: mat(:), body(:)
    integer, allocatable :: at(:)
    real(dp), target :: t_time, t_dt
    integer(int64), target :: t_step
    integer(hid_t) :: f, g, untimed_file, untimed_group
    integer :: st, np
    character(len=:), allocatable :: tmp
    np = m%particles%np
    tmp = path // '.tmp'
    call h5open_f(st)
    call check(st, 'the HDF5 library')
    call h5eset_auto_f(0, st)
    call h5pcreate_f(H5P_FILE_CREATE_F, untimed_file, st)
    call h5pset_obj_track_times_f(untimed_file, .false., st)
    call h5pcreate_f(H5P_GROUP_CREATE_F, untimed_group, st)
    call h5pset_obj_track_times_f(untimed_group, .false., st)
    call h5pcreate_f(H5P_DATASET_CREATE_F, untimed_dataset, st)
    call h5pset_obj_track_times_f(untimed_dataset, .false., st)
    call check(st, 'the creation properties')
    call h5fcreate_f(tmp, H5F_ACC_TRUNC_F, f, st, creation_prp=untimed_file)
    if (st < 0) then
      write (error_unit, '(a)') 'mpm3d_ref: cannot create the state file ' // path
      stop 1, quiet=.true.
    end if
    call h5gcreate_f(f, '/particles', g, st, gcpl_id=untimed_group)
    call check(st, '/particles')
    ! In deck order, whatever the storage order (particles_order_by_blocks).
    call particles_deck_order(m%particles, at)
    rho = m%particles%mass(at) / m%particles%vol(at)
    mat = m%particles%mat(at) + 1
    body = m%particles%body(at) + 1
    x = m%particles%x(:, at)
    v = m%particles%v(:, at)
    sig = m%particles%sig(:, at)
    call write_real(g, 'position', c_loc(x), np, 3)
    call write_real(g, 'velocity', c_loc(v), np, 3)
    call write_real(g, 'stress', c_loc(sig), np, 6)
    s1 = m%particles%mass(at)
    call write_real(g, 'mass', c_loc(s1), np, 0)
    s1 = m%particles%vol(at)
    call write_real(g, 'volume', c_loc(s1), np, 0)
    call write_real(g, 'density', c_loc(rho), np, 0)
    s1 = m%particles%epeff(at)
    call write_real(g, 'epeff', c_loc(s1), np, 0)
    s1 = m%particles%ie(at)
    call write_real(g, 'internal_energy', c_loc(s1), np, 0)
    if (allocated(m%particles%temp)) then
      s1 = m%particles%temp(at)
      call write_real(g, 'temperature', c_loc(s1), np, 0)
    end if
    call write_int(g, 'material', c_loc(mat), np)
    call write_int(g, 'body', c_loc(body), np)
    t_time = time
    t_step = step
    t_dt = dt
    call write_attr(g, 'time', H5T_NATIVE_DOUBLE, c_loc(t_time))
    call write_attr(g, 'step', h5kind_to_type(int64, H5_INTEGER_KIND), c_loc(t_step))
    call write_attr(g, 'dt', H5T_NATIVE_DOUBLE, c_loc(t_dt))
    call h5gclose_f(g, st)
    call h5fclose_f(f, st)
    call check(st, path)
    call h5pclose_f(untimed_dataset, st)
    call h5pclose_f(untimed_group, st)
    call h5pclose_f(untimed_file, st)
    call h5close_f(st)
    if (c_rename(tmp // c_null_char, path // c_null_char) /= 0) then
      st = c_remove(tmp // c_null_char)
      write (error_unit, '(a)') 'mpm3d_ref: cannot write the state file ' // path
      stop 1, quiet=.true.
    end if
  end subroutine write_state_h5

end module mpm3d_data_out
