"""The package's Python code raises the extension's one exception too."""
from ._rocking import RockingError


def error(detail):
    """A :class:`RockingError` without a C code (scenes, arguments checked in Python, the OpenSees
    coupling); ``detail`` names the field or argument."""
    e = RockingError(detail)
    e.code = e.name = e.message = None
    e.detail = detail
    return e
