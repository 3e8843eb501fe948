"""The GP controller: each individual's trees, evaluated every tick, are its desired angles.

As in the paper, "the controller program is interpreted as a list of the
desired orientation angles for the joints": tree j's value is the target of
actuator ``wiring.actuators[j]``; the figure's other joints hold their neutral
angles (the paper's humanoid had 4–10 of its joints under genetic control).

Terminal values are an affine map of the figure's sensor columns, ``inputs =
sensors @ input_weights + input_offset``: a plain sensor is a column of the
identity, a goal-relative position such as ``gx = X − root_x`` has weight −1
and offset X. Tree values are clipped to the joint's range; a NaN becomes the
joint's neutral angle and ±inf the end of its range (the neutral angle if the
range is unbounded); both are counted in `GPController.nonfinite`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.control.gp.interpreter import PackedPopulation
from sinews.control.gp.primitives import GPError
from sinews.control.gp.tree import Program

__all__ = ["GPController", "Wiring"]

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class Wiring:
    """How a figure's sensors feed the terminals and the trees drive its servos.

    Attributes:
        input_weights: (S, V) weight of sensor column s in terminal v.
        input_offset: (V,) constant part of each terminal.
        actuators: (J,) actuator index driven by each tree slot.
        neutral: (n_act,) targets of the joints no tree drives, and of a NaN tree.
        joint_range: (n_act, 2) lowest and highest target, rad.
    """

    input_weights: FloatArray
    input_offset: FloatArray
    actuators: npt.NDArray[np.intp]
    neutral: FloatArray
    joint_range: FloatArray

    def __post_init__(self) -> None:
        weights = np.asarray(self.input_weights, dtype=np.float64)
        offset = np.asarray(self.input_offset, dtype=np.float64)
        actuators = np.asarray(self.actuators, dtype=np.intp)
        neutral = np.asarray(self.neutral, dtype=np.float64)
        joint_range = np.asarray(self.joint_range, dtype=np.float64)
        n_act = len(neutral)
        if weights.ndim != 2 or offset.shape != (weights.shape[1],):
            raise GPError("input_weights must be (S, V) and input_offset (V,)")
        if not (np.isfinite(weights).all() and np.isfinite(offset).all()):
            raise GPError("input weights and offsets must be finite")
        if actuators.ndim != 1 or len(set(actuators.tolist())) != len(actuators):
            raise GPError("actuators must list distinct actuator indices")
        if len(actuators) == 0 or actuators.min() < 0 or actuators.max() >= n_act:
            raise GPError(f"actuators must be indices in [0, {n_act})")
        if joint_range.shape != (n_act, 2):
            raise GPError(f"joint_range must have shape ({n_act}, 2)")
        for name, array in (
            ("input_weights", weights),
            ("input_offset", offset),
            ("actuators", actuators),
            ("neutral", neutral),
            ("joint_range", joint_range),
        ):
            array.flags.writeable = False
            object.__setattr__(self, name, array)

    @property
    def n_trees(self) -> int:
        """Trees per program J (driven joints)."""
        return len(self.actuators)

    @property
    def n_terminals(self) -> int:
        """Terminal columns V."""
        return len(self.input_offset)


class GPController:
    """A population of GP programs driving a figure (the `Controller` protocol).

    Args:
        programs: P programs of ``wiring.n_trees`` trees each.
        wiring: sensors → terminals and trees → actuators.
        parallel: evaluate with the parallel kernel (slower inside a MuJoCo
            rollout on a machine whose cores MuJoCo already uses; see
            `sinews.control.gp.kernels`).

    Attributes:
        nonfinite: (P,) number of NaN or infinite tree values since `reset`.
    """

    def __init__(
        self, programs: Sequence[Program], wiring: Wiring, *, parallel: bool = False
    ) -> None:
        self.packed = PackedPopulation.pack(programs)
        self.parallel = parallel
        if self.packed.n_trees != wiring.n_trees:
            raise GPError(
                f"programs have {self.packed.n_trees} trees, wiring drives {wiring.n_trees}"
            )
        self.wiring = wiring
        n = self.packed.n_programs
        self.nonfinite = np.zeros(n, dtype=np.int64)
        self._values = np.empty((n, wiring.n_trees))
        self._targets = np.tile(wiring.neutral, (n, 1))
        slot_range = wiring.joint_range[wiring.actuators]
        self._low, self._high = slot_range[:, 0], slot_range[:, 1]
        self._neutral = wiring.neutral[wiring.actuators]

    def reset(self, n_individuals: int) -> None:
        """Zero the non-finite counts; ``n_individuals`` must be the number of programs."""
        if n_individuals != self.packed.n_programs:
            raise GPError(f"{self.packed.n_programs} programs cannot drive {n_individuals} figures")
        self.nonfinite[:] = 0

    def control(self, t: float, sensors: FloatArray) -> FloatArray:
        """Every individual's targets from its trees.

        Args:
            t: seconds since reset (the trees read time from the sensors).
            sensors: (P, S) the figure's sensor columns.

        Returns:
            (P, n_act) desired angles, rad.
        """
        inputs = sensors @ self.wiring.input_weights + self.wiring.input_offset
        values = self._tree_values(inputs)
        targets = np.clip(values, self._low, self._high)
        finite = np.isfinite(values)
        if not finite.all():
            self.nonfinite += np.count_nonzero(~finite, axis=1)
            targets = np.where(np.isfinite(targets), targets, self._neutral)
        self._targets[:, self.wiring.actuators] = targets
        return self._targets

    def _tree_values(self, inputs: FloatArray) -> FloatArray:
        """(P, J) tree values on (P, V) terminal rows (a benchmark swaps in another interpreter)."""
        return self.packed.evaluate(inputs, self._values, parallel=self.parallel)
