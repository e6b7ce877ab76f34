! The Fortran API end to end against an analytic answer: the ball of c_api_ball_test.c (radius
! 0.6 at distance 3, tests/support/ball_image.h), rendered through module tetray from tets and
! from hexahedra (tetray_set_cells), must cover as many pixels of the PNG as the camera geometry
! and the mesh's interpolation error allow. The mesh, the bounds and the PNG count come from the C
! helper, so both languages check the same answer. Stops with code 1 on a failed check.
program fortran_ball_test
  use, intrinsic :: iso_c_binding
  use mpi
  use tetray
  use tetray_test_check
  implicit none

  interface
    integer(c_int64_t) function ball_point_count(cells) bind(c, name="tetray_ball_point_count")
      import :: c_int, c_int64_t
      integer(c_int), value :: cells
    end function
    integer(c_int64_t) function ball_tet_count(cells) bind(c, name="tetray_ball_tet_count")
      import :: c_int, c_int64_t
      integer(c_int), value :: cells
    end function
    subroutine ball_mesh(cells, xyz, tets, distance) bind(c, name="tetray_ball_mesh")
      import :: c_int, c_double, c_int64_t
      integer(c_int), value :: cells
      real(c_double) :: xyz(*), distance(*)
      integer(c_int64_t) :: tets(*)
    end subroutine
    subroutine ball_pixel_bounds(cells, radius, eye_distance, fov_deg, width, height, fewest, &
        most) bind(c, name="tetray_ball_pixel_bounds")
      import :: c_int, c_double, c_int64_t
      integer(c_int), value :: cells, width, height
      real(c_double), value :: radius, eye_distance, fov_deg
      integer(c_int64_t) :: fewest, most
    end subroutine
    integer(c_int64_t) function ball_hex_count(cells) bind(c, name="tetray_ball_hex_count")
      import :: c_int, c_int64_t
      integer(c_int), value :: cells
    end function
    subroutine ball_hexahedra(cells, connectivity) bind(c, name="tetray_ball_hexahedra")
      import :: c_int, c_int64_t
      integer(c_int), value :: cells
      integer(c_int64_t) :: connectivity(*)
    end subroutine
    integer(c_int64_t) function png_covered_pixels(path) bind(c, name="tetray_png_covered_pixels")
      import :: c_char, c_int64_t
      character(kind=c_char) :: path(*)
    end function
  end interface

  integer(c_int), parameter :: cells = 16, side = 64
  character(len=*), parameter :: dir = "fortran_ball_test_out"
  integer :: ierr

  call mpi_init(ierr)
  call render_ball("ball", .false.)
  call render_ball("hexahedra", .true.)
  call execute_command_line("rm -rf " // dir)
  call mpi_finalize(ierr)
  if (failures > 0) stop 1

contains

  ! Renders the ball as scene `name` from tets or hexahedra, and checks its pixel count.
  subroutine render_ball(name, as_hexahedra)
    character(len=*), intent(in) :: name
    logical, intent(in) :: as_hexahedra
    real(c_double), allocatable, target :: xyz(:), distance(:)
    integer(c_int64_t), allocatable, target :: tets(:), hexahedra(:), offsets(:)
    integer(c_int8_t), allocatable, target :: types(:)
    integer(c_int64_t) :: points, tet_count, hex_count, covered, fewest, most, c
    type(c_ptr) :: handle

    call check(tetray_create_from_yaml(MPI_COMM_WORLD, &
        "output: {directory: " // dir // ", formats: [png], quiet: true, writer_queue_depth: 0}" &
        // new_line("a") // "scenes: [{name: " // name // ", field: distance, " // &
        "isovalues: [0.6], camera: {eye: [0, 0, 3], look_at: [0, 0, 0], up: [0, 1, 0], " // &
        "fov_deg: 40}, image: {width: 64, height: 64}}]", handle) == TETRAY_OK, "create")
    points = ball_point_count(cells)
    tet_count = ball_tet_count(cells)
    hex_count = ball_hex_count(cells)
    allocate(xyz(3 * points), distance(points), tets(4 * tet_count), hexahedra(8 * hex_count), &
        offsets(hex_count + 1), types(hex_count))
    call ball_mesh(cells, xyz, tets, distance)
    if (as_hexahedra) then
      call ball_hexahedra(cells, hexahedra)
      offsets = [(8 * c, c = 0, hex_count)]
      types = 12_c_int8_t  ! VTK_HEXAHEDRON
      call check(tetray_set_mesh(handle, c_loc(xyz), TETRAY_FLOAT64, points, c_null_ptr, &
          TETRAY_FLOAT64, c_null_ptr, TETRAY_INT64, 0_c_int64_t, c_null_ptr, c_null_ptr) == &
          TETRAY_OK, "set_mesh without tets")
      call check(tetray_set_cells(handle, c_loc(types), c_loc(offsets), c_loc(hexahedra), &
          TETRAY_INT64, hex_count, c_null_ptr) == TETRAY_OK, "set_cells")
    else
      call check(tetray_set_mesh(handle, c_loc(xyz), TETRAY_FLOAT64, points, c_null_ptr, &
          TETRAY_FLOAT64, c_loc(tets), TETRAY_INT64, tet_count, c_null_ptr, c_null_ptr) == &
          TETRAY_OK, "set_mesh")
    end if
    call check(tetray_set_field(handle, "distance", c_loc(distance), TETRAY_FLOAT64, points) == &
        TETRAY_OK, "set_field")
    call check(tetray_execute(handle, 0_c_int64_t, 0d0, TETRAY_CHANGED_ALL) == TETRAY_OK, &
        "execute")
    call check(tetray_finalize(handle) == TETRAY_OK, "finalize")
    call tetray_destroy(handle)

    covered = png_covered_pixels(dir // "/" // name // "/" // name // "_000000.png" // &
        c_null_char)
    call ball_pixel_bounds(cells, 0.6d0, 3d0, 40d0, side, side, fewest, most)
    print *, "fortran_ball_test: ", name, ": pixels covered", covered, "expected", fewest, "to", &
        most
    call check(covered >= fewest .and. covered <= most, &
        "the ball covers the pixels its geometry predicts")
  end subroutine

end program
