"""Exceptions with messages that name the bad value and what is allowed."""

import math


class ParameterError(ValueError):
    """An invalid parameter: the message names the parameter, its value and what is allowed.

    Parameters
    ----------
    name : str
        The parameter (or key) that is wrong.
    value : object
        Its value.
    allowed : str
        What is allowed, in words (``"a finite number > 0"``).

    Attributes
    ----------
    name, value, allowed
        As given.

    Examples
    --------
    >>> from chainchaos import random_chain
    >>> random_chain(seed=1, alpha=0.5)
    Traceback (most recent call last):
        ...
    chainchaos.errors.ParameterError: invalid alpha = 0.5: allowed is alpha >= 1
    """

    def __init__(self, name: str, value, allowed: str):
        self.name, self.value, self.allowed = name, value, allowed
        super().__init__(f"invalid {name} = {value!r}: allowed is {allowed}")


class ChainFileError(ValueError):
    """A chain or radii file that is missing, unreadable, or not a chain (the data contract,
    docs/conventions.md#chain-file).

    Parameters
    ----------
    message : str
        The file and what is wrong with it.
    """

    def __init__(self, message: str):
        super().__init__(message)


class ConfigError(ValueError):
    """A wrong pipeline config: one line per wrong key, naming the key, its value and what is
    allowed (chainchaos.workflow.config_check).

    Parameters
    ----------
    messages : list of str
        One line per wrong key.

    Attributes
    ----------
    messages : list of str
        As given.
    """

    def __init__(self, messages: list[str]):
        self.messages = list(messages)
        super().__init__("invalid config (config/schema.yaml, config/README.md):\n  " + "\n  ".join(self.messages))


class StudyError(ConfigError):
    """A wrong study file: one line per wrong key, naming the key, its value and what is allowed
    (chainchaos.studies.study.spec).

    A :class:`ConfigError`, and so a ``ValueError``.

    Parameters
    ----------
    messages : list of str
        One line per wrong key.

    Attributes
    ----------
    messages : list of str
        As given.
    """

    def __init__(self, messages: list[str]):
        self.messages = list(messages)
        ValueError.__init__(self, "invalid study (keys: studies/README.md):\n  "
                            + "\n  ".join(self.messages))


class SimulationError(RuntimeError):
    """A run stopped by a guard (non-finite state or energy error above the bound).

    Parameters
    ----------
    scene : str
        The scene's (or orbit's) name.
    time : float
        The sample time at which the guard stopped the run, in the model's time unit.
    quantity : str
        What the guard saw (``"relative energy error"``, ``"non-finite state"``).
    value : float
        Its value (dimensionless for the energy error).
    bound : str, optional
        The bound it exceeded, in words (empty: none to name).

    Attributes
    ----------
    scene, time, quantity, value
        As given.
    """

    def __init__(self, scene: str, time: float, quantity: str, value: float, bound: str = ""):
        self.scene, self.time, self.quantity, self.value = scene, time, quantity, value
        detail = f" (bound {bound})" if bound else ""
        super().__init__(f"scene {scene!r} stopped at t = {time:.6g}: {quantity} = {value:.6g}{detail}")


class KeptFileError(RuntimeError):
    """A result kept as data (chainchaos.records.kept) that cannot stand in for its computation and
    cannot be judged either: unreadable, truncated, or without the settings that key it. The
    message is one line: the file, what is wrong, how to restore or remake it.

    Parameters
    ----------
    message : str
        That line.
    """

    def __init__(self, message: str):
        super().__init__(message)


class BuildError(RuntimeError):
    """A build failure with a message for the reader (no traceback is shown): TeX missing, a
    LaTeX error (chainchaos.output.manuscript).

    Parameters
    ----------
    message : str
        What failed and what to do, for the reader.
    """

    def __init__(self, message: str):
        super().__init__(message)


def require(condition: bool, name: str, value, allowed: str) -> None:
    """Raise :class:`ParameterError` unless ``condition`` holds.

    Parameters
    ----------
    condition : bool
        What must hold.
    name : str
        The parameter it is about.
    value : object
        The parameter's value.
    allowed : str
        What is allowed, in words.

    Raises
    ------
    ParameterError
        When ``condition`` is false, with ``name``, ``value`` and ``allowed``.
    """
    if not condition:
        raise ParameterError(name, value, allowed)


def require_finite_positive(owner, *keys: str) -> None:
    """Require every named attribute of ``owner`` to be a finite number > 0.

    Parameters
    ----------
    owner : object
        The object whose attributes are checked (a settings record).
    *keys : str
        The attributes' names.

    Raises
    ------
    ParameterError
        Naming the first attribute that is not an int or float, finite and > 0.
    """
    for key in keys:
        value = getattr(owner, key)
        require(isinstance(value, (int, float)) and math.isfinite(value) and value > 0, key, value,
                "a finite number > 0")
