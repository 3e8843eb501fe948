"""Who loves whom, who holds whose hand: the relationship logic of Falling for You.

`Romance` pre-allocates its parts in the scene's `Assembly` (an attraction
pair from every hand of every lover to every hand of the beloved, a link
spring for every pair of hands that may ever hold, a heart balloon per
couple and per baby with a string to each hand it may be tied to) and
switches them between engine steps: it reaches out (the nearest free hand
of each lover toward the beloved), links hands that meet, raises balloons,
brings babies, and lets go of links pulled harder than the break force.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError
from sinews.scenes.assembly import Assembly, Part
from sinews.scenes.dolls import HANDS
from sinews.scenes.messages import SceneEvent
from sinews.scenes.world import World
from sinews.springmass import Body

__all__ = ["BALLOON_MASS", "Romance", "RomanceTuning"]

BALLOON_MASS = 2.0
"""Kilograms of a heart balloon."""
_STRING = (0.8, 300.0)
"""Rest length (m) and strength (N/m) of a balloon's string."""
_LINK_LENGTH = 0.06
"""Metres between two held hands."""
_PARK = np.array([1000.0, -1000.0])
_RED, _PINK = (220, 36, 60), (244, 120, 160)


@dataclass(frozen=True)
class RomanceTuning:
    """Forces and timings of love (newtons, metres, seconds).

    Attributes:
        attraction: pull on a lover's hand toward its beloved's hand.
        reach: hands further apart than this do not pull.
        link_distance: hands closer than this link.
        link_strength: newtons per metre of the link spring.
        break_force: a link lets go when its spring pulls harder than this.
        lift: a couple's balloon lifts this many times the couple's weight
            (a baby's balloon, twice the baby's).
        baby_delay: seconds a couple holds hands before a baby comes.
        heartbreak: seconds a broken-up couple cannot link again.
    """

    attraction: float = 30.0
    reach: float = 2.2
    link_distance: float = 0.12
    link_strength: float = 250.0
    break_force: float = 110.0
    lift: float = 2.0
    baby_delay: float = 2.5
    heartbreak: float = 6.0


@dataclass
class _Couple:
    balloon: int
    strings: dict[int, int]  # hand node -> string spring
    since: float | None = None  # when they last started holding hands
    apart_until: float = -1.0
    baby: int | None = None


@dataclass
class _Baby:
    part: Part
    balloon: int
    strings: dict[int, int]
    born: bool = False


@dataclass(frozen=True)
class _Link:
    hands: tuple[int, int]
    dolls: tuple[int, int]
    edge: int


