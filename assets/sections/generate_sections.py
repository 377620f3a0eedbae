#!/usr/bin/env python3
"""Writes the shipped hand-placed thin section (granite) from stated modal
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


SECTIONS = (("granite_hand_placed", granite, 7),)


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
