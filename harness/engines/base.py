"""The one interface through which the harness reaches every engine."""
from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np


@dataclass
class WarpFunctions:
    """An engine's sampler and pdf for one distribution, over numpy arrays.

    sample: (N, 2) uniforms in [0,1)^2 -> (N, 2) or (N, 3) points (float64).
    pdf: points -> (N,) densities (float64).
    native_run: given N, prepares N uniforms in the engine's own containers and
    returns a call that warps them all (for throughput, without conversions).
    """

    sample: Callable[[np.ndarray], np.ndarray]
    pdf: Callable[[np.ndarray], np.ndarray]
    native_run: Callable[[int], Callable[[], Any]]


class Engine(ABC):
    """A renderer the harness can drive."""

    #: Short name used in reports and results.json.
    name: str

    @abstractmethod
    def warp(self, name: str, alpha: float | None = None) -> WarpFunctions | None:
        """The warp called `name` (Mitsuba's snake-case name, e.g. "square_to_tent"),
        with its parameter if it has one; None if this engine lacks that distribution."""

    @abstractmethod
    def version(self) -> str:
        """What exactly is running (library version, variant), for provenance."""
