"""The package's exceptions."""


class CaseError(ValueError):
    """Bad input in a case: ``str(error)`` is the CLI's ``file:line: message``.

    ``line`` 0 means the file as a whole (e.g. it does not exist).
    """

    def __init__(self, text: str, file: str = "", line: int = 0, message: str = ""):
        super().__init__(text)
        self.file, self.line, self.message = file, line, message


class Interrupted(KeyboardInterrupt):
    """A solve stopped by Ctrl-C: ``result`` holds what it had found, verified as the CLI
    verifies an interrupted run (a second Ctrl-C skips the verification)."""

    def __init__(self, result):
        super().__init__("linkbox: interrupted: " + result.headline)
        self.result = result


CaseError.__module__ = Interrupted.__module__ = "linkbox"  # as tracebacks name them
