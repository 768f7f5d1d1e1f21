#!/usr/bin/env python3
"""Rotates FEMA P695's two Erzincan components (ERZ_032, ERZ_122: azimuths 32° and 122°) back to
the as-recorded NS and EW components, the thesis's "1992 Erzican-NS" (Fig. 39, 43; Table 5 NF-26).

NS (azimuth 0°) = cos 32° · ERZ_032 + cos 122° · ERZ_122, EW (90°) = sin 32° · ERZ_032 + sin 122° ·
ERZ_122. Peak values 0.515 g (NS) and 0.496 g (EW), those published for the Erzincan station.

    python3 tools/erzincan_ns.py ../shared/records/fema-p695/nearfield_pulse OUTDIR
writes OUTDIR/RSN821_ERZIKAN_ERZ_NS_rotated.AT2 and ..._EW_rotated.AT2 (AT2, units of g).
"""
import math
import sys


def read(path):
    lines = open(path).read().split("\n")
    return lines[:4], [float(x) for line in lines[4:] for x in line.split()]


def main(src, out):
    head, a = read(f"{src}/RSN821_ERZIKAN_ERZ_032.AT2")
    _, b = read(f"{src}/RSN821_ERZIKAN_ERZ_122.AT2")
    assert len(a) == len(b)
    r32, r122 = math.radians(32), math.radians(122)
    for name, (c1, c2) in {
        "NS": (math.cos(r32), math.cos(r122)),
        "EW": (math.sin(r32), math.sin(r122)),
    }.items():
        s = [c1 * x + c2 * y for x, y in zip(a, b)]
        print(f"{name}: PGA {max(map(abs, s)):.4f} g")
        with open(f"{out}/RSN821_ERZIKAN_ERZ_{name}_rotated.AT2", "w") as f:
            f.write("Rotated back from FEMA P695 ERZ_032 and ERZ_122 (tools/erzincan_ns.py)\n")
            f.write(f"Erzican, Turkey 1992, Erzincan, {name}\n")
            f.write("ACCELERATION TIME SERIES IN UNITS OF G\n")
            f.write(head[3] + "\n")
            for i in range(0, len(s), 5):
                f.write("".join(f"{v:15.7E}" for v in s[i : i + 5]) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
