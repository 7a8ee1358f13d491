"""Several demonstrations of one task: trimming, affine alignment, mean, outliers, band."""

from __future__ import annotations

import numpy as np

from forceskill.model import multi, synthetic
from forceskill.model.demo import Demo


def test_trim_lead_keeps_the_whole_rise_and_a_short_quiet_lead() -> None:
    _, demos = synthetic.pressing_set(seed=1, n=1)
    d = demos[0]
    trimmed, lead = multi.trim_lead(d, 0.001)
    level = float(np.median(d.force_N[:50]))
    onset = float(d.t_s[np.flatnonzero(np.abs(d.force_N - level) > 0.3)[0]])
    # the slow rise crosses 0.3 N well after it began: the trim goes back to its start
    assert onset - 0.6 < lead < onset - multi.LEAD_KEEP_S - 0.1
    assert abs(float(np.mean(trimmed.force_N[:50])) - level) < 0.02
    assert trimmed.t_s[0] == 0.0 and trimmed.force_N.size == d.force_N.size - round(lead / 0.001)


def test_register_recovers_a_known_stretch_and_lag() -> None:
    t = np.arange(6001) * 0.001
    f = np.interp(t, [0, 1, 2, 3, 4, 6], [0, 3, 3, 5, 5, 5])
    tau = np.linspace(0.0, 6.0, 600)
    s_true, lag_true = 1.13, 0.08
    tt = np.arange(int(7.0 / 0.001)) * 0.001
    g = np.interp((tt - lag_true) / s_true, t, f)  # recording time = s*tau + lag
    s, lag, gain = multi.register(tt, g, tau, np.interp(tau, t, f), 6.0)
    assert abs(s - s_true) < 0.005 and abs(lag - lag_true) < 0.01 and abs(gain - 1.0) < 0.01


def test_mean_profile_is_closer_to_the_truth_than_each_recording() -> None:
    truth, demos = synthetic.pressing_set(seed=2, n=6)
    mp = multi.mean_profile(demos, 0.001)
    assert all(a.used and not a.outlier for a in mp.alignments)
    assert abs(np.mean([a.stretch for a in mp.alignments]) - 1.0) < 1e-9
    f_max = float(np.max(truth.force_N))

    def err(t: np.ndarray, f: np.ndarray) -> float:  # best affine alignment on the truth
        tau = np.linspace(0.0, truth.t_s[-1], 600)
        s, lag, _ = multi.register(t, f, tau, np.interp(tau, truth.t_s, truth.force_N), truth.t_s[-1])
        return float(
            np.max(np.abs(np.interp(s * tau + lag, t, f) - np.interp(tau, truth.t_s, truth.force_N)))
        )

    e_mean = err(mp.demo.t_s, mp.demo.force_N)
    e_single = [err(d.t_s, d.force_N) for d in demos]
    assert e_mean < 0.6 * float(np.median(e_single)), (e_mean / f_max, np.array(e_single) / f_max)
    assert mp.sigma_N.shape == mp.demo.force_N.shape and np.all(mp.sigma_N >= 0.0)


def test_an_outlier_is_named_and_left_out_unless_kept() -> None:
    _, demos = synthetic.pressing_set(seed=1, n=5)
    odd = synthetic.engraving(seed=4, duration_s=6.5, k_v=100.0, f_max_N=4.5, noise_N=0.03)
    demos.insert(2, Demo(odd.t_s, odd.pos_m, odd.force_N, "odd"))
    mp = multi.mean_profile(demos, 0.001)
    assert [a.outlier for a in mp.alignments] == [False, False, True, False, False, False]
    assert [a.used for a in mp.alignments] == [True, True, False, True, True, True]
    kept = multi.mean_profile(demos, 0.001, keep_outliers=True)
    assert kept.alignments[2].outlier and all(a.used for a in kept.alignments)


def test_two_recordings_name_no_outlier() -> None:
    _, demos = synthetic.pressing_set(seed=5, n=2)
    mp = multi.mean_profile(demos, 0.001)
    assert not any(a.outlier for a in mp.alignments) and all(a.used for a in mp.alignments)
