"""Output that cannot be written (src/io/README.md, "Output"): exit 4 with a message that names the
file, the cause and the fix, never a crash.
  * A directory as -o: "is a directory", with or without --overwrite (run, observe).
  * --overwrite of a file that is not HDF5 (a scene or notes given as -o by mistake):
    refused, the file left as it was (run, observe).
  * A directory the user cannot write (run as nobody, when this test runs as root and
    setpriv exists): the errno text, "Permission denied".
  * A full file system (a tmpfs of 100 kB, when this test may mount one): the run stops
    at the write that fails, exit 4 (not SIGSEGV, exit -11 or 139: HDF5 1.10.8 crashed at
    exit on the file it could not close), "the disk is full".
Cases the machine cannot set up (the last two) are printed as skipped."""
import os
import shutil
import subprocess
import tempfile

from common import REPO, Checks, parse_args

SHORT = ["--set", "grid.n_cells=32", "--set", "grid.stretch=0", "--set",
         "output.t_end_yr=100", "--set", "output.t_first_yr=1", "--set",
         "output.n_snapshots=5"]


def panoptic(exe, out, *extra, prefix=(), cwd=None):
    cmd = [*prefix, exe, "run", os.path.join(REPO, "params/fiducial.toml"), "-o", out,
           *SHORT, *extra]
    return subprocess.run(cmd, capture_output=True, text=True, cwd=cwd)


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir
    exe = os.path.abspath(args.exe)

    d = os.path.join(w, "a_directory")
    os.makedirs(d, exist_ok=True)
    for extra in ([], ["--overwrite"]):
        p = panoptic(exe, d, *extra)
        c.check(p.returncode == 4 and "is a directory" in p.stderr,
                f"-o DIR {' '.join(extra)}: exit {p.returncode} (4): {p.stderr.strip()}")

    # --overwrite replaces an earlier output, not a file of another kind
    notes = os.path.join(w, "notes.toml")
    with open(notes, "w") as f:
        f.write("# my notes\n")
    p = panoptic(exe, notes, "--overwrite")
    c.check(p.returncode == 4 and "not an HDF5 file" in p.stderr,
            f"run -o a text file --overwrite: exit {p.returncode} (4): {p.stderr.strip()}")
    ok = os.path.join(w, "ok.h5")
    panoptic(exe, ok, "--overwrite").check_returncode()
    p = subprocess.run([exe, "observe", ok, "--time-yr", "100", "--lambda-mm", "1.3",
                        "-o", notes, "--overwrite"], capture_output=True, text=True)
    c.check(p.returncode == 4 and "not an HDF5 file" in p.stderr,
            f"observe -o a text file --overwrite: exit {p.returncode} (4): "
            f"{p.stderr.strip()}")
    with open(notes) as f:
        c.check(f.read() == "# my notes\n", "the text file left as it was")
    p = subprocess.run([exe, "observe", ok, "--time-yr", "100", "--lambda-mm", "1.3",
                        "-o", d, "--overwrite"], capture_output=True, text=True)
    c.check(p.returncode == 4 and "is a directory" in p.stderr,
            f"observe -o DIR: exit {p.returncode} (4): {p.stderr.strip()}")

    setpriv = shutil.which("setpriv")
    if os.geteuid() == 0 and setpriv:
        ro = tempfile.mkdtemp(prefix="panoptic_ro_")
        try:
            os.chmod(ro, 0o555)
            p = panoptic(exe, os.path.join(ro, "x.h5"), prefix=[
                setpriv, "--reuid=65534", "--regid=65534", "--clear-groups"], cwd="/")
            if p.returncode in (126, 127):  # nobody may not run the build's binary
                print(f"skipped: unwritable directory ({p.stderr.strip()})")
            else:
                c.check(p.returncode == 4 and "Permission denied" in p.stderr
                        and "-o" in p.stderr, f"unwritable directory: exit "
                        f"{p.returncode} (4): {p.stderr.strip()}")
        finally:
            shutil.rmtree(ro, ignore_errors=True)
    else:
        print("skipped: unwritable directory (needs root and setpriv)")

    full = tempfile.mkdtemp(prefix="panoptic_full_")
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=100k", "tmpfs", full],
                             capture_output=True).returncode == 0
    try:
        if mounted:
            p = panoptic(exe, "full.h5", cwd=full)
            c.check(p.returncode == 4, f"full file system: exit {p.returncode} (4; "
                    "-11 or 139 is the crash at exit)")
            # the output or its checkpoint meets the full disk first (it depends on
            # their sizes); the message names the file that could not be written
            c.check("the disk is full" in p.stderr and "make room" in p.stderr and
                    ("full.h5" in p.stderr or "full.chk.h5" in p.stderr),
                    f"full file system: the message: {p.stderr.strip()}")
        else:
            print("skipped: full file system (cannot mount a tmpfs here)")
    finally:
        if mounted:
            subprocess.run(["umount", full])
        shutil.rmtree(full, ignore_errors=True)
    c.finish()


if __name__ == "__main__":
    main()
