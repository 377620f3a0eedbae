#!/usr/bin/env python3
"""Writes the shipped thin sections (granite, schist) from stated modal
compositions and grain-size distributions. Format and geometry rules: docs/sections.md.

Each section is a list of grains: mineral, centre and size in mm, Bunge Euler angles (crystal to
section frame) and optional twin and growth zones. Only what a petrographer would choose is written
here (where grains are, how big, how oriented); the grain outline, cleavage cracks and twin
lamellae follow at load from the mineral's crystallography.

Deterministic (fixed seeds, Python's random.Random, stdlib only), so the shipped files are
reproducible byte for byte:
    python3 assets/sections/generate_sections.py [--out DIR]
"""
import argparse
import json
import math
import os
import random

# The mineral library gains compositions ("plagioclase:An55", "olivine:Fo85"), plagioclase
# crystallography (habit, albite twins) and metamorphic minerals (almandine, microcline, ...) in
# stages. Until it has them, FULL_LIBRARY = False writes only what loads today: plain names, no
# albite twins, no zoning by composition, and no garnet. Set True once they exist and rerun.
FULL_LIBRARY = True


def plag(an):
    return "plagioclase:An%d" % an if FULL_LIBRARY else "plagioclase"


def r3(v):
    return round(v, 3)


def random_euler(rng):
    # Uniform orientations: φ1, φ2 uniform, cos Φ uniform (the Haar measure in Bunge angles;
    # Bunge 1982, "Texture Analysis in Materials Science", §2.3).
    return [round(rng.uniform(0, 360), 2), round(math.degrees(math.acos(rng.uniform(-1, 1))), 2),
            round(rng.uniform(0, 360), 2)]


def euler_from_frame(e1, e2, e3):
    # Bunge angles of the crystal frame whose axes e1, e2, e3 are given in the section frame
    # (rows of g = Z(φ2)X(Φ)Z(φ1)): Φ = acos e3z, φ1 = atan2(e3x, −e3y), φ2 = atan2(e1z, e2z).
    phi = math.degrees(math.atan2(math.hypot(e3[0], e3[1]), e3[2]))
    phi1 = math.degrees(math.atan2(e3[0], -e3[1])) % 360.0
    phi2 = math.degrees(math.atan2(e1[2], e2[2])) % 360.0
    return [round(phi1, 2), round(phi, 2), round(phi2, 2)]


def unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def euler_with_e3(rng, e3):
    # A frame with e3 along the given direction and e1 at a random angle about it.
    e3 = unit(e3)
    ref = [1.0, 0.0, 0.0] if abs(e3[0]) < 0.9 else [0.0, 1.0, 0.0]
    p = unit(cross(e3, ref))
    q = cross(e3, p)
    t = rng.uniform(0, 2 * math.pi)
    e1 = [math.cos(t) * p[i] + math.sin(t) * q[i] for i in range(3)]
    e2 = cross(e3, e1)
    return euler_from_frame(e1, e2, e3)


def scattered(rng, direction, scatter_deg):
    # The direction tilted by a normal deviate of scatter_deg in a random azimuth about it.
    d = unit(direction)
    ref = [0.0, 0.0, 1.0] if abs(d[2]) < 0.9 else [1.0, 0.0, 0.0]
    p = unit(cross(d, ref))
    q = cross(d, p)
    a, t = math.radians(rng.gauss(0, scatter_deg)), rng.uniform(0, 2 * math.pi)
    return [math.cos(a) * d[i] + math.sin(a) * (math.cos(t) * p[i] + math.sin(t) * q[i]) for i in range(3)]


