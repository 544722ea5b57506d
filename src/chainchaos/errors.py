"""Exceptions with messages that name the bad value and what is allowed."""

import math


class ParameterError(ValueError):
    """An invalid parameter: the message names the parameter, its value and what is allowed."""

    def __init__(self, name: str, value, allowed: str):
        self.name, self.value, self.allowed = name, value, allowed
        super().__init__(f"invalid {name} = {value!r}: allowed is {allowed}")


class ChainFileError(ValueError):
    """A chain or radii file that is missing, unreadable, or not a chain (the data contract,
    docs/conventions.md#chain-file)."""


class ConfigError(ValueError):
    """A wrong pipeline config: one line per wrong key, naming the key, its value and what is
    allowed (chainchaos.workflow.config_check)."""

    def __init__(self, messages: list[str]):
        self.messages = list(messages)
        super().__init__("invalid config (config/schema.yaml, config/README.md):\n  " + "\n  ".join(self.messages))


class StudyError(ConfigError):
    """A wrong study file: one line per wrong key, naming the key, its value and what is allowed
    (chainchaos.studies.study.spec)."""

    def __init__(self, messages: list[str]):
        self.messages = list(messages)
        ValueError.__init__(self, "invalid study (keys: studies/README.md):\n  "
                            + "\n  ".join(self.messages))


class SimulationError(RuntimeError):
    """A run stopped by a guard (non-finite state or energy error above the bound)."""

    def __init__(self, scene: str, time: float, quantity: str, value: float, bound: str = ""):
        self.scene, self.time, self.quantity, self.value = scene, time, quantity, value
        detail = f" (bound {bound})" if bound else ""
        super().__init__(f"scene {scene!r} stopped at t = {time:.6g}: {quantity} = {value:.6g}{detail}")


class KeptFileError(RuntimeError):
    """A result kept as data (chainchaos.records.kept) that cannot stand in for its computation and
    cannot be judged either: unreadable, truncated, or without the settings that key it. The
    message is one line: the file, what is wrong, how to restore or remake it."""


class BuildError(RuntimeError):
    """A build failure with a message for the reader (no traceback is shown): TeX missing, a
    LaTeX error (chainchaos.output.manuscript)."""


def require(condition: bool, name: str, value, allowed: str) -> None:
    """Raise :class:`ParameterError` unless ``condition`` holds."""
    if not condition:
        raise ParameterError(name, value, allowed)


def require_finite_positive(owner, *keys: str) -> None:
    """Every named attribute of ``owner`` is a finite number > 0 (else :class:`ParameterError`)."""
    for key in keys:
        value = getattr(owner, key)
        require(isinstance(value, (int, float)) and math.isfinite(value) and value > 0, key, value,
                "a finite number > 0")
