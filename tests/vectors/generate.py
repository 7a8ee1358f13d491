#!/usr/bin/env python3
"""Golden vectors shared by the Python reference and the C core (deterministic, seeded).

Writes, next to this script:
  <name>.skill, <name>.skill.json   skills fitted from two analytic demonstrations
                                    (pressing-like from rest at 100 N/m, engraving-like starting in
                                    contact at 1 N at 280 N/m), N in {10, 50, 100}, ridge
                                    and lwr, hold and release
  <name>_g<G>_t<T>.csv              dmp.rollout of the image: header ``t,f_hat``, %.17g, rows
                                    n = 0..round(T_skill*time_scale/dt)
  manifest.txt                      ``<skill> <goal_scale> <time_scale> <rollout csv>`` per line
  wipe_*.skill, wipe_*_g<G>_t<T>_p<P>.csv, manifest_y.txt
                                    skills with the position DMP on y (format v3), fitted from a
                                    wiping-like demonstration (force profile + path along y):
                                    header ``t,f_hat,y_hat`` (dmp.rollout and dmp.rollout_path),
                                    ``<skill> <goal_scale> <time_scale> <path_scale> <csv>`` per line
  periodic_*.skill, periodic_*_g<G>_a<A>_t<T>_c<C>.csv, manifest_periodic.txt
                                    periodic skills (format v4) fitted from a multi-stroke
                                    wiping demonstration: header ``t,f_hat`` (periodic.rollout
                                    over C cycles), ``<skill> <goal> <amplitude> <time> <cycles>
                                    <csv>`` per line
  periodic_y_*.skill, periodic_y_*_g<G>_a<A>_t<T>_c<C>_p<P>.csv, manifest_periodic_y.txt
                                    periodic skills with the y path (format v4, flags bit 1)
                                    fitted from the wiping strokes with a path along y: header
                                    ``t,f_hat,y_hat`` (periodic.rollout, periodic.rollout_path),
                                    ``<skill> <goal> <amplitude> <time> <cycles> <path> <csv>``
                                    per line (``--periodic-y`` writes only these)
  band_*.skill, band_*_points.csv, band_*_g<G>_t<T>.csv, manifest_band.txt
                                    skills with the demonstrated band (format v5), fitted from
                                    the mean of several recordings (forceskill.model.multi): the
                                    band's points ``f_band_lo,f_band_hi`` and the rollout with the
                                    band at run time ``t,f_hat,f_band_lo,f_band_hi``
                                    (Skill.band_at), ``<skill> <goal_scale> <time_scale> <points
                                    csv> <rollout csv>`` per line (``--band`` writes only these)
  contact_*.csv, manifest_contact.txt
                                    the contact wait (forceskill.model.contact.loss_window) of
                                    a discrete and a periodic skill above, the contact lost for a
                                    window: header ``t,f_contact,rate,f_hat`` (the measured force
                                    is an input), ``<skill> <goal> <amplitude> <time> <threshold_N>
                                    <tau_s> <hold_s> <csv>`` per line
  bad/*.skill, bad/manifest.txt     corrupt images, one per rejection of docs/skill_format.md:
                                    ``<file> <expected code>``; images that must fail after the CRC
                                    check carry a correct CRC.
Run: .venv/bin/python tests/vectors/generate.py   (tests/host/model/test_vectors.py checks the files are current;
     --contact: only the contact-wait files, from the skill images on disk)
"""

from __future__ import annotations

import struct
import sys
import zlib
from pathlib import Path
from typing import Any

import numpy as np

from forceskill.model import contact, dmp, periodic, synthetic
from forceskill.model.demo import Demo
from forceskill.model.fit import fit
from forceskill.model.params import Gains, gains_for_object
from forceskill.model.periodic_fit import fit_periodic
from forceskill.model.skill import _F64_NAMES, _F64_NAMES_Y, MAGIC, MAX_KERNELS, Skill
from forceskill.model.skill import HEADER_SIZE_V2 as HEADER_SIZE

#: the HIL objects' mass (hil_sim/scenarios): the skills' force gains are adapted to it, so the
#: vectors run stably on the simulator (the fault rig and the HIL tests execute them)
OBJECT_MASS_KG = 10.0
HERE = Path(__file__).resolve().parent

# Short demonstrations keep the rollouts (and tests/vectors) well under 2 MB.
DEMOS = {
    "press": (lambda: synthetic.pressing(seed=11, duration_s=1.5, k_v1=100.0, k_v2=180.0), 100.0),
    "engrave": (
        lambda: _in_contact(synthetic.engraving(seed=12, duration_s=2.0, k_v=280.0, f_max_N=8.0)),
        280.0,
    ),
}


