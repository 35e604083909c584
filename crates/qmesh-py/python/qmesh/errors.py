"""The exceptions qmesh raises. Every message is the command line's: the file, the line
and what was expected, in words."""


class MeshError(Exception):
    """Any qmesh error."""


class MeshValueError(MeshError, ValueError):
    """Bad content (a file that does not parse, a rule file with a wrong key, arrays of
    the wrong shape) or an operation that does not apply to the mesh."""


class MeshIOError(MeshError, OSError):
    """A file that cannot be opened, read or written."""
