#!/usr/bin/env python3
"""Derives the numbers of the material presets (assets/materials/*.json) and checks the files against them.

Sand, mud and gravel: GSAB Lambert strength nu_db and exponent q fitted to the backscattering strength of
the Jackson & Richardson high-frequency seafloor model as implemented in HydrOffice OpenBST (module
hyo2.openbst.lib.models.jackson2, its sediment table `dicts.py`: Medium Sand, Silt, Sandy Gravel), at one
frequency over one window of grazing angles. The fit is linear least squares in dB:

    S(graze) = nu_db + q * 10 log10 cos(theta),   theta = 90 deg - graze (incidence), so cos(theta) = sin(graze)

one sample per degree of grazing, equal weights. The model's density and sound-speed ratios of these classes
are checked against the APL-UW TR 9407 regressions on mean grain size (as reproduced in CASS gsiz2des).

Rock: Lambertian (q = 2) from measured scattering strengths (Olson, Lyons & Saebo 2016), no model.
Hull: the energy an air-backed steel plate can transmit, an upper bound of its mirror loss.

Usage:
  git clone https://github.com/hydroffice/hyo2_openbst /tmp/openbst
  git -C /tmp/openbst checkout 6fdcf36ebb547a11fd626ef90f8b0f34d2d7233c
  python3 tools/material_presets.py --openbst /tmp/openbst [--check assets/materials] [--frequency-khz 20]
Needs numpy only (the module's np.complex, removed in numpy 1.24, is aliased to complex here).
"""
import argparse
import json
import math
import pathlib
import sys

import numpy as np

FREQUENCY_KHZ = 100.0    # the top of the model's stated band (10-100 kHz); imaging sonars run above it
GRAZING_DEG = (5.0, 50.0)  # incidence 40-85 deg: where a forward-looking sonar meets the floor
WATER_SPEED_M_S = 1500.0   # the model's default (ModelParams.c_w)

# preset name -> OpenBST test sediment, mean grain size [phi] at which TR 9407's regression gives the same
# density and sound-speed ratios
SEDIMENTS = {"sand": ("MEDIUM_SAND", 1.5), "mud": ("SILT", 6.0), "gravel": ("SANDY_GRAVEL", -1.0)}

# Olson, Lyons & Saebo (2016): very rough rock, 20 deg grazing, "sine-squared shape of the empirical
# Lambertian model", scattering strength between -30 and -20 dB.
ROCK_GRAZING_DEG, ROCK_SS_DB = 20.0, (-30.0, -20.0)


def tr9407_rho_nu(mz):
    """Density and sound-speed ratios from mean grain size mz [phi], APL-UW TR 9407 (eqs. as in CASS gsiz2des)."""
    if -1 <= mz < 1:
        return (2.3139 + mz * (-0.17057 + mz * 0.007797), 1.2778 + mz * (-0.056452 + mz * 0.002709))
    if 1 <= mz < 5.3:
        return (3.0455 + mz * (-1.1069031 + mz * (0.2290201 - mz * 0.0165406)),
                1.3425 + mz * (-0.1382798 + mz * (0.0213937 - mz * 0.0014881)))
    if 5.3 <= mz <= 9:
        return (1.1565 - mz * 0.0012973, 1.0019 - mz * 0.0024324)
    raise ValueError("mz outside the fluid-sediment regressions")


def model_curve(openbst, sediment, frequency_hz):
    """Grazing angles [deg], backscattering strength [dB], reflection loss [dB] of one OpenBST test sediment."""
    sys.path.insert(0, str(openbst))
    if not hasattr(np, "complex"):
        np.complex = complex
    from hyo2.openbst.lib.models.jackson2.dicts import TestSediments
    from hyo2.openbst.lib.models.jackson2.model import Model
    from hyo2.openbst.lib.models.jackson2.model_params import ModelParams
    model = Model()
    params = ModelParams()
    params.f, params.c_w = frequency_hz, WATER_SPEED_M_S
    model.mdl_params = params
    model.use_test_sed_params(TestSediments[sediment])
    model.run()
    return model.out.theta_g, model.out.ss_tot, model.out.ref_loss, model.sed_params


def fit_lambert(graze_deg, ss_db, lo, hi):
    """nu_db, q, rms and largest residual [dB] of the fit over grazing angles [lo, hi]."""
    sel = (graze_deg >= lo) & (graze_deg <= hi)
    x = 10 * np.log10(np.sin(np.radians(graze_deg[sel])))
    a = np.vstack([np.ones_like(x), x]).T
    (nu_db, q), *_ = np.linalg.lstsq(a, ss_db[sel], rcond=None)
    r = ss_db[sel] - a @ np.array([nu_db, q])
    return nu_db, q, float(np.sqrt(np.mean(r ** 2))), float(np.abs(r).max())


