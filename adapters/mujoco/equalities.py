"""The MJCF equality section: loops as site `connect`s, laws as `joint` equalities (or fixed tendons
and a `tendon` equality when more than two joints take part).

MuJoCo's joint equality reads y - y0 = a0 + a1 (x - x0) + ... + a4 (x - x0)^4 for joint1 = y and
joint2 = x (the tendon equality likewise on tendon lengths); every reference here is 0 (the model is
written at the assembled poses). A law c1 q1 + k P(c) + const = 0, with P(c) = p1 c + ... + p4 c^4
the clock's term (linear: P(c) = c), becomes joint1 = q1, joint2 = the clock and
a0 = -const / c1, an = -k pn / c1. With more tree joints, tendon1 is the fixed tendon sum cj qj and
tendon2 the clock alone (a tendon equality of one tendon when the law is linear in the clock).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

from adapters.mujoco.laws import QUARTIC, Law
from adapters.mujoco.tree import Tree
from scenarios.bodies import Point


def num(*values: float) -> str:
    return " ".join(repr(float(v)) for v in values)


def polycoef(a0: float, scale: float, powers: tuple[float, ...]) -> str:
    """a0, then scale * p1 ... scale * p4 (zeros beyond the law's degree)."""
    coefficients = [a0, *(scale * p for p in powers)]
    return num(*coefficients, *[0.0] * (QUARTIC + 1 - len(coefficients)))


def _site(elements: dict[str, ET.Element], point: Point, name: str) -> str:
    ET.SubElement(elements[point.body], "site", name=name, pos=num(*point.local, 0.0))
    return name


def equalities(root: ET.Element, elements: dict[str, ET.Element], tree: Tree, laws: list[Law]) -> None:
    """The <equality> section (and the fixed tendons the laws need) under `root`."""
    equality = ET.SubElement(root, "equality")
    tendons: ET.Element | None = None
    for loop in tree.closures:
        site1 = _site(elements, loop.p_i, f"{loop.name}_i")
        site2 = _site(elements, loop.p_j, f"{loop.name}_j")
        ET.SubElement(equality, "connect", name=loop.name, site1=site1, site2=site2)
    for law in laws:
        terms = law.terms()
        const = law.form.const
        clock = law.clock.joint if law.clock is not None else None
        if len(terms) <= 2:
            (joint1, c1), *rest = terms
            attrs = {"name": law.name, "joint1": joint1}
            coefficients = polycoef(-const / c1, 0.0, ())
            if rest:
                joint2, k = rest[0]
                attrs["joint2"] = joint2
                powers = law.powers if joint2 == clock else (1.0,)
                coefficients = polycoef(-const / c1, -k / c1, powers)
            attrs["polycoef"] = coefficients
            ET.SubElement(equality, "joint", attrs)
            continue
        if tendons is None:
            tendons = ET.Element("tendon")
            root.insert(list(root).index(equality), tendons)
        linear = law.linear or clock is None
        fixed = ET.SubElement(tendons, "fixed", name=law.name)
        for joint, coef in terms:
            if linear or joint != clock:
                ET.SubElement(fixed, "joint", joint=joint, coef=num(coef))
        attrs = {"name": law.name, "tendon1": law.name, "polycoef": polycoef(-const, 0.0, ())}
        if not linear:
            driver = ET.SubElement(tendons, "fixed", name=f"{law.name}_clock")
            ET.SubElement(driver, "joint", joint=str(clock), coef="1.0")
            k = law.form.coefs[str(clock)]
            attrs.update(tendon2=f"{law.name}_clock", polycoef=polycoef(-const, -k, law.powers))
        ET.SubElement(equality, "tendon", attrs)