@dataclass
class Romance:
    """The relationships of a Falling for You scene and the parts that show them.

    Attributes:
        loves: (D, D) bool, ``loves[a, b]``: grown-up doll a is attracted to doll b.
        hands: (C, 2) node of each doll's left and right hand (grown-ups, then babies).
        tuning: forces and timings.
        couples_formed: links made between grown-ups so far.
    """

    loves: npt.NDArray[np.bool_]
    hands: npt.NDArray[np.int64]
    tuning: RomanceTuning
    _links: list[_Link]
    _pursuits: list[tuple[int, int, list[tuple[int, int, int]]]]
    _couples: dict[tuple[int, int], _Couple]
    _babies: list[_Baby]
    _held: dict[int, int] = field(default_factory=dict)  # hand node -> index in _links
    couples_formed: int = 0

    @classmethod
    def build(
        cls,
        rng: np.random.Generator,
        assembly: Assembly,
        dolls: list[tuple[Part, Body]],
        n_adults: int,
        tuning: RomanceTuning,
        loves: npt.ArrayLike | None = None,
    ) -> Romance:
        """Choose who loves whom and add every spare part to ``assembly``.

        Unless ``loves`` says, each grown-up loves each other one with
        probability 0.35, and doll 0 and one other always love each other,
        so the story has a couple.

        Args:
            rng: who loves whom.
            assembly: where the dolls already are.
            dolls: (part, body) of every doll, grown-ups first, then babies.
            n_adults: how many of ``dolls`` are grown-ups.
            tuning: forces and timings.
            loves: (n_adults, n_adults) bool, who loves whom, or None to choose.
        """
        hands = np.array([[p.nodes.start + b.index(h) for h in HANDS] for p, b in dolls])
        if loves is None:
            chosen = rng.random((n_adults, n_adults)) < 0.35
            partner = int(rng.integers(1, n_adults))
            chosen[0, partner] = chosen[partner, 0] = True
        else:
            chosen = np.array(loves, dtype=bool)
            if chosen.shape != (n_adults, n_adults):
                raise SinewsError(f"loves must have shape {(n_adults, n_adults)}")
        np.fill_diagonal(chosen, False)
        loves = chosen
        pursuits = []
        for a, b in zip(*np.nonzero(loves), strict=True):
            pairs = [
                (assembly.add_attraction(ha, hb, tuning.attraction, tuning.reach), ha, hb)
                for ha, hb in itertools.product(hands[a].tolist(), hands[b].tolist())
            ]
            pursuits.append((int(a), int(b), pairs))
        links = []
        for a, b in itertools.combinations(range(len(dolls)), 2):
            if a < n_adults:  # babies only ever hold a grown-up's hand
                for ha, hb in itertools.product(hands[a].tolist(), hands[b].tolist()):
                    edge = assembly.add_spring(
                        ha, hb, _LINK_LENGTH, tuning.link_strength, active=False
                    )
                    links.append(_Link((ha, hb), (a, b), edge))
        load = [float(body.mass @ body.weight) for _, body in dolls]
        couples = {}
        for a, b in itertools.combinations(range(n_adults), 2):
            lift = tuning.lift * (load[a] + load[b])
            ties = [*hands[a].tolist(), *hands[b].tolist()]
            couples[(a, b)] = _Couple(*_balloon(assembly, f"balloon{a}_{b}", lift, _RED, ties))
        babies = []
        for c in range(n_adults, len(dolls)):
            ties = hands[c].tolist()
            balloon, strings = _balloon(assembly, f"balloon{c}", 2.0 * load[c], _PINK, ties)
            babies.append(_Baby(dolls[c][0], balloon, strings))
        return cls(loves, hands, tuning, links, pursuits, couples, babies)

    def is_single(self, doll: int) -> bool:
        """Whether ``doll`` holds nobody's hand."""
        return not any(h in self._held for h in self.hands[doll].tolist())

    def link_tension(self, world: World) -> dict[tuple[int, int], float]:
        """Newtons each held link pulls with, by its pair of hand nodes."""
        tension = {}
        for index in set(self._held.values()):
            link = self._links[index]
            a, b = link.hands
            length = float(np.hypot(*(world.positions[b] - world.positions[a])))
            pull = world.strength[link.edge] * (length - world.rest_length[link.edge])
            tension[link.hands] = float(pull)
        return tension

    def reach_out(self, world: World) -> None:
        """Switch on, for each lover, the pull of its nearest free hand toward the beloved."""
        strengths = world.attraction_strength
        for a, b, pairs in self._pursuits:
            for index, _, _ in pairs:
                strengths[index] = 0.0
            couple = self._couples[(min(a, b), max(a, b))]
            if world.time < couple.apart_until or self._holding(a, b):
                continue
            best, nearest = None, self.tuning.reach
            for index, ha, hb in pairs:
                distance = float(np.hypot(*(world.positions[hb] - world.positions[ha])))
                if ha not in self._held and distance < nearest:
                    best, nearest = index, distance
            if best is not None:
                strengths[best] = self.tuning.attraction

    def hold_and_let_go(self, world: World, events: list[SceneEvent]) -> None:
        """Break links pulled too hard, link mutual lovers' hands that meet, bring babies."""
        for hands, pull in self.link_tension(world).items():
            if pull > self.tuning.break_force:
                self._let_go(world, self._held[hands[0]], events)
        for a, b in itertools.combinations(range(len(self.loves)), 2):
            if self.loves[a, b] and self.loves[b, a]:
                self._meet(world, a, b, events)
        for parents, couple in self._couples.items():
            due = couple.since is not None and world.time >= couple.since + self.tuning.baby_delay
            if due and couple.baby is None:
                self._bring_baby(world, parents, events)

    def tidy(
        self, world: World, camera: npt.NDArray[np.float64], far: float, events: list[SceneEvent]
    ) -> None:
        """Put away balloons and babies that floated further than ``far`` metres from the camera."""
        for couple in self._couples.values():
            if couple.since is None and _gone(world, couple.balloon, camera, far):
                world.park(couple.balloon, at=_PARK)
        for j, baby in enumerate(self._babies):
            c = len(self.loves) + j
            nodes = baby.part.nodes
            if baby.born and self.is_single(c) and _gone(world, nodes.start, camera, far):
                world.park(nodes, at=world.shape[nodes] + _PARK)
                world.switch(baby.part.edges, on=False)
                world.park(baby.balloon, at=_PARK)
                world.switch(list(baby.strings.values()), on=False)
                baby.born = False
                events.append(SceneEvent("lost", (c,)))

    def _holding(self, a: int, b: int) -> bool:
        """Whether dolls ``a`` and ``b`` hold each other's hand."""
        return any(
            self._links[self._held[h]].dolls in ((a, b), (b, a))
            for h in self.hands[a].tolist()
            if h in self._held
        )

    def _link(self, world: World, ha: int, hb: int) -> None:
        index = next(k for k, link in enumerate(self._links) if set(link.hands) == {ha, hb})
        world.switch(self._links[index].edge, on=True)
        self._held[ha] = self._held[hb] = index

    def _meet(self, world: World, a: int, b: int, events: list[SceneEvent]) -> None:
        """Link a free hand of ``a`` with a free hand of ``b`` if they touch; raise the balloon."""
        couple = self._couples[(a, b)]
        if world.time < couple.apart_until or self._holding(a, b):
            return
        for ha, hb in itertools.product(self.hands[a].tolist(), self.hands[b].tolist()):
            if ha in self._held or hb in self._held:
                continue
            if np.hypot(*(world.positions[hb] - world.positions[ha])) < self.tuning.link_distance:
                self._link(world, ha, hb)
                self.couples_formed += 1
                couple.since = world.time
                _raise(world, couple.balloon, couple.strings, (ha, hb))
                events += [SceneEvent("link", (a, b)), SceneEvent("balloon", (a, b))]
                return

    def _let_go(self, world: World, index: int, events: list[SceneEvent]) -> None:
        link = self._links[index]
        world.switch(link.edge, on=False)
        for hand in link.hands:
            del self._held[hand]
        events.append(SceneEvent("break", link.dolls))
        couple = self._couples.get(link.dolls)
        if couple is not None:  # two grown-ups: their balloon floats away
            couple.since = None
            couple.apart_until = world.time + self.tuning.heartbreak
            world.switch(list(couple.strings.values()), on=False)

    def _bring_baby(self, world: World, parents: tuple[int, int], events: list[SceneEvent]) -> None:
        """A baby appears holding a parent's free hand, its own balloon on its other hand."""
        free = [h for p in parents for h in self.hands[p].tolist() if h not in self._held]
        unborn = [j for j, baby in enumerate(self._babies) if not baby.born]
        if not free or not unborn:
            return
        baby, c = self._babies[unborn[0]], len(self.loves) + unborn[0]
        parent_hand = free[0]
        # a parent's right hand (column 1) takes the baby's left (column 0), and vice versa
        parent_side = int(parent_hand in self.hands[:, 1])
        holding, other = int(self.hands[c, 1 - parent_side]), int(self.hands[c, parent_side])
        nodes = baby.part.nodes
        offset = world.positions[parent_hand] - world.shape[holding] + [0.0, -0.04]
        world.reveal(nodes, world.shape[nodes] + offset, world.velocities[parent_hand])
        world.switch(baby.part.edges, on=True)
        self._link(world, holding, parent_hand)
        _raise(world, baby.balloon, baby.strings, (other,))
        baby.born = True
        self._couples[parents].baby = c
        events.append(SceneEvent("baby", (*parents, c)))


def _balloon(
    assembly: Assembly, name: str, load: float, color: tuple[int, int, int], hands: list[int]
) -> tuple[int, dict[int, int]]:
    """A parked heart balloon lifting ``load`` kg against gravity, with a string to each hand."""
    node = assembly.add_node(
        name,
        (float(_PARK[0]), float(_PARK[1])),
        mass=BALLOON_MASS,
        radius=0.22,
        color=color,
        weight=-load / BALLOON_MASS,
        shape="heart",
        active=False,
    )
    strings = {h: assembly.add_spring(node, h, *_STRING, active=False) for h in hands}
    return node, strings


def _raise(world: World, balloon: int, strings: dict[int, int], hands: tuple[int, ...]) -> None:
    """Show ``balloon`` above ``hands``, tied to them."""
    held = list(hands)
    above = world.positions[held].mean(axis=0) + np.array([0.0, _STRING[0]])
    world.reveal(balloon, above, world.velocities[held].mean(axis=0))
    world.switch([strings[h] for h in held], on=True)


def _gone(world: World, node: int, camera: npt.NDArray[np.float64], far: float) -> bool:
    distance = np.hypot(*(world.positions[node] - camera))
    return bool(world.node_visible[node]) and bool(distance > far)
