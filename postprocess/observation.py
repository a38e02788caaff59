"""Read a synthetic observation (the output of `panoptic observe`).

    obs = load_observation("out/fiducial_obs.h5")
    obs.wavelength_mm                     # (n_lambda,) [mm]
    r, I = obs.profile(1.3)               # deprojected radius [au], convolved [Jy/beam]
    obs.image(1.3)                        # (ny, nx) [Jy/beam]; kind="model": [Jy/arcsec^2]
    obs["beam_bmaj_arcsec"], obs["image/x_arcsec"]   # any attribute or group/dataset
"""
import h5py
import numpy as np

GROUPS = ("model", "image", "profile", "flux", "spectral_index")


class Observation:
    """Contents of one observe output, loaded into memory.

    Attributes:
        path           the file
        data           dict: every root attribute by name (time_yr, distance_pc, incl_deg,
                       pa_deg, beam_bmaj_arcsec, beam_bmin_arcsec, beam_pa_deg,
                       beam_area_arcsec2, ...), every dataset of the groups as
                       "group/name", and lambda_mm, pixel_arcsec; obs[key] reads it
        units          dict "group/name" -> `units` attribute
        wavelength_mm  observed wavelengths (n_lambda,) [mm]
    """

    def __init__(self, path, data, units):
        self.path, self.data, self.units = str(path), data, units
        self.wavelength_mm = data["lambda_mm"]

    def __getitem__(self, key):
        return self.data[key]

    def __contains__(self, key):
        return key in self.data

    def __repr__(self):
        lams = ", ".join(f"{x:g}" for x in self.wavelength_mm)
        return (f"<panoptic Observation {self.path!r}: t = {self.data.get('time_yr', 0):.4g} "
                f"yr, {lams} mm>")

    def _index(self, lambda_mm):
        """Index of the wavelength lambda_mm [mm]; KeyError naming the wavelengths."""
        hits = np.flatnonzero(np.isclose(self.wavelength_mm, lambda_mm, rtol=1e-9))
        if hits.size == 0:
            raise KeyError(f"{lambda_mm:g} mm is not a wavelength of {self.path}: "
                           f"{', '.join(f'{x:g}' for x in self.wavelength_mm)} mm")
        return int(hits[0])

    def image(self, lambda_mm, kind="convolved"):
        """The image at wavelength lambda_mm [mm], (ny, nx) on x_arcsec (east-west) and
        the same in y: kind "convolved" [Jy beam^-1] or "model" [Jy arcsec^-2]."""
        return self.data[f"image/{kind}"][self._index(lambda_mm)]

    def profile(self, lambda_mm):
        """(deprojected radius [au], azimuthally averaged convolved intensity
        [Jy beam^-1]) at wavelength lambda_mm [mm]."""
        return self.data["profile/r_au"], self.data["profile/convolved"][self._index(lambda_mm)]

    def model_intensity(self, lambda_mm):
        """(cell centres [au], model intensity [Jy arcsec^-2]) at lambda_mm [mm]."""
        return self.data["model/r_au"], self.data["model/intensity"][self._index(lambda_mm)]


def load_observation(path):
    """Read an observe output (HDF5) into an Observation. ValueError when the file is a
    run's output or something else."""
    with h5py.File(path, "r") as f:
        if "wavelength_mm" not in f or "image" not in f:
            what = "a run's output (read it with load_run)" if "snapshots" in f else \
                "not an output of `panoptic observe`"
            raise ValueError(f"{path} is {what}")
        data = {k: _plain(f.attrs[k]) for k in f.attrs}
        units = {}
        for group in GROUPS:
            if group not in f:
                continue
            for k, v in f[group].items():
                data[f"{group}/{k}"] = v[()]
                units[f"{group}/{k}"] = _plain(v.attrs.get("units", ""))
        data["lambda_mm"] = f["wavelength_mm"][()]
        data["pixel_arcsec"] = _plain(f["image"].attrs["pixel_arcsec"])
    return Observation(path, data, units)


def _plain(value):
    """An HDF5 attribute as str / float / int / array."""
    if isinstance(value, np.ndarray) and value.size == 1:
        value = value.item()
    if isinstance(value, (bytes, np.bytes_)):
        return value.decode("utf-8")
    return value.item() if isinstance(value, np.generic) else value
