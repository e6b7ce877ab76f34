! The check of the Fortran tests: a failed check prints what failed and the C API's last error,
! and is counted in `failures`; the test stops with code 1 when any failed.
module tetray_test_check
  use tetray, only: tetray_error_message
  implicit none
  private
  integer, public :: failures = 0
  public :: check

contains

  subroutine check(ok, what)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: what
    if (.not. ok) then
      print *, "FAILED: ", what, " (", tetray_error_message(), ")"
      failures = failures + 1
    end if
  end subroutine

end module
