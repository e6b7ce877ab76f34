! One tet carrying f = z, its 0.5 isosurface rendered through the installed tetray from Fortran;
! the image directory is the first argument. Stops with code 1 on any failure.
program one_tet
  use, intrinsic :: iso_c_binding
  use mpi
  use tetray
  implicit none
  type(c_ptr) :: handle
  real(c_double), target :: xyz(12) = [0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 0d0, 1d0]
  integer(c_int64_t), target :: tets(4) = [0_c_int64_t, 1_c_int64_t, 2_c_int64_t, 3_c_int64_t]
  real(c_double), target :: f(4) = [0d0, 0d0, 0d0, 1d0]
  character(len=512) :: dir
  integer :: ierr, status

  call mpi_init(ierr)
  call get_command_argument(1, dir)
  status = tetray_create_from_yaml(MPI_COMM_WORLD, "output: {directory: " // trim(dir) // &
      ", formats: [png], quiet: true}" // new_line("a") // &
      "scenes: [{name: tet, field: f, isovalues: [0.5], image: {width: 16, height: 16}}]", handle)
  if (status == TETRAY_OK) status = tetray_set_mesh(handle, c_loc(xyz), TETRAY_FLOAT64, &
      4_c_int64_t, c_null_ptr, TETRAY_FLOAT64, c_loc(tets), TETRAY_INT64, 1_c_int64_t, &
      c_null_ptr, c_null_ptr)
  if (status == TETRAY_OK) status = tetray_set_field(handle, "f", c_loc(f), TETRAY_FLOAT64, &
      4_c_int64_t)
  if (status == TETRAY_OK) status = tetray_execute(handle, 0_c_int64_t, 0d0, TETRAY_CHANGED_ALL)
  if (status == TETRAY_OK) status = tetray_finalize(handle)
  if (status /= TETRAY_OK) print *, "consumer: ", tetray_error_message()
  call tetray_destroy(handle)
  call mpi_finalize(ierr)
  if (status /= TETRAY_OK) stop 1
end program
