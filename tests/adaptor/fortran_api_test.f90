! The C API from Fortran through module tetray: one tet carrying f = z, will_render, a rendered
! step and its report, a size error with its message, a scene skipped for a missing field, and a
! config error. Stops with code 1 on a failed check.
program fortran_api_test
  use, intrinsic :: iso_c_binding
  use mpi
  use tetray
  use tetray_test_check
  implicit none
  type(c_ptr) :: handle, bad
  real(c_double), target :: xyz(12) = [0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 0d0, 1d0]
  integer(c_int64_t), target :: tets(4) = [0_c_int64_t, 1_c_int64_t, 2_c_int64_t, 3_c_int64_t]
  real(c_double), target :: f(4) = [0d0, 0d0, 0d0, 1d0]
  type(tetray_report) :: report
  integer(c_int) :: will
  character(len=:), allocatable :: skipped
  integer :: ierr
  character(len=*), parameter :: dir = "fortran_api_test_out"

  call mpi_init(ierr)
  call check(tetray_create_from_yaml(MPI_COMM_WORLD, &
      "output: {directory: " // dir // ", formats: [png], quiet: true, writer_queue_depth: 0}" // &
      new_line("a") // "scenes: [{name: tet, field: f, isovalues: [0.25], image: {width: 16, height: 16}}," // &
      " {name: by_h, field: f, isovalues: [0.5], color_by: h, image: {width: 16, height: 16}}]", &
      handle) == TETRAY_OK, "create")
  call check(tetray_set_mesh(handle, c_loc(xyz), TETRAY_FLOAT64, 4_c_int64_t, c_null_ptr, &
      TETRAY_FLOAT64, c_loc(tets), TETRAY_INT64, 1_c_int64_t, c_null_ptr, c_null_ptr) == TETRAY_OK, &
      "set_mesh")
  call check(tetray_set_field(handle, "f", c_loc(f), TETRAY_FLOAT64, 4_c_int64_t) == TETRAY_OK, &
      "set_field")
  call check(tetray_will_render(handle, 0_c_int64_t, 0d0, will) == TETRAY_OK .and. will == 1, &
      "will_render")
  call check(tetray_execute(handle, 0_c_int64_t, 0d0, TETRAY_CHANGED_ALL) == TETRAY_PARTIAL, &
      "execute without h is partial")
  call check(index(tetray_error_message(), "scene 'by_h' skipped") > 0, "partial message")
  call check(tetray_get_report(handle, report) == TETRAY_OK .and. report%rendered == 1 .and. &
      report%scenes_rendered == 1 .and. report%scenes_skipped == 1, "report")
  call check(tetray_bvh_decision(report) == "rebuild", "bvh decision")
  call check(tetray_skipped_scene(handle, 0_c_int, skipped) == TETRAY_OK .and. skipped == "by_h", &
      "skipped scene")
  call check(tetray_set_field(handle, "h", c_loc(f), TETRAY_FLOAT64, 4_c_int64_t) == TETRAY_OK, &
      "set h")
  call check(len(tetray_error_message()) == 0, "no message after a success")
  call check(tetray_set_field(handle, "f", c_loc(f), TETRAY_FLOAT64, 2_c_int64_t) == TETRAY_OK, &
      "set short field")
  call check(tetray_execute(handle, 1_c_int64_t, 1d0, TETRAY_CHANGED_FIELDS) == &
      TETRAY_INVALID_ARGUMENT, "short field is invalid")
  call check(index(tetray_error_message(), "2 values but the mesh has 4 points") > 0, "message")
  call check(tetray_finalize(handle) == TETRAY_OK, "finalize")
  call tetray_destroy(handle)
  call check(tetray_create_from_yaml(MPI_COMM_WORLD, "scenes: [{name: s}]", bad) == &
      TETRAY_CONFIG_ERROR, "config error")
  call execute_command_line("rm -rf " // dir)
  call mpi_finalize(ierr)
  if (failures > 0) stop 1
  print *, "fortran_api_test: all checks passed"

end program
