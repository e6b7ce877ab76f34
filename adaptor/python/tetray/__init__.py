"""tetray: in-situ isosurface ray tracing of tetrahedral finite-element fields.

A solver creates one ``Adaptor`` per communicator (an mpi4py communicator) and calls
``execute`` from its time loop with numpy arrays, which tetray reads in place during the call
(README.md, section "Python").
"""

from ._errors import Error, PartialWarning
from ._tetray import Adaptor, Changes, ExecuteReport, StatusCode

__all__ = ["Adaptor", "Changes", "Error", "ExecuteReport", "PartialWarning", "StatusCode"]
