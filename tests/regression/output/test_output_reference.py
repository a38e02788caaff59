"""`panoptic reference --outputs` lists every dataset and attribute of a run's output, and
only those: a fiducial run (short) and one with the processes the fiducial scene leaves
off (evolving gas, erosion) and a size-distribution run (params/tests/
distribution_small.toml) are listed entry by entry (datasets as group/name, attributes
of the root and of the groups as group@name, "@name" at the root), every listed entry is
in one of the three files, and every dataset carries its units and description attributes
with the listed units."""
import os

from postprocess.reader import open_output

from common import Checks, parse_args, run, run_checked

SHORT = ["output.t_end_yr=300", "output.n_snapshots=3"]
# what the fiducial scene leaves off, on top of it (the listing's scene turns every
# process on: src/model/output_table.cpp, every_process_scene)
REST = ["gas.evolve=true", "erosion.model=balance"]


def listed(exe):
    """{path: units} of the listing's rows ("-": none)."""
    text = run_checked([exe, "reference", "--outputs"]).stdout
    rows = {}
    for line in text.splitlines()[2:]:
        cells = [c.strip() for c in line.strip().strip("|").split(" | ")]
        rows[cells[0]] = cells[1]
    return rows


def entries(path):
    """{path: units} of every dataset and every root and group attribute of a file (a
    dataset's own units and description attributes are part of its row)."""
    found = {}
    with open_output(path) as f:
        for name in f.attrs:
            found["@" + name] = None

        def visit(name, obj):
            if hasattr(obj, "shape"):
                units = obj.attrs.get("units")
                found[name] = (units.decode() if isinstance(units, bytes) else units,
                               sorted(obj.attrs))
            else:
                for a in obj.attrs:
                    found[f"{name}@{a}"] = None

        f.visititems(visit)
    return found


def main():
    args = parse_args()
    c = Checks()
    rows = listed(args.exe)
    files = {}
    for tag, scene, sets in (("fiducial", "params/fiducial.toml", SHORT),
                             ("every process", "params/fiducial.toml", SHORT + REST),
                             ("distribution", "params/tests/distribution_small.toml", SHORT)):
        out = os.path.join(args.workdir, tag.replace(" ", "_") + ".h5")
        run(args.exe, scene, out, sets)
        files[tag] = entries(out)
        missing = sorted(p for p in files[tag] if p not in rows)
        c.check(not missing, f"{tag}: every entry of the file ({len(files[tag])}) is listed"
                + (f"; not listed: {missing}" if missing else ""))
        wrong = []
        for p, info in files[tag].items():
            if info is None or p not in rows:
                continue
            units, attrs = info
            if attrs != ["description", "units"] or (units or "-") != rows[p]:
                wrong.append(f"{p}: attributes {attrs}, units {units!r}, listed {rows[p]!r}")
        c.check(not wrong, f"{tag}: every dataset has units and description, the listed units"
                + (f"; {wrong}" if wrong else ""))
    absent = sorted(p for p in rows if all(p not in f for f in files.values()))
    c.check(not absent, f"every listed entry ({len(rows)}) is in one of the files"
            + (f"; not in either: {absent}" if absent else ""))
    c.finish()


if __name__ == "__main__":
    main()
