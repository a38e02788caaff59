"""Launch a panoptic run from Python: a thin wrapper around `panoptic run`.

    run = panoptic.run("params/fiducial.toml", set={"disk.alpha": 1e-3,
                                                    "output.t_end_yr": 1e5},
                       out="out/alpha_1e-3.h5")

runs `panoptic run SCENE -o OUT --overwrite --set disk.alpha=0.001 ...`, waits for it and
returns load_run(OUT). A non-zero exit raises PanopticError carrying panoptic's own
message (its stderr) and exit code (README of src/run: 75 = stopped, restartable).
"""
import math
import os
import shutil
import subprocess
import tempfile

from .reader import load_run


class PanopticError(RuntimeError):
    """`panoptic run` exited non-zero. Attributes: returncode, stderr, stdout, cmd."""

    def __init__(self, cmd, returncode, stdout, stderr):
        self.cmd, self.returncode, self.stdout, self.stderr = cmd, returncode, stdout, stderr
        lines = (stderr.strip() or stdout.strip()).splitlines()
        message = "\n".join(lines[-8:]) or "(no output)"   # panoptic's message ends it
        super().__init__(f"panoptic exited with {returncode}: {message}")


def find_executable(exe=None):
    """The panoptic executable: `exe` if given, else $PANOPTIC_EXE, else `panoptic` on the
    PATH, else build/panoptic of the repository this package sits in (an editable or
    in-tree use). FileNotFoundError saying where it looked otherwise."""
    for candidate, what in ((exe, "exe="), (os.environ.get("PANOPTIC_EXE"), "PANOPTIC_EXE")):
        if candidate:
            if os.path.isfile(candidate) and os.access(candidate, os.X_OK):
                return os.path.abspath(candidate)
            raise FileNotFoundError(f"{what} {candidate}: no such executable")
    tried = []
    on_path = shutil.which("panoptic")
    if on_path:
        return on_path
    tried.append("panoptic on the PATH")
    in_tree = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                           "build", "panoptic")
    if os.path.isfile(in_tree) and os.access(in_tree, os.X_OK):
        return in_tree
    tried.append(in_tree)
    raise FileNotFoundError("no panoptic executable (tried: " + ", ".join(tried) + "); "
                            "build it (cmake --build build --target panoptic) and pass "
                            "exe=..., or set PANOPTIC_EXE")


def toml_literal(value):
    """A Python value as the TOML literal `--set key=VALUE` takes: true/false, numbers
    (repr, so that no digit is lost), quoted strings, [lists]."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, (list, tuple)):
        return "[" + ",".join(toml_literal(v) for v in value) + "]"
    if hasattr(value, "item"):          # a numpy scalar
        return toml_literal(value.item())
    raise TypeError(f"cannot write {value!r} ({type(value).__name__}) as a TOML value")


def run(scene, set=None, out=None, exe=None, args=(), overwrite=True, timeout=None,
        quiet=True):
    """Run panoptic on `scene` (a .toml path) with overrides `set` ({key: value}, e.g.
    {"disk.alpha": 1e-3, "planetesimals.si": "none"}; the keys of
    params/reference.toml) into `out` (default: a new temporary directory's
    <scene>.h5); returns load_run(out).

    exe: the executable (find_executable); args: further `panoptic run` options
    (["--max-wall", "1h"]); overwrite: pass --overwrite (replace an existing `out`);
    quiet: capture panoptic's stdout (else it goes to this process's stdout).
    Raises PanopticError (panoptic's stderr, exit code) on a non-zero exit."""
    exe = find_executable(exe)
    if out is None:
        stem = os.path.splitext(os.path.basename(str(scene)))[0] or "run"
        out = os.path.join(tempfile.mkdtemp(prefix="panoptic_"), f"{stem}.h5")
    out = os.fspath(out)
    cmd = [exe, "run", os.fspath(scene), "-o", out]
    if overwrite:
        cmd.append("--overwrite")
    for key, value in (set or {}).items():
        cmd += ["--set", f"{key}={toml_literal(value)}"]
    cmd += [str(a) for a in args]
    p = subprocess.run(cmd, stdout=subprocess.PIPE if quiet else None,
                       stderr=subprocess.PIPE, text=True, timeout=timeout)
    if p.returncode != 0:
        raise PanopticError(cmd, p.returncode, p.stdout or "", p.stderr or "")
    return load_run(out)
