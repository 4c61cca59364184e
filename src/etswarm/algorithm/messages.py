"""Layout of the ET status message (9-byte Kilobot payload, message type 1).

Every robot running ET re-broadcasts one status message every ``tx_period`` ticks. Bytes
(little-endian, ``uint8`` each):

=====  ==========================  ==============================================
byte   placed robot (Inactive ..   Queued / Search robot
       Leader)
=====  ==========================  ==============================================
0-1    robot ID (uint16)           robot ID (uint16)
2      state code (see states)     state code
3      tag X (int8)                queue rank (``release``), low byte
4      tag Y (int8)                queue rank, high byte
5      timestep TS (uint8,         hops to the robots placed on the
       255 at most)                target (after a regeneration, see
                                   ``release``; 255 = no way known)
6      offset x from the site's    a searcher's bits: ANCHORED_BIT when
       centre (int8, units of      it hears a stationary robot,
       0.5 mm, see ``offsets``)    YIELDING_BIT while it yields to
                                   another searcher, INSIDE_BIT while
                                   its readings place it in a hole
                                   (``hole_watch``); a Queued robot's
                                   release hold left (units of
                                   HOLD_UNIT_TICKS, see ``release``)
7      neighbour-site bits (bit k  robots released so far, low byte
       = a robot holds the site in
       lattice direction k)
8      offset y (int8, 0.5 mm)     robots released so far, high byte
=====  ==========================  ==============================================

Unless ``ETParams.status_signature`` is "off", the high four bits of byte 2 carry
``status_nibble`` of the sender's target signature (the state code keeps the low four).

Election message (kind 2; Danger and Leader robots): bytes 0-1 robot ID, 2-3 lowest ID
heard (the leader candidate), 4 hops from it, 5-6 parent ID (0xFFFF: none), 7-8 robots
in this robot's subtree. Target message (kind 3; relayed for a while after a scaled target
is adopted): 0-1 robot ID, 2 epoch, 3-4 the target's code (bits 0-12 n, the cells of
scale(bitmap, n); bits 13-15 its turns of 60°, ``placement_turns``), 5 tx, 6 ty (int8
translation, tags), 7-8 leader ID. With census ``walk``, electing robots that hold a tag
send their status instead of their election message every other period while a walking
Leader (status with state Leader) has been heard lately, so the walker learns their tags.
Silent-sites message (kind 4; electing robots that know of placed robots that fell
silent, every third period instead of their election message, see ``silent``): 0-1 robot
ID, 2 tags that follow (1-2), 3-8 up to two tags of three bytes: int8 X, Y and the mask
of the lattice directions from the site where robots are known to be alive; the epoch
elected for is in the type byte as for an election.
Held-sites message (kind 5; placed robots, every ``held_gossip_every`` periods instead of
their status, see ``site_memory``): 0-1 robot ID, 2 chunk index c, 3 the signature of
the sender's target (``target_signature`` of its n and placement), 4-8 the 40 sites
c * 40 .. c * 40 + 39 of the sender's held-site memory (row-major over the memory window of
its target; bit b of byte 4 + b // 8 for site c * 40 + b); the epoch is in the type byte as
for a status. Two remnants of one damage both elect for the same epoch, each with its own
target and memory window: the signature keeps one remnant's chunks out of the other's
memories. A receiver that has the sender in its table takes the message's distance as
a fresh reading of it, so neighbour counts and localisation lose no readings.
Extent message (kind 6; electing robots, every third period instead of their election
message for a while after their extent last grew, see ``extent``): 0-1 robot ID, 2-7 the
least and greatest tag X, Y and X - Y of the remnant heard of so far (int8 each), 8 unused;
the epoch elected for is in the type byte.
Watch message (kind 7; placed robots on a hole's edge that know a searcher was seen in the
hole lately, every third period instead of their status, see ``hole_watch``): 0-1 robot
ID, 2-3 a searcher's ID (0xFFFF: none), 4 how long ago it was seen in the hole (whole
seconds, 255 at most), 5-7 a second searcher the same way, 8 unused; the epoch is in the
type byte as for a status.

The target epoch a status belongs to is in its type byte (mod 32). TS is the paper's
gradient, a few tens at most on the library's shapes (39 on bigdisc), so one byte holds it.

The release count floods as a maximum among Queued robots, so the repository releases
no more robots than the target needs. ``messages`` holds only constants and
numba helpers so the controller can encode and decode without allocation.
"""

from __future__ import annotations

from numba import njit

#: Message kinds, in the low 3 bits of the kilolib type byte; the high 5 bits carry the
#: target epoch (mod 32) the message belongs to (for an election: the epoch elected for).
MSG_STATUS = 1
MSG_ELECT = 2
MSG_TARGET = 3
MSG_SILENT = 4
MSG_HELD = 5
MSG_EXTENT = 6
MSG_WATCH = 7
KIND_MASK = 0x07
EPOCH_SHIFT = 3

PAYLOAD_BYTES = 9
#: Sites of the held-site memory per held-sites message (bytes 4-8).
CHUNK_SITES = 40
#: First byte of those sites; byte 3 is the target's signature.
CHUNK_FIRST_BYTE = 4

#: Byte 6 of a searcher's status: it hears a stationary robot; it yields to a searcher.
ANCHORED_BIT = 1
YIELDING_BIT = 2
#: ... its readings place it in a hole of the shape (``hole_watch.localises_in_hole``).
INSIDE_BIT = 4
#: Byte 6 of a Queued robot's status counts its release hold in units of this many ticks.
HOLD_UNIT_TICKS = 32


@njit(inline="always")
def put_u16(buf, offset, value):  # type: ignore[no-untyped-def]
    """Write ``value`` (0..65535) little-endian at ``buf[offset:offset+2]``."""
    buf[offset] = value & 0xFF
    buf[offset + 1] = (value >> 8) & 0xFF


@njit(inline="always")
def get_u16(buf, offset):  # type: ignore[no-untyped-def]
    """Read a little-endian uint16 from ``buf[offset:offset+2]``."""
    return int(buf[offset]) | (int(buf[offset + 1]) << 8)


@njit(inline="always")
def put_i8(buf, offset, value):  # type: ignore[no-untyped-def]
    """Write a signed byte (-128..127) at ``buf[offset]`` (two's complement)."""
    buf[offset] = value & 0xFF


@njit(inline="always")
def get_i8(buf, offset):  # type: ignore[no-untyped-def]
    """Read a signed byte from ``buf[offset]``."""
    v = int(buf[offset])
    return v - 256 if v >= 128 else v


@njit(inline="always")
def target_signature(n, tx, ty):  # type: ignore[no-untyped-def]
    """One byte that tells targets apart: of the cell count ``n`` of scale(bitmap, n) and
    its placement ``(tx, ty)`` (tags), as every robot of a remnant learnt them from its
    Leader's target message. Two targets that differ get different signatures but for
    one pair in 256."""
    h = (n & 0xFFFF) * 0x9E37 + (tx & 0xFF) * 0x85EB + (ty & 0xFF) * 0xC2B3
    h ^= h >> 11
    h = (h * 0x2C1B) & 0xFFFFFF
    return (h ^ (h >> 8) ^ (h >> 16)) & 0xFF


@njit(inline="always")
def status_nibble(signature):  # type: ignore[no-untyped-def]
    """The four bits of a target signature (``target_signature``) that a status carries in
    the high half of its byte 2 (``ETParams.status_signature``): two different targets
    share them once in 16."""
    return (signature ^ (signature >> 4)) & 0x0F
