"""A model's cam contacts in MJCF: the cam and follower geoms on their bodies, and how they collide:
one explicit contact pair per cam geom, or, for a flat face on facets, a contype/conaffinity bit of
the cam's own (adapters.mujoco.cams, CamPair.mask) with the pair's condim, solref and solimp on both
geoms (MuJoCo mixes two equal values into the same numbers)."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

from adapters.mujoco.cams import CamPair, Geom
from adapters.mujoco.equalities import num

CONTACT_RGBA = "0.9 0.5 0.3 1"


def cam_geoms(elements: dict[str, ET.Element], cams: list[CamPair], solref: str, solimp: str) -> None:
    """Every cam's geoms and its follower's on their bodies' elements, with their collision bit
    where they collide by bits."""
    for pair in cams:
        for geom in pair.cam:
            _geom(elements[geom.body], geom, _bits(pair, True, solref, solimp))
        _geom(elements[pair.follower.body], pair.follower, _bits(pair, False, solref, solimp))


def contact_pairs(root: ET.Element, cams: list[CamPair], solref: str, solimp: str) -> None:
    """One contact pair per cam facet, all on the one follower geom (a cam colliding by bits has none)."""
    paired = [pair for pair in cams if not pair.mask]
    if not paired:
        return
    contact = ET.SubElement(root, "contact")
    for pair in paired:
        for k, piece in enumerate(pair.cam):
            ET.SubElement(
                contact,
                "pair",
                name=pair.name if len(pair.cam) == 1 else f"{pair.name}_{k}",
                geom1=piece.name,
                geom2=pair.follower.name,
                condim="1",
                solref=solref,
                solimp=solimp,
            )


def cam_flags(cams: list[CamPair]) -> dict[str, str]:
    """The option flags cams colliding by bits need: no parent filter, which explicit pairs never
    pass through either (only the cams' geoms collide at all: the default contype and conaffinity
    are 0)."""
    return {"filterparent": "disable"} if any(pair.mask for pair in cams) else {}


def _bits(pair: CamPair, cam: bool, solref: str, solimp: str) -> dict[str, str]:
    """A cam geom's (`cam`) or its follower's collision attributes where they collide by bits; none
    for explicit pairs."""
    if not pair.mask:
        return {}
    bit = str(pair.mask)
    return {
        "contype": bit if cam else "0",
        "conaffinity": "0" if cam else bit,
        "condim": "1",
        "solref": solref,
        "solimp": solimp,
    }


def _geom(body: ET.Element, geom: Geom, collision: dict[str, str]) -> None:
    half = geom.angle / 2.0
    place = {"pos": num(*geom.pos, 0.0), "quat": num(math.cos(half), 0.0, 0.0, math.sin(half))}
    if geom.fromto is not None:
        x1, y1, x2, y2 = geom.fromto
        place = {"fromto": num(x1, y1, 0.0, x2, y2, 0.0)}
    attrs = {"name": geom.name, "type": geom.kind, "size": num(*geom.size), **place, "rgba": CONTACT_RGBA}
    attrs.update(collision)
    ET.SubElement(body, "geom", attrs)
