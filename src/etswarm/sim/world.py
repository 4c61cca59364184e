"""The world: every robot's state as arrays, robot ID = index.

Only the simulator, the recorder, the measures and the viewer read ``pos`` and
``heading``; controllers see the radio inbox and write motors, LED and radio out.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from etswarm.errors import EtswarmError
from etswarm.seeding import stream
from etswarm.sim.fpmath import normal_array
from etswarm.sim.params import SimParams

#: Motor codes (World.motor).
STOP, FORWARD, LEFT, RIGHT = 0, 1, 2, 3

#: Payload bytes per message (kilolib ``message_t.data``).
PAYLOAD_BYTES = 9

#: Names of the entries of ``World.counters`` (int64 running totals).
COUNTER_NAMES = (
    "messages_sent",  # broadcasts made
    "messages_delivered",  # copies put into an inbox
    "messages_lost",  # copies dropped by the loss probability
    "inbox_overflow",  # copies dropped because the receiver's inbox was full
    "pushes",  # pairwise overlap resolutions
    "push_pass_limit",  # ticks whose collision phase hit max_push_passes
    "collision_checks",  # robots examined by the collision phase (all passes)
)


class World:
    """All robot state of one swarm (N robots; shapes given per array).

    Attributes:
        pos: (N, 2) float64 mm, robot centres.
        heading: (N,) float64 rad, 0 = +x, counter-clockwise positive.
        motor: (N,) int8, 0 stop, 1 forward, 2 turn left (CCW), 3 turn right (CW).
        led: (N,) uint8, controller-defined code (ET: the state index).
        alive: (N,) bool; a dead robot is an obstacle only (no radio, no control, no motors).
        present: (N,) bool; an absent robot is out of the world (no collisions, no radio).
        speed: (N,) float64 mm/s forward speed (per-robot calibration).
        turn_rate: (N,) float64 rad/s pivot rate (per-robot calibration).
        tx_phase: (N,) int64 in [0, tx_period): robot i broadcasts on ticks with
            ``tick % tx_period == tx_phase[i]`` while ``out_on[i]``.
        out_on: (N,) bool, robot broadcasts.  out_type: (N,) uint8.  out_data: (N, 9) uint8.
        in_count: (N,) int32 messages in the inbox this tick (<= K); with a message delay
            (``SimParams.message_delay_ticks``), between ticks: the next tick's inbox.
        in_type: (N, K) uint8.  in_data: (N, K, 9) uint8.
        in_dist: (N, K) float32 mm, measured centre distance of each message's sender.
        counters: (7,) int64 running totals, named by :data:`COUNTER_NAMES`.
        tick: int, the world clock (ticks since the start).
    """

    def __init__(self, n: int, inbox_capacity: int = 32) -> None:
        if n < 0:
            raise EtswarmError(f"number of robots must be >= 0, got {n}")
        if inbox_capacity < 1:
            raise EtswarmError(f"inbox capacity must be >= 1, got {inbox_capacity}")
        k = int(inbox_capacity)
        self.pos = np.zeros((n, 2), dtype=np.float64)
        self.heading = np.zeros(n, dtype=np.float64)
        self.motor = np.zeros(n, dtype=np.int8)
        self.led = np.zeros(n, dtype=np.uint8)
        self.alive = np.ones(n, dtype=np.bool_)
        self.present = np.ones(n, dtype=np.bool_)
        self.speed = np.full(n, 7.0)
        self.turn_rate = np.full(n, np.deg2rad(13.0))
        self.tx_phase = np.zeros(n, dtype=np.int64)
        self.out_on = np.zeros(n, dtype=np.bool_)
        self.out_type = np.zeros(n, dtype=np.uint8)
        self.out_data = np.zeros((n, PAYLOAD_BYTES), dtype=np.uint8)
        self.in_count = np.zeros(n, dtype=np.int32)
        self.in_type = np.zeros((n, k), dtype=np.uint8)
        self.in_data = np.zeros((n, k, PAYLOAD_BYTES), dtype=np.uint8)
        self.in_dist = np.zeros((n, k), dtype=np.float32)
        self.counters = np.zeros(len(COUNTER_NAMES), dtype=np.int64)
        self.tick = 0

    @property
    def n(self) -> int:
        """Number of robots (present or not)."""
        return int(self.pos.shape[0])

    @property
    def inbox_capacity(self) -> int:
        """K, the number of messages a robot can receive per tick."""
        return int(self.in_type.shape[1])

    @classmethod
    def from_positions(
        cls,
        pos: np.ndarray | Sequence[Sequence[float]],
        heading: np.ndarray | Sequence[float] | None = None,
        params: SimParams | None = None,
        seed: int = 0,
    ) -> World:
        """A world with robots at ``pos`` ((N, 2) mm) facing ``heading`` ((N,) rad).

        Headings default to uniform random (placement stream). Per-robot speed and turn
        rate are drawn with the configured spread from a child of the "motion" stream,
        broadcast phases uniformly from a child of the "radio" stream, so they do not
        disturb the streams the simulator draws from while running.
        """
        params = params or SimParams()
        pos_arr = np.asarray(pos, dtype=np.float64)
        if pos_arr.ndim != 2 or pos_arr.shape[1] != 2:
            raise EtswarmError(f"positions must have shape (N, 2), got {pos_arr.shape}")
        if not np.all(np.isfinite(pos_arr)):
            raise EtswarmError("positions must be finite numbers")
        n = pos_arr.shape[0]
        world = cls(n, params.inbox_capacity)
        world.pos[:] = pos_arr
        if heading is None:
            world.heading[:] = stream(seed, "placement").spawn(1)[0].uniform(-np.pi, np.pi, n)
        else:
            h = np.asarray(heading, dtype=np.float64)
            if h.shape != (n,):
                raise EtswarmError(f"headings must have shape ({n},), got {h.shape}")
            world.heading[:] = h
        world.calibrate(params, seed)
        return world

    def calibrate(self, params: SimParams, seed: int) -> None:
        """(Re)draw speed, turn rate and broadcast phase of every robot (see from_positions)."""
        n = self.n
        motion = stream(seed, "motion").spawn(1)[0]
        speed_f = 1.0 + params.speed_spread * normals(motion, n, params.portable_math)
        turn_f = 1.0 + params.turn_rate_spread * normals(motion, n, params.portable_math)
        self.speed[:] = params.speed_mm_s * np.clip(speed_f, 0.1, 1.9)
        self.turn_rate[:] = np.deg2rad(params.turn_rate_deg_s) * np.clip(turn_f, 0.1, 1.9)
        radio = stream(seed, "radio").spawn(1)[0]
        self.tx_phase[:] = radio.integers(0, params.tx_period, n)

    def set_message(self, i: int, msg_type: int, payload: bytes | Sequence[int]) -> None:
        """Make robot ``i`` broadcast ``payload`` (at most 9 bytes) with type ``msg_type``.

        Shorter payloads are zero-padded. Raises EtswarmError for a larger payload, a type
        outside 0..255 or a byte outside 0..255.
        """
        data = bytes(payload) if not isinstance(payload, bytes) else payload
        if len(data) > PAYLOAD_BYTES:
            raise EtswarmError(
                f"message payload of robot {i} is {len(data)} bytes; at most {PAYLOAD_BYTES} fit"
            )
        if not 0 <= int(msg_type) <= 255:
            raise EtswarmError(f"message type of robot {i} must be in 0..255, got {msg_type}")
        self.out_data[i, :] = 0
        self.out_data[i, : len(data)] = np.frombuffer(data, dtype=np.uint8)
        self.out_type[i] = msg_type
        self.out_on[i] = True

    def clear_message(self, i: int) -> None:
        """Robot ``i`` stops broadcasting."""
        self.out_on[i] = False

    def kill(self, ids: int | Sequence[int] | np.ndarray) -> None:
        """Robots ``ids`` die: they stay as obstacles, silent and deaf, motors off."""
        self.alive[ids] = False
        self.motor[ids] = STOP
        self.out_on[ids] = False

    def remove(self, ids: int | Sequence[int] | np.ndarray) -> None:
        """Robots ``ids`` leave the world (and die): no collisions, no radio, not drawn."""
        self.kill(ids)
        self.present[ids] = False

    def state_arrays(self) -> dict[str, np.ndarray]:
        """The arrays that define the physical and visible state (for saving and comparing)."""
        return {
            "pos": self.pos,
            "heading": self.heading,
            "motor": self.motor,
            "led": self.led,
            "alive": self.alive,
            "present": self.present,
            "out_on": self.out_on,
            "out_type": self.out_type,
            "out_data": self.out_data,
        }

    def counter_dict(self) -> dict[str, int]:
        """The running counters by name."""
        return {name: int(v) for name, v in zip(COUNTER_NAMES, self.counters, strict=True)}


def normals(rng: np.random.Generator, n: int, portable: bool) -> np.ndarray:
    """``n`` standard normal draws ((n,) float64): by ``fpmath.normal_array`` when
    ``portable`` (the same bits on every machine), else numpy's."""
    return normal_array(rng, n) if portable else rng.standard_normal(n)
