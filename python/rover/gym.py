"""A Gymnasium environment over a step-wise run (needs gymnasium).

The action is one motor torque per wheel [N·m], bounded by the rover's
limits, added to the scenario's own loops (a scenario without
``[control.speed]`` leaves the torques to the agent alone). The
observation is the state [x; w] (2N values, SI units). Each episode's
terrain is drawn anew from the episode's seed when the scenario's terrain
is random, so a seeded ``reset`` gives the same ground and the same run.
"""

from __future__ import annotations

import copy
import os
import tomllib
from typing import Any, Callable, Mapping, Optional, Union

import numpy as np

from . import RunFailed, Simulation, _require, load

gym = _require("gymnasium", "rover.gym")

#: reward(previous row, row) -> float; rows by trajectory column name.
Reward = Callable[[dict, dict], float]


def forward_progress(previous: dict, row: dict) -> float:
    """The default reward: metres gained along X in the step."""
    return row["X"] - previous["X"]


class RoverEnv(gym.Env):
    """``RoverEnv(scenario, rover=None, reward=forward_progress,
    steps_per_action=1, max_steps=200)``: ``rover`` (a name, a path, TOML
    text, a dict or a loaded rover; None: the scenario's own); each action holds for
    ``steps_per_action`` output intervals; an episode ends when the run
    fails (terminated, reward ``failure_reward``) or after ``max_steps``
    actions (truncated)."""

    metadata = {"render_modes": []}

    def __init__(
        self,
        scenario: Union[str, os.PathLike, Mapping[str, Any]],
        rover=None,
        reward: Reward = forward_progress,
        steps_per_action: int = 1,
        max_steps: int = 200,
        failure_reward: float = -1.0,
    ):
        if isinstance(scenario, Mapping):
            self._scenario = copy.deepcopy(dict(scenario))
        elif isinstance(scenario, os.PathLike) or "\n" not in scenario:
            with open(scenario, "rb") as f:
                self._scenario = tomllib.load(f)
        else:
            self._scenario = tomllib.loads(scenario)
        self._rover = None if rover is None else load(rover)
        self.reward_fn = reward
        self.steps_per_action = steps_per_action
        self.max_steps = max_steps
        self.failure_reward = failure_reward
        self.sim = Simulation(self._rover, self._scenario)
        limits = np.array(
            (self._rover or load(self._scenario["rover"])).max_torque, dtype=np.float64
        )
        self.action_space = gym.spaces.Box(-limits, limits, dtype=np.float64)
        n2 = 2 * self.sim.dof
        self.observation_space = gym.spaces.Box(-np.inf, np.inf, shape=(n2,), dtype=np.float64)
        self._action = np.zeros(self.sim.wheel_count)
        self._steps = 0
        self._row: dict = {}

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        terrain = self._scenario.get("terrain", {})
        if terrain.get("kind") == "random":
            scenario = copy.deepcopy(self._scenario)
            scenario["terrain"]["seed"] = int(self.np_random.integers(0, 2**31 - 1))
            self.sim = Simulation(self._rover, scenario)
        else:
            self.sim.reset()
        self._steps = 0
        self._row = self.sim.row
        return self.sim.state, {"t": self.sim.time}

    def step(self, action):
        np.copyto(self._action, np.clip(action, self.action_space.low, self.action_space.high))
        self.sim.set_torques(self._action)
        self._steps += 1
        truncated = self._steps >= self.max_steps
        try:
            self.sim.step(self.steps_per_action)
        except RunFailed as e:
            return self.sim.state, self.failure_reward, True, truncated, {"t": self.sim.time, "error": str(e)}
        row = self.sim.row
        reward = float(self.reward_fn(self._row, row))
        self._row = row
        return self.sim.state, reward, False, truncated, {"t": self.sim.time}
