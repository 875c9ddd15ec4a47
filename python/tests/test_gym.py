"""The Gymnasium environment."""

import numpy as np
import pytest

gym = pytest.importorskip("gymnasium")
from gymnasium.utils.env_checker import check_env  # noqa: E402

from rover.gym import RoverEnv  # noqa: E402


@pytest.fixture
def env(data):
    return RoverEnv(data / "slip_rough.toml", steps_per_action=2, max_steps=5)


def test_the_environment_passes_gymnasiums_checks(env):
    check_env(env, skip_render_check=True)


def test_spaces_come_from_the_rover(env):
    assert env.action_space.shape == (4,)
    assert np.all(env.action_space.high == 1.29)
    assert env.observation_space.shape == (20,)


def test_a_seeded_episode_repeats_and_another_seed_gives_other_ground(env):
    def episode(seed):
        obs, _ = env.reset(seed=seed)
        total, out = 0.0, [obs]
        for _ in range(5):
            obs, r, terminated, truncated, _ = env.step(np.full(4, 0.3))
            total += r
            out.append(obs)
            if terminated or truncated:
                break
        return total, np.array(out), truncated

    a, b, c = episode(1), episode(1), episode(2)
    assert a[2]
    assert a[0] == b[0] and np.array_equal(a[1], b[1])
    assert not np.array_equal(a[1], c[1])