def _in_contact(d: Demo) -> Demo:
    """The demonstration starting at 1 N (already in contact): the skill's f0 is not 0."""
    return Demo(d.t_s, d.pos_m, d.force_N + 1.0, d.source + " +1 N", y_m=d.y_m)


#: the y half: (name, N, method, end policy) and the scales (goal, time, path) of each
WIPE_DEMO = (lambda: _in_contact(synthetic.wiping(seed=13, duration_s=2.0, k_v=280.0, f_max_N=8.0)), 280.0)
WIPE_SKILLS = (
    ("wipe_n10_ridge_hold", 10, "ridge", "hold", ((1.0, 1.0, 1.0),)),
    ("wipe_n50_ridge_release", 50, "ridge", "release", ((1.0, 1.0, 1.0), (1.5, 1.3, 1.5))),
)


#: the periodic skills: (name, N, method) and the scales (goal, amplitude, time, cycles) of each
STROKES_DEMO = (
    lambda: synthetic.wiping_strokes(seed=14, n_strokes=6, period_s=0.5, approach_s=0.6, release_s=0.5),
    280.0,
)
PERIODIC_SKILLS = (
    ("periodic_n20_ridge", 20, "ridge", ((1.0, 1.0, 1.0, 1.0),)),
    ("periodic_n50_lwr", 50, "lwr", ((1.0, 1.0, 1.0, 1.0),)),
    ("periodic_n50_ridge", 50, "ridge", ((1.0, 1.0, 1.0, 2.0), (1.5, 0.5, 1.0, 1.0), (1.0, 1.5, 1.3, 1.5))),
)
PeriodicScales = tuple[tuple[float, float, float, float], ...]
#: the periodic skills with the y path: (name, N, method) and (goal, amplitude, time, cycles, path)
STROKES_Y_DEMO = (
    lambda: synthetic.wiping_strokes(
        seed=14, n_strokes=6, period_s=0.5, approach_s=0.6, release_s=0.5, path_m=0.03
    ),
    280.0,
)
PERIODIC_Y_SKILLS = (
    ("periodic_y_n20_ridge", 20, "ridge", ((1.0, 1.0, 1.0, 1.0, 1.0),)),
    ("periodic_y_n50_ridge", 50, "ridge", ((1.0, 1.0, 1.0, 2.0, 1.0), (1.2, 1.5, 1.3, 1.5, 1.5))),
)


def _num(x: float) -> str:
    return f"{x:g}".replace(".", "p")


def fitted_periodic_skills() -> dict[str, tuple[Skill, PeriodicScales]]:
    """The periodic skills and their scales, fitted afresh."""
    make, k = STROKES_DEMO
    demo = make()
    gains = gains_for_object(k, OBJECT_MASS_KG)
    return {
        name: (fit_periodic(demo, k, n_kernels=n, method=method, gains=gains).skill, sc)
        for name, n, method, sc in PERIODIC_SKILLS
    }


def golden_periodic(skills: dict[str, tuple[Skill, PeriodicScales]]) -> tuple[dict[str, bytes], list[str]]:
    """Image, JSON twin and the periodic.rollout CSV of every periodic skill at its scales."""
    files: dict[str, bytes] = {}
    manifest: list[str] = []
    for name, (sk, scales) in skills.items():
        files[f"{name}.skill"] = sk.to_bytes()
        files[f"{name}.skill.json"] = sk.to_json().encode()
        for gs, amp, ts, cyc in scales:
            t, f = periodic.rollout(sk, cycles=cyc, goal_scale=gs, amplitude_scale=amp, time_scale=ts)
            csv = f"{name}_g{_num(gs)}_a{_num(amp)}_t{_num(ts)}_c{_num(cyc)}.csv"
            lines = ["t,f_hat"] + [f"{a:.17g},{b:.17g}" for a, b in zip(t.tolist(), f.tolist(), strict=True)]
            files[csv] = ("\n".join(lines) + "\n").encode()
            manifest.append(f"{name}.skill {gs:g} {amp:g} {ts:g} {cyc:g} {csv}")
    return files, manifest


