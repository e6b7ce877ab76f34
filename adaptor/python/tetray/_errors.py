"""tetray.Error: a failed tetray call; tetray.PartialWarning: a call that skipped scenes."""


class Error(RuntimeError):
    """Raised for a failed tetray call.

    ``code`` is the tetray.StatusCode (``code.name`` its name, ``int(code)`` its value, the same
    as the C API's TETRAY_* codes) and ``message`` the adaptor's text, which names the problem.
    The adaptor stays usable after an Error: the next call may succeed.
    """

    def __init__(self, code, message):
        super().__init__(f"{code.name}: {message}")
        self.code = code
        self.message = message


class PartialWarning(UserWarning):
    """Warned for a call that completed but skipped some scenes (StatusCode.partial).

    The message names each skipped scene and why (e.g. its field missing on a rank); the other
    scenes rendered, and the call's ExecuteReport lists the skipped ones in ``skipped_scenes``.
    """
