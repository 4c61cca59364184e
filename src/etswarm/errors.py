"""The one exception type users see: a single-line, actionable message."""


class EtswarmError(Exception):
    """A user-facing error. ``str(err)`` is one line naming the file, row or option at fault.

    The CLI prints it as ``etswarm: error: <message>`` and exits with status 2; it never
    shows a traceback for these.
    """

    def __init__(self, message: str) -> None:
        super().__init__(" ".join(str(message).split()))