def golden_periodic_y() -> tuple[dict[str, bytes], list[str]]:
    """Image, JSON twin and the t,f_hat,y_hat rollout CSV of every periodic skill with the y
    path at its scales, fitted afresh."""
    make, k = STROKES_Y_DEMO
    demo = make()
    gains = gains_for_object(k, OBJECT_MASS_KG)
    files: dict[str, bytes] = {}
    manifest: list[str] = []
    for name, n, method, scales in PERIODIC_Y_SKILLS:
        sk = fit_periodic(demo, k, n_kernels=n, method=method, gains=gains).skill
        files[f"{name}.skill"] = sk.to_bytes()
        files[f"{name}.skill.json"] = sk.to_json().encode()
        for gs, amp, ts, cyc, ps in scales:
            t, f = periodic.rollout(sk, cycles=cyc, goal_scale=gs, amplitude_scale=amp, time_scale=ts)
            _, y = periodic.rollout_path(sk, cycles=cyc, path_scale=ps, time_scale=ts)
            csv = f"{name}_g{_num(gs)}_a{_num(amp)}_t{_num(ts)}_c{_num(cyc)}_p{_num(ps)}.csv"
            rows = zip(t.tolist(), f.tolist(), y.tolist(), strict=True)
            lines = ["t,f_hat,y_hat"] + [f"{a:.17g},{b:.17g},{c:.17g}" for a, b, c in rows]
            files[csv] = ("\n".join(lines) + "\n").encode()
            manifest.append(f"{name}.skill {gs:g} {amp:g} {ts:g} {cyc:g} {ps:g} {csv}")
    return files, manifest


def write_periodic_y() -> int:
    """Write the periodic y-path files (golden_periodic_y) next to this script; their count."""
    files, manifest = golden_periodic_y()
    for name, data in files.items():
        (HERE / name).write_bytes(data)
    (HERE / "manifest_periodic_y.txt").write_text("\n".join(manifest) + "\n")
    return len(files)


#: the band vectors: (name, recordings seed, N, band points, scales (goal, time))
BAND_SKILLS = (
    ("band_press_n50_ridge", 21, 50, 100, ((1.5, 1.3),)),
    ("band_press_n20_ridge", 22, 20, 16, ((1.0, 1.0),)),
)


def fitted_band_skills() -> dict[str, tuple[Skill, tuple[tuple[float, float], ...]]]:
    """The band skills: the mean of four short pressing recordings at 100 N/m (HIL object mass),
    with the band mean +- max(3 sigma, 5 % of max)."""
    from forceskill.model import multi
    from forceskill.model.demo import resample

    out = {}
    for name, seed, n, m, scales in BAND_SKILLS:
        _, demos = synthetic.pressing_set(seed=seed, n=4, duration_s=1.5)
        mp = multi.mean_profile([resample(d, 0.001) for d in demos], 0.001)
        sk = fit(mp.demo, 100.0, n_kernels=n, gains=gains_for_object(100.0, OBJECT_MASS_KG)).skill
        lo, hi = multi.band_from_spread(mp.demo.force_N, mp.sigma_N, mp.noise_N)
        sk.band_lo_N, sk.band_hi_N = multi.band_points(lo, hi, m)
        sk.format_version = 5
        out[name] = (Skill.from_bytes(sk.to_bytes()), scales)
    return out


def golden_band() -> tuple[dict[str, bytes], list[str]]:
    """Image, JSON twin, the band's points and the rollouts with the band of every band skill."""
    files: dict[str, bytes] = {}
    manifest: list[str] = []
    for name, (sk, scales) in fitted_band_skills().items():
        assert sk.band_lo_N is not None and sk.band_hi_N is not None
        files[f"{name}.skill"] = sk.to_bytes()
        files[f"{name}.skill.json"] = sk.to_json().encode()
        pts = ["f_band_lo,f_band_hi"] + [
            f"{a:.17g},{b:.17g}" for a, b in zip(sk.band_lo_N.tolist(), sk.band_hi_N.tolist(), strict=True)
        ]
        files[f"{name}_points.csv"] = ("\n".join(pts) + "\n").encode()
        for gs, ts in scales:
            t, f = dmp.rollout(sk, goal_scale=gs, time_scale=ts)
            lo, hi = sk.band_at(t, gs, ts)
            csv = f"{name}_g{_num(gs)}_t{_num(ts)}.csv"
            rows = zip(t.tolist(), f.tolist(), lo.tolist(), hi.tolist(), strict=True)
            lines = ["t,f_hat,f_band_lo,f_band_hi"] + [
                f"{a:.17g},{b:.17g},{c:.17g},{d:.17g}" for a, b, c, d in rows
            ]
            files[csv] = ("\n".join(lines) + "\n").encode()
            manifest.append(f"{name}.skill {gs:g} {ts:g} {name}_points.csv {csv}")
    return files, manifest


def write_band() -> int:
    """Write the band files (golden_band) next to this script; their count."""
    files, manifest = golden_band()
    for name, data in files.items():
        (HERE / name).write_bytes(data)
    (HERE / "manifest_band.txt").write_text("\n".join(manifest) + "\n")
    return len(files)