def derive(openbst, frequency_khz=FREQUENCY_KHZ):
    """{preset: {key: value}} rounded as the preset files hold them, and a printed account."""
    out = {}
    print(f"Jackson & Richardson model (OpenBST jackson2) at {frequency_khz:g} kHz, fit over grazing "
          f"{GRAZING_DEG[0]:g}-{GRAZING_DEG[1]:g} deg")
    print("preset  sediment      rho    nu     TR9407(rho, nu) at Mz   nu_db     q   rms  max  "
          "loss@10/30/90 deg")
    for name, (sediment, mz) in SEDIMENTS.items():
        g, ss, loss, sp = model_curve(openbst, sediment, frequency_khz * 1e3)
        nu_db, q, rms, worst = fit_lambert(g, ss, *GRAZING_DEG)
        rho9407, nu9407 = tr9407_rho_nu(mz)
        at = {a: loss[np.argmin(abs(g - a))] for a in (10, 30, 90)}
        print(f"{name:7s} {sediment:13s} {sp.a_rho:5.3f} {sp.nu_p:6.4f}  ({rho9407:5.3f}, {nu9407:6.4f}) "
              f"at {mz:4.1f}  {nu_db:6.1f} {q:5.2f} {rms:4.1f} {worst:4.1f}  "
              f"{at[10]:4.1f} / {at[30]:4.1f} / {at[90]:4.1f}")
        out[name] = {"nu_db": round(nu_db, 1), "q": round(q, 2)}
    mid = sum(ROCK_SS_DB) / 2
    rock_nu = mid - 10 * math.log10(math.sin(math.radians(ROCK_GRAZING_DEG)) ** 2)
    print(f"rock: Lambert (q = 2), S({ROCK_GRAZING_DEG:g} deg) = {mid:g} dB (middle of {ROCK_SS_DB[0]:g} to "
          f"{ROCK_SS_DB[1]:g}) -> nu_db = {rock_nu:.1f} (range {ROCK_SS_DB[0] - mid + rock_nu:.1f} to "
          f"{ROCK_SS_DB[1] - mid + rock_nu:.1f})")
    g, ss, _, _ = model_curve(openbst, "ROCK", frequency_khz * 1e3)
    nu_db, q, rms, worst = fit_lambert(g, ss, *GRAZING_DEG)
    s20 = ss[np.argmin(abs(g - ROCK_GRAZING_DEG))]
    print(f"  (the model's Rock for comparison: nu_db {nu_db:.1f}, q {q:.2f}, S(20 deg) = {s20:.1f} dB)")
    out["rock"] = {"nu_db": round(rock_nu, 1), "q": 2}
    # Hull: water (1025 kg/m3, 1500 m/s) against air (1.21 kg/m3, 343 m/s) behind the plate. The plate
    # transmits at most what the bare water-air interface does (at its thickness resonances it is
    # transparent), so the reflected energy is at least 1 - T.
    z_w, z_a = 1025 * 1500.0, 1.21 * 343.0
    t = 4 * z_w * z_a / (z_w + z_a) ** 2
    print(f"hull: air-backed plate transmits T <= {t:.2e}: mirror loss <= {-10 * math.log10(1 - t):.4f} dB -> 0")
    out["hull"] = {"reflection_db": 0}
    return out


def check(derived, directory):
    """Every derived value equals the preset file's; returns the number of mismatches."""
    bad = 0
    for name, values in derived.items():
        preset = json.loads((pathlib.Path(directory) / f"{name}.json").read_text())["values"]
        for key, v in values.items():
            got = preset.get(key, {}).get("value")
            if got is None or abs(got - v) > 1e-9:
                print(f"MISMATCH {name}.{key}: file {got}, derived {v}")
                bad += 1
    print("presets match the derivation" if bad == 0 else f"{bad} mismatches")
    return bad


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--openbst", required=True, help="a checkout of hydroffice/hyo2_openbst")
    ap.add_argument("--check", metavar="DIR", help="compare with DIR/NAME.json (assets/materials)")
    ap.add_argument("--frequency-khz", type=float, default=FREQUENCY_KHZ,
                    help="fit at another frequency (the presets: %(default)g; --check needs the default)")
    args = ap.parse_args()
    derived = derive(args.openbst, args.frequency_khz)
    return 1 if args.check and check(derived, args.check) else 0


if __name__ == "__main__":
    sys.exit(main())
