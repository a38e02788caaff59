"""Labelled variants (src/run/README.md, Variants): the --set items of a run (and its
preset) are its own root attributes, `overrides` (a JSON list, in the order applied) and
`label` (the scene's name with the items), shown in the printed header, in
`Run.scene` (which plot titles show) and in the default output name,
out/<scene>+<key>=<value>....h5, or out/<scene>+set-<8 hex digits of the FNV-1a digest of
the items> when an item holds other characters or the name would be long. A second run to
an existing output is refused naming the file and the options -o and --overwrite."""
import json
import os
import subprocess

import h5py

from common import REPO, Checks, load_run, parse_args

SCENE = os.path.join(REPO, "params", "tests", "restart.toml")
SHORT = ["output.t_end_yr=1e3", "grid.n_cells=50"]


def run(exe, cwd, *args):
    return subprocess.run([exe, "run", SCENE, *args], capture_output=True, text=True,
                          cwd=cwd)


def sets(items):
    return [a for s in items for a in ("--set", s)]


def fnv1a64(data):
    h = 0xcbf29ce484222325
    for b in data:
        h = ((h ^ b) * 0x100000001b3) % 2**64
    return h


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir
    args.exe = os.path.abspath(args.exe)  # the runs start in the work directory
    if os.path.isdir(f"{w}/out"):
        for name in os.listdir(f"{w}/out"):
            os.remove(f"{w}/out/{name}")

    # a readable variant: the default name, the header, the attributes, Run.scene
    items = ["disk.sigma_1au=5100"] + SHORT
    label = "restart+disk.sigma_1au=5100+output.t_end_yr=1e3+grid.n_cells=50"
    p = run(args.exe, w, *sets(items))
    out = f"{w}/out/{label}.h5"
    c.check(p.returncode == 0 and os.path.exists(out),
            f"default output out/{label}.h5: exit {p.returncode} {p.stderr.strip()[:200]}")
    c.check(f"variant {label}: --set disk.sigma_1au=5100 --set output.t_end_yr=1e3 "
            "--set grid.n_cells=50" in p.stdout, "the header names the variant: "
            + next((ln for ln in p.stdout.splitlines() if ln.startswith("variant")), ""))
    with h5py.File(out, "r") as f:
        attrs = {k: (v.decode() if isinstance(v, bytes) else str(v))
                 for k, v in f.attrs.items()}
    c.check(json.loads(attrs.get("overrides", "null")) == items and
            attrs.get("label") == label and attrs.get("scene") == "restart",
            f"root attributes overrides {attrs.get('overrides')}, label "
            f"{attrs.get('label')}, scene {attrs.get('scene')}")
    r = load_run(out)
    c.check(r.scene == label and r.overrides == items,
            f"Run.scene {r.scene!r} (plot titles), Run.overrides {r.overrides}")

    # the same again: refused, naming the output and the options
    p = run(args.exe, w, *sets(items))
    c.check(p.returncode == 4 and f"out/{label}.h5: output file exists" in p.stderr and
            "-o FILE" in p.stderr and "--overwrite" in p.stderr and
            "checkpoint" not in p.stderr.split("--overwrite")[0],
            f"an existing output: exit {p.returncode} (4), {p.stderr.strip()}")

    # a preset and a string value: "+fast", the quotes dropped
    p = run(args.exe, w, "--fast", *sets(['dust.init="gaussian_ring"'] + SHORT))
    label = "restart+fast+dust.init=gaussian_ring+output.t_end_yr=1e3+grid.n_cells=50"
    c.check(p.returncode == 0 and os.path.exists(f"{w}/out/{label}.h5"),
            f"--fast and a string value: out/{label}.h5 {p.stderr.strip()[:200]}")
    with h5py.File(f"{w}/out/{label}.h5", "r") as f:
        overrides = json.loads(f.attrs["overrides"])
    c.check(overrides[:2] == ["grid.n_cells=250", "solver.rtol=1e-4"] and
            overrides[2] == 'dust.init="gaussian_ring"',
            f"overrides: the preset's items first, then --set: {overrides}")

    # a list value (brackets): the digest of the items
    items = ["pebbles.radii_au=[5.0, 50.0]"] + SHORT
    digest = fnv1a64("".join(s + "\n" for s in items).encode()) >> 32
    label = f"restart+set-{digest:08x}"
    p = run(args.exe, w, *sets(items))
    c.check(p.returncode == 0 and os.path.exists(f"{w}/out/{label}.h5"),
            f"a list value: out/{label}.h5 (FNV-1a computed here) "
            f"{[f for f in os.listdir(f'{w}/out') if 'set-' in f]}")

    # no override: out/<scene>.h5 as before, label = the scene, overrides []
    p = run(args.exe, w)  # transport alone: 0.1 s
    c.check(p.returncode == 0 and os.path.exists(f"{w}/out/restart.h5"),
            f"no override: out/restart.h5 {p.stderr.strip()[:200]}")
    r = load_run(f"{w}/out/restart.h5")
    c.check(r.attrs.get("label") == "restart" and r.attrs.get("overrides") == "[]" and
            r.scene == "restart" and r.overrides == [],
            f"no override: label {r.attrs.get('label')!r}, overrides "
            f"{r.attrs.get('overrides')!r}")
    c.finish()


if __name__ == "__main__":
    main()