def bad_images_band(base: Skill) -> list[tuple[str, bytes, int]]:
    """Version-5 rejections from a valid band skill."""
    good = base.to_bytes()
    assert base.band_lo_N is not None
    m = base.band_points
    arrays_end = len(good) - 4 - 16 * m

    def patch(data: bytes, off: int, fmt: str, value: Any, fix_len: bool = False) -> bytes:
        b = bytearray(data)
        struct.pack_into(fmt, b, off, value)
        if fix_len:
            struct.pack_into("<I", b, 8, len(b))
        body = bytes(b[:-4])
        return body + struct.pack("<I", zlib.crc32(body) & 0xFFFFFFFF)

    def band_count(k: int) -> bytes:  # k points, arrays resized to match (a consistent length)
        lo = np.resize(base.band_lo_N, k) if k else np.zeros(0)
        body = bytearray(good[:arrays_end]) + np.concatenate([lo, lo + 1.0]).astype("<f8").tobytes()
        struct.pack_into("<H", body, 208, k)
        struct.pack_into("<I", body, 8, len(body) + 4)
        return bytes(body) + struct.pack("<I", zlib.crc32(bytes(body)) & 0xFFFFFFFF)

    crossed = patch(good, arrays_end + 8 * 3, "<d", float(base.band_hi_N[3]) + 0.1)  # type: ignore[index]
    return [
        ("b_header_size.skill", patch(good, 6, "<H", 208), 211),
        ("b_count_1.skill", band_count(1), 234),
        ("b_count_0.skill", band_count(0), 234),
        ("b_count_129.skill", band_count(129), 234),
        ("b_count_field.skill", patch(good, 208, "<H", m - 1), 203),
        ("b_reserved.skill", patch(good, 212, "<H", 1), 234),
        ("b_nan.skill", patch(good, arrays_end + 8 * m + 16, "<d", float("nan")), 206),
        ("b_crossed.skill", crossed, 234),
    ]


_HDR4 = struct.Struct("<IHHIHH23dHHHH")


def bad_images_periodic(base: Skill, discrete: Skill) -> list[tuple[str, bytes, int]]:
    """Version-4 rejections from a valid periodic skill (and a discrete skill written as v4)."""
    from forceskill.model.skill import _F64_NAMES_P

    names = (*_F64, *_F64_NAMES_Y, *_F64_NAMES_P)

    def pack4(sk: Skill, centres: np.ndarray | None = None, **kw: Any) -> bytes:
        n = sk.n_kernels
        f = {k: getattr(sk, k) for k in names}
        f.update({k: v for k, v in kw.items() if k in names})
        head = _HDR4.pack(
            MAGIC,
            kw.get("version", 4),
            kw.get("header_size", 208),
            208 + 24 * n + 4,
            n,
            kw.get("flags", sk.flags),
            *(float(f[k]) for k in names),
            kw.get("kind", sk.kind),
            kw.get("contact_cN", sk.contact_cN),
            kw.get("contact_tau_ms", sk.contact_tau_ms),
            kw.get("reserved16", 0),
        )
        c = sk.centres if centres is None else centres
        body = head + np.concatenate([c, sk.widths, sk.weights]).astype("<f8").tobytes()
        return body + struct.pack("<I", zlib.crc32(body) & 0xFFFFFFFF)

    assert pack4(base) == base.to_bytes()
    c_hi = base.centres.copy()
    c_hi[-1] = 2.0 * np.pi
    c_eq = base.centres.copy()
    c_eq[3] = c_eq[2]
    return [
        ("version_6.skill", pack4(base, version=6), 202),
        ("p_header_size.skill", pack4(base, header_size=152), 211),
        ("p_kind_2.skill", pack4(base, kind=2), 228),
        ("p_reserved.skill", pack4(base, reserved16=1), 228),
        ("p_contact_tau_only.skill", pack4(base, contact_tau_ms=50), 233),
        ("p_contact_tau_max.skill", pack4(base, contact_cN=200, contact_tau_ms=10001), 233),
        ("p_discrete_amplitude.skill", pack4(discrete, amplitude_N=1.0), 228),
        ("p_nan_amplitude.skill", pack4(base, amplitude_N=np.nan), 206),
        ("p_centre_2pi.skill", pack4(base, centres=c_hi), 231),
        ("p_centres_equal.skill", pack4(base, centres=c_eq), 231),
        ("p_y_flag.skill", pack4(base, flags=base.flags | 0x0002), 203),
        ("p_amplitude_0.skill", pack4(base, amplitude_N=0.0), 230),
        ("p_period.skill", pack4(base, duration_s=base.duration_s * (1.0 + 1e-6)), 229),
    ]


def discrete_as_v4(base: Skill) -> Skill:
    """A discrete skill written as format v4 (kind 0, periodic fields 0)."""
    sk = Skill.from_bytes(base.to_bytes())
    sk.format_version = 4
    return sk


