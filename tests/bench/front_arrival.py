#!/usr/bin/env python3
"""When a growth front reaches each radius: for every run, the first snapshot time at
which a per-cell snapshot field of the cell nearest each radius reaches a value: by
default the mass-dominating St reaching 1e-4 (between DustPy's disk's initial grains, St
~ 1e-6, and its fragmentation-limited pebbles, St ~ 3e-4), or e.g. `--field m_mean
--value 1e-3`, the mass-weighted mean mass reaching 1e-3 g, which does not depend on the
aggregates' filling factor as St does; with two or more runs, each run's time over the
first's.
Usage: front_arrival.py RUN.h5 [RUN2.h5 ...] [--field St] [--value 1e-4] [--radii 1.5,...]
(tests/bench/results/porosity_track.md)."""
import argparse

import numpy as np

from porous_mmsn import open_run  # readable while its run still writes it (SWMR)


def arrival_times(path, radii, field, value):
    """Per radius: (cell centre [au], first snapshot time [yr] with the field >= value,
    or nan)."""
    with open_run(path) as f:
        r = f["grid/r_c"][:]
        t = f["snapshots/time"][:]
        x = f[f"snapshots/{field}"][:]
    out = []
    for radius in radii:
        i = int(np.argmin(np.abs(np.log(r / radius))))
        reached = np.nonzero(x[:, i] >= value)[0]
        out.append((r[i], t[reached[0]] if reached.size else np.nan))
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("runs", nargs="+")
    p.add_argument("--field", default="St")
    p.add_argument("--value", type=float, default=1e-4)
    p.add_argument("--radii", default="1.5,2,3,5,7,10,15,20,30")
    a = p.parse_args()
    radii = [float(x) for x in a.radii.split(",")]
    table = [arrival_times(path, radii, a.field, a.value) for path in a.runs]
    for k, path in enumerate(a.runs):
        print(f"run{k}: {path}")
    head = " r [au]" + "".join(f"  run{k} t [yr]" for k in range(len(a.runs)))
    head += "".join(f"  run{k}/run0" for k in range(1, len(a.runs)))
    print(f"first snapshot with {a.field} >= {a.value:g}")
    print(head)
    for j in range(len(radii)):
        row = f"{table[0][j][0]:7.2f}" + "".join(f"  {t[j][1]:12.4g}" for t in table)
        row += "".join(f"  {t[j][1] / table[0][j][1]:9.3f}" for t in table[1:])
        print(row)


if __name__ == "__main__":
    main()
