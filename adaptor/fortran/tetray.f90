! Fortran interface to tetray's C API (tetray/adaptor.h) through ISO_C_BINDING. The wrappers
! tetray_create and tetray_create_from_yaml take a Fortran communicator and Fortran strings;
! everything else is the C call itself. Arrays are passed with c_loc(array) and stay the
! solver's: they must remain valid until the tetray_execute that reads them. Connectivity is
! 0-based, as in C.
module tetray
  use, intrinsic :: iso_c_binding
  implicit none
  private

  integer(c_int), parameter, public :: TETRAY_OK = 0, TETRAY_INVALID_ARGUMENT = 1, &
    TETRAY_CONFIG_ERROR = 2, TETRAY_IO_ERROR = 3, TETRAY_MPI_ERROR = 4, &
    TETRAY_INTERNAL_ERROR = 5, TETRAY_NOT_INITIALIZED = 6, TETRAY_PARTIAL = 7
  integer(c_int), parameter, public :: TETRAY_FLOAT32 = 0, TETRAY_FLOAT64 = 1
  integer(c_int), parameter, public :: TETRAY_INT32 = 0, TETRAY_INT64 = 1
  integer(c_int), parameter, public :: TETRAY_CHANGED_GEOMETRY = 1, TETRAY_CHANGED_TOPOLOGY = 2, &
    TETRAY_CHANGED_FIELDS = 4, TETRAY_CHANGED_ALL = 7

  type, bind(c), public :: tetray_report
    integer(c_int) :: rendered
    integer(c_int) :: scenes_rendered
    real(c_double) :: seconds_blocked
    integer(c_int64_t) :: tets_skipped
    integer(c_int) :: scenes_skipped
    type(c_ptr) :: bvh_decision  ! read it with tetray_bvh_decision(report)
  end type

  public :: tetray_create, tetray_create_from_yaml, tetray_set_mesh, tetray_set_cells, &
    tetray_set_field, &
    tetray_clear_fields, tetray_will_render, tetray_execute, tetray_get_report, &
    tetray_skipped_scene, tetray_bvh_decision, tetray_finalize, tetray_destroy, &
    tetray_error_message

  interface
    integer(c_int) function c_create_f(comm, path, handle) bind(c, name="tetray_create_f")
      import :: c_int, c_char, c_ptr
      integer(c_int), value :: comm
      character(kind=c_char), intent(in) :: path(*)
      type(c_ptr), intent(out) :: handle
    end function

    integer(c_int) function c_create_from_yaml_f(comm, yaml, handle) &
        bind(c, name="tetray_create_from_yaml_f")
      import :: c_int, c_char, c_ptr
      integer(c_int), value :: comm
      character(kind=c_char), intent(in) :: yaml(*)
      type(c_ptr), intent(out) :: handle
    end function

    integer(c_int) function tetray_set_mesh(handle, xyz, xyz_type, point_count, displacement, &
        displacement_type, connectivity, index_type, tet_count, ghost, global_ids) &
        bind(c, name="tetray_set_mesh")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: handle, xyz, displacement, connectivity, ghost, global_ids
      integer(c_int), value :: xyz_type, displacement_type, index_type
      integer(c_int64_t), value :: point_count, tet_count
    end function

    ! Cells instead of tets (VTK types and node order, 0-based), after tetray_set_mesh.
    integer(c_int) function tetray_set_cells(handle, types, offsets, connectivity, index_type, &
        cell_count, ghost) bind(c, name="tetray_set_cells")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: handle, types, offsets, connectivity, ghost
      integer(c_int), value :: index_type
      integer(c_int64_t), value :: cell_count
    end function

    integer(c_int) function c_set_field(handle, name, values, type, count) &
        bind(c, name="tetray_set_field")
      import :: c_int, c_int64_t, c_ptr, c_char
      type(c_ptr), value :: handle, values
      character(kind=c_char), intent(in) :: name(*)
      integer(c_int), value :: type
      integer(c_int64_t), value :: count
    end function

    integer(c_int) function tetray_clear_fields(handle) bind(c, name="tetray_clear_fields")
      import :: c_int, c_ptr
      type(c_ptr), value :: handle
    end function

    integer(c_int) function tetray_will_render(handle, step, time, will_render) &
        bind(c, name="tetray_will_render")
      import :: c_int, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: handle
      integer(c_int64_t), value :: step
      real(c_double), value :: time
      integer(c_int), intent(out) :: will_render
    end function

    integer(c_int) function tetray_execute(handle, step, time, changes) &
        bind(c, name="tetray_execute")
      import :: c_int, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: handle
      integer(c_int64_t), value :: step
      real(c_double), value :: time
      integer(c_int), value :: changes
    end function

    integer(c_int) function tetray_get_report(handle, report) bind(c, name="tetray_get_report")
      import :: c_int, c_ptr, tetray_report
      type(c_ptr), value :: handle
      type(tetray_report), intent(out) :: report
    end function

    integer(c_int) function c_get_skipped_scene(handle, index, name) &
        bind(c, name="tetray_get_skipped_scene")
      import :: c_int, c_ptr
      type(c_ptr), value :: handle
      integer(c_int), value :: index
      type(c_ptr), intent(out) :: name
    end function

    integer(c_int) function tetray_finalize(handle) bind(c, name="tetray_finalize")
      import :: c_int, c_ptr
      type(c_ptr), value :: handle
    end function

    subroutine tetray_destroy(handle) bind(c, name="tetray_destroy")
      import :: c_ptr
      type(c_ptr), value :: handle
    end subroutine

    type(c_ptr) function c_last_error() bind(c, name="tetray_last_error")
      import :: c_ptr
    end function

    integer(c_size_t) function c_strlen(text) bind(c, name="strlen")
      import :: c_size_t, c_ptr
      type(c_ptr), value :: text
    end function
  end interface