KERNELS = (10, 50, 100)
METHODS = ("ridge", "lwr")
# (goal_scale, time_scale): every skill at (1, 1); N = 50 skills also scaled.
SCALES_ALL = ((1.0, 1.0),)
SCALES_N50 = ((1.5, 1.0), (1.0, 1.3), (1.5, 1.3))


def skill_name(demo: str, n: int, method: str, end: str) -> str:
    return f"{demo}_n{n}_{method}_{end}"


def rollout_csv(skill: Skill, goal_scale: float, time_scale: float) -> bytes:
    t, f = dmp.rollout(skill, goal_scale=goal_scale, time_scale=time_scale)
    lines = ["t,f_hat"] + [f"{a:.17g},{b:.17g}" for a, b in zip(t.tolist(), f.tolist(), strict=False)]
    return ("\n".join(lines) + "\n").encode()


def fitted_skills() -> dict[str, Skill]:
    """The skills of the golden set, fitted afresh."""
    out: dict[str, Skill] = {}
    for dname, (make, k) in DEMOS.items():
        demo = make()
        for n in KERNELS:
            for i, method in enumerate(METHODS):
                end = "release" if (n // 10 + i) % 2 else "hold"  # both policies for each method
                res = fit(
                    demo,
                    k,
                    n_kernels=n,
                    method=method,
                    end_policy=end,
                    surface_m=synthetic.SURFACE_M,
                    gains=gains_for_object(k, OBJECT_MASS_KG),
                )
                out[skill_name(dname, n, method, end)] = res.skill
    return out


def fitted_y_skills() -> dict[str, tuple[Skill, tuple[tuple[float, float, float], ...]]]:
    """The skills with a y DMP and their scales, fitted afresh."""
    make, k = WIPE_DEMO
    demo = make()
    out = {}
    for name, n, method, end, scales in WIPE_SKILLS:
        res = fit(
            demo,
            k,
            n_kernels=n,
            method=method,
            end_policy=end,
            surface_m=synthetic.SURFACE_M,
            gains=gains_for_object(k, OBJECT_MASS_KG),
        )
        out[name] = (res.skill, scales)
    return out


def rollout_y_csv(skill: Skill, goal_scale: float, time_scale: float, path_scale: float) -> bytes:
    t, f = dmp.rollout(skill, goal_scale=goal_scale, time_scale=time_scale)
    _, y = dmp.rollout_path(skill, time_scale=time_scale, path_scale=path_scale)
    lines = ["t,f_hat,y_hat"] + [
        "{:.17g},{:.17g},{:.17g}".format(*r) for r in zip(t.tolist(), f.tolist(), y.tolist(), strict=False)
    ]
    return ("\n".join(lines) + "\n").encode()


def golden_y(
    skills: dict[str, tuple[Skill, tuple[tuple[float, float, float], ...]]],
) -> tuple[dict[str, bytes], list[str]]:
    """Files and manifest_y lines for the skills with a y DMP."""
    files: dict[str, bytes] = {}
    manifest: list[str] = []
    for name, (sk, scales) in skills.items():
        image = sk.to_bytes()
        files[name + ".skill"] = image
        files[name + ".skill.json"] = sk.to_json().encode()
        parsed = Skill.from_bytes(image)
        for gs, ts, ps in scales:
            csv_name = f"{name}_g{scale_tag(gs)}_t{scale_tag(ts)}_p{scale_tag(ps)}.csv"
            files[csv_name] = rollout_y_csv(parsed, gs, ts, ps)
            manifest.append(f"{name}.skill {gs:g} {ts:g} {ps:g} {csv_name}")
    return files, manifest


def scale_tag(x: float) -> str:
    return f"{x:g}".replace(".", "p")


def golden(skills: dict[str, Skill]) -> tuple[dict[str, bytes], list[str]]:
    """Files (name -> bytes) and manifest lines for the given skills (rollouts of their images)."""
    files: dict[str, bytes] = {}
    manifest: list[str] = []
    for name, sk in skills.items():
        image = sk.to_bytes()
        files[name + ".skill"] = image
        files[name + ".skill.json"] = sk.to_json().encode()
        parsed = Skill.from_bytes(image)  # roll out exactly what the file holds
        scales = SCALES_ALL + (SCALES_N50 if sk.n_kernels == 50 else ())
        for gs, ts in scales:
            csv_name = f"{name}_g{scale_tag(gs)}_t{scale_tag(ts)}.csv"
            files[csv_name] = rollout_csv(parsed, gs, ts)
            manifest.append(f"{name}.skill {gs:g} {ts:g} {csv_name}")
    return files, manifest


# ---- corrupt images ------------------------------------------------------------------------

_HDR = struct.Struct("<IHHIHH15d")
_F64 = _F64_NAMES  # the header's float64 fields in file order (the model's own list)
#: a v1 image (metres, k-dependent gains): 14 f64 in a 128-byte header
_HDR_V1 = struct.Struct("<IHHIHH14d")


def pack(
    fields: dict[str, Any], centres: np.ndarray, widths: np.ndarray, weights: np.ndarray, fix_crc: bool = True
) -> bytes:
    """An image from raw fields (magic, version, header_size, total_length, n, flags, f64s)."""
    head = _HDR.pack(
        fields["magic"],
        fields["version"],
        fields["header_size"],
        fields["total_length"],
        fields["n"],
        fields["flags"],
        *(float(fields[k]) for k in _F64),
    )
    body = (
        head
        + np.asarray(centres, "<f8").tobytes()
        + np.asarray(widths, "<f8").tobytes()
        + np.asarray(weights, "<f8").tobytes()
    )
    crc = zlib.crc32(body) & 0xFFFFFFFF if fix_crc else fields.get("crc", 0)
    return body + struct.pack("<I", crc)


def bad_images(base: Skill) -> list[tuple[str, bytes, int]]:
    """(file name, bytes, expected code) for every rejection, from a valid N = 10 skill."""
    n = base.n_kernels
    f0: dict[str, Any] = {
        "magic": MAGIC,
        "version": 2,
        "header_size": HEADER_SIZE,
        "total_length": HEADER_SIZE + 24 * n + 4,
        "n": n,
        "flags": base.flags,
    }
    f0.update({k: getattr(base, k) for k in _F64})
    c, w, wt = base.centres.copy(), base.widths.copy(), base.weights.copy()
    good = pack(f0, c, w, wt)
    assert good == base.to_bytes()

    def mod(**kw: Any) -> bytes:
        f = dict(f0)
        f.update(kw)
        return pack(f, c, w, wt)

    def arr(centres: np.ndarray = c, widths: np.ndarray = w, weights: np.ndarray = wt) -> bytes:
        return pack(f0, centres, widths, weights)

    out: list[tuple[str, bytes, int]] = []
    out.append(("short_header.skill", good[:100], 200))
    out.append(("empty.skill", b"", 200))
    out.append(("magic.skill", mod(magic=0x4C4B5347), 201))
    v1_head = _HDR_V1.pack(MAGIC, 1, 128, 128 + 24 * n + 4, n, 0, *([1.0] * 14))
    v1_body = v1_head + np.concatenate([c, w, wt]).astype("<f8").tobytes()
    out.append(("version_1.skill", v1_body + struct.pack("<I", zlib.crc32(v1_body) & 0xFFFFFFFF), 202))
    out.append(("version_0.skill", mod(version=0), 202))
    out.append(("header_size.skill", mod(header_size=120), 211))
    out.append(("length_field.skill", mod(total_length=f0["total_length"] + 24), 203))
    out.append(("length_truncated.skill", good[:-8], 203))
    out.append(("length_trailing.skill", good + b"\0\0\0\0", 203))
    bad_crc = bytearray(good)
    bad_crc[HEADER_SIZE + 16 * n + 3] ^= 0x40  # a weight byte
    out.append(("crc.skill", bytes(bad_crc), 204))
    e = np.zeros(0)
    out.append(("kernels_0.skill", pack(dict(f0, n=0, total_length=HEADER_SIZE + 4), e, e, e), 205))
    n2 = MAX_KERNELS + 1
    c2 = np.linspace(0.0, 0.99, n2)
    w2 = np.full(n2, 0.5 * (c2[1] - c2[0]))
    out.append(
        (
            f"kernels_{n2}.skill",
            pack(dict(f0, n=n2, total_length=HEADER_SIZE + 24 * n2 + 4), c2, w2, np.zeros(n2)),
            205,
        )
    )
    wt_nan = wt.copy()
    wt_nan[3] = np.nan
    out.append(("nan_weight.skill", arr(weights=wt_nan), 206))
    out.append(("inf_tau.skill", mod(tau_s=np.inf), 206))
    out.append(("nan_surface.skill", mod(surface_m=np.nan), 206))
    out.append(("nan_force0.skill", mod(force0_N=np.nan), 206))
    c_nan = c.copy()
    c_nan[0] = np.nan
    out.append(("nan_centre.skill", arr(centres=c_nan), 206))
    out.append(("range_dt_zero.skill", mod(dt_s=0.0), 207))
    out.append(("range_dt_big.skill", mod(dt_s=0.2), 207))
    out.append(("range_tau.skill", mod(tau_s=-1.0), 207))
    out.append(("range_duration_zero.skill", mod(duration_s=0.0), 207))
    out.append(("range_duration_big.skill", mod(duration_s=3601.0), 207))
    out.append(("range_stiffness.skill", mod(stiffness_Npm=0.0), 207))
    out.append(("range_goal.skill", mod(goal_N=-0.5), 207))
    w_zero = w.copy()
    w_zero[4] = 0.0
    out.append(("range_width.skill", arr(widths=w_zero), 207))
    c_dec = c.copy()
    c_dec[5], c_dec[6] = c[6], c[5]
    out.append(("centres_order.skill", arr(centres=c_dec), 208))
    c_eq = c.copy()
    c_eq[2] = c_eq[1]
    out.append(("centres_equal.skill", arr(centres=c_eq), 208))
    c_hi = c.copy()
    c_hi[-1] = 1.0 + 1e-9
    out.append(("centres_above_1.skill", arr(centres=c_hi), 208))
    c_lo = c.copy()
    c_lo[0] = -1e-12
    out.append(("centres_below_0.skill", arr(centres=c_lo), 208))
    out.append(("gains_alpha.skill", mod(alpha=base.alpha * (1.0 + 1e-6)), 209))
    out.append(("gains_gamma.skill", mod(gamma=base.gamma * (1.0 - 1e-6)), 209))
    out.append(("gains_kd_le_md.skill", mod(k_d_Nspm=base.m_d_kg), 209))
    # beta > alpha/4 with alpha/beta/gamma consistent with the stored gains (phase overshoots)
    g_hi = Gains(base.m_d_kg, base.k_d_Nspm, 1500.0, base.kkf_Npm, base.kki_Npms)
    alpha, gamma = base.alpha, base.gamma
    beta = (g_hi.k_p_Npm + g_hi.kkf_Npm - g_hi.m_d_kg * gamma) / (g_hi.m_d_kg * alpha) - 1.0
    assert beta > alpha / 4
    out.append(("gains_beta_gt_alpha_4.skill", mod(k_p_Npm=1500.0, beta=beta), 209))
    out.append(("flag_y_axis.skill", mod(flags=0x0002), 210))  # the y DMP needs version 3
    out.append(("flag_unknown.skill", mod(flags=0x0100), 210))
    return out


_HDR3 = struct.Struct("<IHHIHH17d")


def bad_images_y(base: Skill) -> list[tuple[str, bytes, int]]:
    """Version-3 rejections (the y half) from a valid skill with a y DMP."""
    assert base.y_weights is not None
    n = base.n_kernels
    names = (*_F64, *_F64_NAMES_Y)

    def pack3(yw: np.ndarray, n_y: int | None = None, **kw: Any) -> bytes:
        f = {k: getattr(base, k) for k in names}
        f.update({k: v for k, v in kw.items() if k in names})
        flags = kw.get("flags", base.flags)
        hsize = kw.get("header_size", 152)
        length = kw.get("total_length", 152 + 32 * n + 4)
        head = _HDR3.pack(MAGIC, 3, hsize, length, n, flags, *(float(f[k]) for k in names))
        body = head + np.concatenate([base.centres, base.widths, base.weights, yw]).astype("<f8").tobytes()
        return body + struct.pack("<I", zlib.crc32(body) & 0xFFFFFFFF)

    yw = base.y_weights
    good = pack3(yw)
    assert good == base.to_bytes()
    out: list[tuple[str, bytes, int]] = []
    out.append(("y_header_size.skill", pack3(yw, header_size=136), 211))
    out.append(("y_length_no_flag.skill", pack3(yw, flags=base.flags & ~0x0002), 203))
    bad = yw.copy()
    bad[2] = np.inf
    out.append(("y_inf_weight.skill", pack3(bad), 206))
    out.append(("y_nan_goal.skill", pack3(yw, goal_y_m=np.nan), 206))
    # beta_y = k_p/(m_d*alpha) - 1 > alpha/4 while the force DMP's alpha, beta, gamma stay valid
    from forceskill.model.params import derive

    g = Gains(base.m_d_kg, base.k_d_Nspm, 1500.0, base.kkf_Npm, base.kki_Npms + 340.0 * base.alpha)
    p = derive(g)
    out.append(
        (
            "y_beta_gt_alpha_4.skill",
            pack3(yw, k_p_Npm=g.k_p_Npm, kki_Npms=g.kki_Npms, alpha=p.alpha, beta=p.beta, gamma=p.gamma),
            209,
        )
    )
    return out


#: the contact-wait vectors: (name, skill, goal, amplitude, time scale, threshold N, tau s, the
#: window without contact [s), ticks)
CONTACT_VECTORS = (
    ("contact_press_n50_lwr_hold", "press_n50_lwr_hold", 1.0, 1.0, 1.0, 0.5, 0.02, (0.6, 0.9), 2000),
    ("contact_press_n50_lwr_hold_tau0", "press_n50_lwr_hold", 1.5, 1.0, 1.3, 0.5, 0.0, (0.6, 0.9), 2000),
    ("contact_periodic_n50_ridge", "periodic_n50_ridge", 1.0, 1.0, 1.0, 1.0, 0.05, (0.3, 0.5), 1200),
    ("contact_periodic_n50_ridge_a1p5", "periodic_n50_ridge", 1.2, 1.5, 1.3, 1.0, 0.2, (0.4, 1.0), 2000),
)


def golden_contact(images: dict[str, bytes]) -> tuple[dict[str, bytes], list[str]]:
    """The contact-wait CSVs and manifest lines of CONTACT_VECTORS, from the given images."""
    files: dict[str, bytes] = {}
    manifest: list[str] = []
    for name, skill, gs, amp, ts, thr, tau, window, n in CONTACT_VECTORS:
        sk = Skill.from_bytes(images[skill + ".skill"])
        fc, f_hat, rate, hold = contact.loss_window(sk, n, window, thr, tau, gs, ts, amp)
        rows = ["t,f_contact,rate,f_hat"]
        cols = zip(fc.tolist(), rate.tolist(), f_hat.tolist(), strict=True)
        rows += [f"{j * sk.dt_s:.17g},{a:.17g},{b:.17g},{c:.17g}" for j, (a, b, c) in enumerate(cols)]
        files[name + ".csv"] = ("\n".join(rows) + "\n").encode()
        manifest.append(f"{skill}.skill {gs:g} {amp:g} {ts:g} {thr:g} {tau:g} {hold!r} {name}.csv")
    return files, manifest


def write_contact(images: dict[str, bytes]) -> int:
    """Write the contact-wait files (golden_contact) next to this script; their count."""
    files, manifest = golden_contact(images)
    for name, data in files.items():
        (HERE / name).write_bytes(data)
    (HERE / "manifest_contact.txt").write_text("\n".join(manifest) + "\n")
    return len(files)


def main() -> int:
    if "--periodic-y" in sys.argv[1:]:
        print(f"wrote {write_periodic_y()} periodic y-path files")
        return 0
    if "--band" in sys.argv[1:]:
        print(f"wrote {write_band()} band files")
        return 0
    if "--contact" in sys.argv[1:]:
        images = {p.name: p.read_bytes() for p in HERE.glob("*.skill")}
        print(f"wrote {write_contact(images)} contact-wait rollouts")
        return 0
    skills = fitted_skills()
    files, manifest = golden(skills)
    y_skills = fitted_y_skills()
    files_y, manifest_y = golden_y(y_skills)
    files.update(files_y)
    p_skills = fitted_periodic_skills()
    files_p, manifest_p = golden_periodic(p_skills)
    files.update(files_p)
    for old in HERE.glob("*.skill*"):
        old.unlink()
    for old in HERE.glob("*.csv"):
        old.unlink()
    for name, data in files.items():
        (HERE / name).write_bytes(data)
    (HERE / "manifest.txt").write_text("\n".join(manifest) + "\n")
    (HERE / "manifest_y.txt").write_text("\n".join(manifest_y) + "\n")
    (HERE / "manifest_periodic.txt").write_text("\n".join(manifest_p) + "\n")
    write_contact({k: v for k, v in files.items() if k.endswith(".skill")})
    write_periodic_y()
    write_band()
    bad_dir = HERE / "bad"
    bad_dir.mkdir(exist_ok=True)
    for old in bad_dir.glob("*.skill"):
        old.unlink()
    base = skills[skill_name("press", 10, "ridge", "release")]
    lines = []
    base_y = y_skills["wipe_n10_ridge_hold"][0]
    bad_p = bad_images_periodic(p_skills["periodic_n20_ridge"][0], discrete_as_v4(base))
    bad_b = bad_images_band(next(iter(fitted_band_skills().values()))[0])
    for name, data, code in bad_images(base) + bad_images_y(base_y) + bad_p + bad_b:
        (bad_dir / name).write_bytes(data)
        lines.append(f"{name} {code}")
    (bad_dir / "manifest.txt").write_text("\n".join(lines) + "\n")
    total = sum(p.stat().st_size for p in HERE.rglob("*") if p.is_file())
    print(
        f"wrote {len(files)} files, {len(manifest)} rollouts, {len(lines)} bad images; "
        f"tests/vectors is {total / 1e6:.2f} MB"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
