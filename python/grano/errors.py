"""The exceptions and warnings of the grano module."""


class Error(Exception):
    """Anything grano refuses or fails at."""


class SceneError(Error, ValueError):
    """A scene, setting or checkpoint refused, with grano's message: the
    file and line, or the key or setting, that was refused."""


class RunError(Error, RuntimeError):
    """A run that failed (an unstable step, a full disk, ...), with the
    method's diagnostic. The simulation keeps its last good state."""


class ValidityWarning(UserWarning):
    """A method's validity limit broken during a run (grano run's
    'validity limit ... broken' warning), told once per limit."""