class Placer:
    """Random sequential placement: each grain's centre keeps 0.4·(sᵢ + sⱼ) from every other
    centre (a hard-core process), largest grains first; grains that find no room after 80 tries
    are dropped. The map's weighted Voronoi cells then tile the gaps."""

    def __init__(self, rng, w, h):
        self.rng, self.w, self.h = rng, w, h
        self.big, self.small = [], {}
        self.cell = None

    def fits(self, x, y, s):
        for (bx, by, bs) in self.big:
            if math.hypot(x - bx, y - by) < 0.4 * (s + bs):
                return False
        cx, cy = int((x + self.w) // self.cell), int((y + self.h) // self.cell)
        for j in (cy - 1, cy, cy + 1):
            for i in (cx - 1, cx, cx + 1):
                for (bx, by, bs) in self.small.get((i, j), ()):
                    if math.hypot(x - bx, y - by) < 0.4 * (s + bs):
                        return False
        return True

    def place(self, sizes):
        # sizes: list of (size_mm, payload); returns [(x, y, size, payload)] in placement order.
        sizes = sorted(sizes, key=lambda t: -t[0])
        small_max = sizes[len(sizes) // 4][0] if sizes else 1.0
        self.cell = 0.8 * small_max
        out = []
        for s, payload in sizes:
            for _ in range(80):
                x = self.rng.uniform(-0.5 * self.w, 0.5 * self.w)
                y = self.rng.uniform(-0.5 * self.h, 0.5 * self.h)
                if self.fits(x, y, s):
                    if s > small_max:
                        self.big.append((x, y, s))
                    else:
                        key = (int((x + self.w) // self.cell), int((y + self.h) // self.cell))
                        self.small.setdefault(key, []).append((x, y, s))
                    out.append((x, y, s, payload))
                    break
        return out


def draw_sizes(rng, area_mm2, mode, fill=0.9):
    # Grains per mineral until its share of the area is met; sizes log-normal (median, σ of ln),
    # the usual description of igneous and metamorphic grain-size distributions (e.g. Higgins
    # 2006, "Quantitative Textural Measurements in Igneous and Metamorphic Petrology", ch. 5).
    out = []
    for name, fraction, median, sigma in mode:
        target, acc = fill * fraction * area_mm2, 0.0
        while acc < target:
            s = min(4.0 * median, max(0.25 * median, rng.lognormvariate(math.log(median), sigma)))
            acc += math.pi * 0.25 * s * s
            out.append((s, name))
    return out


def section(name, size, source, grains):
    return {"type": "section", "name": name, "thickness_um": 30, "size_mm": size, "source": source,
            "grains": grains}


def grain(mineral, x, y, s, euler, **extra):
    g = {"mineral": mineral, "centre_mm": [r3(x), r3(y)], "size_mm": r3(s), "euler_deg": euler}
    g.update(extra)
    return g


def granite(rng):
    # Monzogranite, IUGS QAP field 3b (Le Maitre et al. 2002, "Igneous Rocks: A Classification and
    # Glossary of Terms", fig. 2.4): quartz 30 %, K-feldspar 35 %, plagioclase 25 %, biotite 7 %,
    # muscovite 3 % by volume; medium-grained, 1-5 mm (Nesse 2012, "Introduction to Optical
    # Mineralogy", ch. 5 igneous textures).
    w, h = 20.0, 15.0
    kfs = "microcline" if FULL_LIBRARY else "orthoclase"
    mode = [("quartz", 0.30, 2.0, 0.35), (kfs, 0.35, 2.5, 0.4), ("plag", 0.25, 2.0, 0.35),
            ("biotite", 0.07, 1.0, 0.35), ("muscovite", 0.03, 0.9, 0.35)]
    grains = []
    for x, y, s, m in Placer(rng, w, h).place(draw_sizes(rng, w * h, mode)):
        e = random_euler(rng)
        if m == "quartz":
            grains.append(grain("quartz", x, y, s, e, aspect=1.0))  # anhedral, interstitial
        elif m == "plag":
            g = grain(plag(rng.randint(20, 32)), x, y, s, e)
            if FULL_LIBRARY:  # subhedral tablets with polysynthetic albite twins
                g.update(aspect=2.0, twin={"law": "albite", "lamella_mm": r3(rng.uniform(0.02, 0.06))})
            grains.append(g)
        elif m == kfs:
            g = grain(kfs, x, y, s, e)
            if rng.random() < 0.5:  # Carlsbad twins, common in granite K-feldspar
                g["twin"] = {"law": "carlsbad"}
            elif kfs == "microcline":  # the albite set of microcline's albite-pericline grid
                g["twin"] = {"law": "albite", "lamella_mm": r3(rng.uniform(0.01, 0.03))}
            grains.append(g)
        else:
            grains.append(grain(m, x, y, s, e))
    src = ("Generated by generate_sections.py: monzogranite mode (quartz 30, K-feldspar 35, plagioclase An20-32 25, "
           "biotite 7, muscovite 3 vol%) after Le Maitre et al. 2002, Igneous Rocks: A Classification and Glossary of "
           "Terms (QAP field 3b); log-normal grain sizes, median 1-2.5 mm (Nesse 2012, Introduction to Optical "
           "Mineralogy); random orientations")
    return section("granite", [w, h], src, grains)


def schist(rng):
    # Garnet-mica schist (pelitic, amphibolite facies): quartz 40 %, muscovite 25 %, biotite 15 %,
    # plagioclase 8 %, garnet porphyroblasts 10 % (1-3 mm), tourmaline 2 % (Yardley 1989, "An
    # Introduction to Metamorphic Petrology", ch. 3; Passchier & Trouw 2005, "Micro-tectonics",
    # ch. 4 for the foliation). The foliation strikes 15° from east, vertical; mica (001) lies in it
    # with 8° scatter, tourmaline [001] lies along the strike with 10° scatter.
    w, h = 12.0, 9.0
    mode = [("quartz", 0.40, 0.35, 0.3), ("muscovite", 0.25, 0.6, 0.3), ("biotite", 0.15, 0.55, 0.3),
            ("plag", 0.08, 0.35, 0.3), ("tourmaline", 0.02, 0.5, 0.3)]
    if FULL_LIBRARY:
        mode.append(("almandine", 0.10, 1.8, 0.3))
    strike = math.radians(15.0)
    along = [math.cos(strike), math.sin(strike), 0.0]
    normal = [-math.sin(strike), math.cos(strike), 0.0]
    grains = []
    for x, y, s, m in Placer(rng, w, h).place(draw_sizes(rng, w * h, mode)):
        if m in ("muscovite", "biotite"):
            grains.append(grain(m, x, y, s, euler_with_e3(rng, scattered(rng, normal, 8.0)), aspect=6.0))
        elif m == "tourmaline":
            grains.append(grain(m, x, y, s, euler_with_e3(rng, scattered(rng, along, 10.0)), aspect=4.0))
        elif m == "quartz":
            grains.append(grain(m, x, y, s, random_euler(rng), aspect=1.0))
        elif m == "plag":
            grains.append(grain(plag(30), x, y, s, random_euler(rng)))
        else:
            grains.append(grain(m, x, y, s, random_euler(rng)))
    src = ("Generated by generate_sections.py: garnet-mica schist, quartz 40, muscovite 25, biotite 15, garnet 10, "
           "plagioclase An30 8, tourmaline 2 vol%, after Yardley 1989, An Introduction to Metamorphic Petrology; foliation "
           "after Passchier & Trouw 2005, Micro-tectonics; micas (001) in a vertical foliation striking 15 deg from east"
           + ("" if FULL_LIBRARY else "; garnet omitted until the mineral library has almandine"))
    return section("schist", [w, h], src, grains)


SECTIONS = (("granite", granite, 7), ("schist", schist, 17))


def dump(sec):
    # One grain per line: the files stay small and diff line by line.
    head = {k: v for k, v in sec.items() if k != "grains"}
    lines = ["{"] + ["%s: %s," % (json.dumps(k), json.dumps(v)) for k, v in head.items()] + ['"grains": [']
    lines += [json.dumps(g, separators=(",", ":")) + ("," if i + 1 < len(sec["grains"]) else "")
              for i, g in enumerate(sec["grains"])]
    return "\n".join(lines) + "\n]}\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=os.path.dirname(os.path.abspath(__file__)), help="output folder")
    args = ap.parse_args()
    for name, make, seed in SECTIONS:
        text = dump(make(random.Random(seed)))
        path = os.path.join(args.out, name + ".json")
        tmp = path + ".tmp"
        with open(tmp, "w") as f:
            f.write(text)
        os.replace(tmp, path)


if __name__ == "__main__":
    main()