contains

  ! `comm` is a Fortran MPI communicator handle (an integer, or mpi_f08's comm%MPI_VAL).
  integer(c_int) function tetray_create(comm, config_path, handle)
    integer, intent(in) :: comm
    character(len=*), intent(in) :: config_path
    type(c_ptr), intent(out) :: handle
    tetray_create = c_create_f(int(comm, c_int), trim(config_path)//c_null_char, handle)
  end function

  integer(c_int) function tetray_create_from_yaml(comm, yaml, handle)
    integer, intent(in) :: comm
    character(len=*), intent(in) :: yaml
    type(c_ptr), intent(out) :: handle
    tetray_create_from_yaml = c_create_from_yaml_f(int(comm, c_int), yaml//c_null_char, handle)
  end function

  integer(c_int) function tetray_set_field(handle, name, values, type, count)
    type(c_ptr), intent(in) :: handle, values
    character(len=*), intent(in) :: name
    integer(c_int), intent(in) :: type
    integer(c_int64_t), intent(in) :: count
    tetray_set_field = c_set_field(handle, trim(name)//c_null_char, values, type, count)
  end function

  ! Skipped scene `index` (0-based, below report%scenes_skipped) of the last tetray_execute.
  integer(c_int) function tetray_skipped_scene(handle, index, name)
    type(c_ptr), intent(in) :: handle
    integer(c_int), intent(in) :: index
    character(len=:), allocatable, intent(out) :: name
    type(c_ptr) :: text
    tetray_skipped_scene = c_get_skipped_scene(handle, index, text)
    if (tetray_skipped_scene == TETRAY_OK) then
      name = fortran_string(text)
    else
      name = ""
    end if
  end function

  function tetray_bvh_decision(report) result(decision)
    type(tetray_report), intent(in) :: report
    character(len=:), allocatable :: decision
    decision = fortran_string(report%bvh_decision)
  end function

  ! The message of the last call on this thread ("" when it returned TETRAY_OK).
  function tetray_error_message() result(message)
    character(len=:), allocatable :: message
    message = fortran_string(c_last_error())
  end function

  ! A copy of a NUL-terminated C string ("" for a null pointer).
  function fortran_string(text) result(copy)
    type(c_ptr), intent(in) :: text
    character(len=:), allocatable :: copy
    character(kind=c_char), pointer :: chars(:)
    integer :: i, n
    if (.not. c_associated(text)) then
      copy = ""
      return
    end if
    n = int(c_strlen(text))
    call c_f_pointer(text, chars, [n])
    allocate(character(len=n) :: copy)
    do i = 1, n
      copy(i:i) = chars(i)
    end do
  end function

end module tetray
