"""The loop analysis (postprocess/tbagspost/hysteresis.py) on loops whose stiffness and damping
are known in closed form, and the Ramberg-Osgood fit on synthetic Masing loops."""
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "postprocess"))
from tbagspost import hysteresis as hy  # noqa: E402


def sine(n=400, a=2.0):
    th = 2 * np.pi * np.arange(n) / n
    return th, a * np.sin(th)


def test_ellipse_of_a_viscous_spring():
    """S = K u + c du/dtheta: an ellipse. S_max = a sqrt(K^2 + c^2), W_d = pi c a^2, so
    h = c / (2 sqrt(K^2 + c^2)); the polygon of n points has area pi c a^2 sin(2 pi/n) n/(2 pi)."""
    K, c, a, n = 3.0, 0.8, 2.0, 400
    th, u = sine(n, a)
    S = K * u + c * a * np.cos(th)
    m = hy.measure(u, S)
    polygon = np.pi * c * a ** 2 * np.sin(2 * np.pi / n) * n / (2 * np.pi)
    assert m.W_d == pytest.approx(polygon, rel=1e-12)
    assert m.W_d == pytest.approx(np.pi * c * a ** 2, rel=1e-4)
    assert m.K_eq == pytest.approx(np.hypot(K, c), rel=1e-4)
    assert m.h_eq == pytest.approx(c / (2 * np.hypot(K, c)), rel=2e-4)


def epp(u, k, F):
    """Elastic-perfectly plastic spring along the path u (exact return mapping)."""
    S = np.zeros_like(u)
    for i in range(1, len(u)):
        S[i] = np.clip(S[i - 1] + k * (u[i] - u[i - 1]), -F, F)
    return S


def test_bilinear_loop_polygon_is_exact():
    """The elastic-perfectly plastic loop as its parallelogram (vertices only): W_d = 4 F (a - d_y),
    K_eq = F / a, h = (2/pi)(1 - d_y/a), to round-off."""
    k, F, a = 10.0, 5.0, 2.0
    dy = F / k
    u = np.array([a, a - 2 * dy, -a, -a + 2 * dy])
    S = np.array([F, -F, -F, F])
    m = hy.measure(u, S)
    assert m.W_d == pytest.approx(4 * F * (a - dy), rel=1e-14)
    assert m.K_eq == pytest.approx(F / a, rel=1e-14)
    assert m.h_eq == pytest.approx(2 / np.pi * (1 - dy / a), rel=1e-14)


def test_bilinear_loop_sampled_like_a_run():
    """The same spring driven by a sine and sampled 400 times per cycle (second cycle, stable):
    the corners fall between samples, so within 1e-3."""
    k, F, a, n = 10.0, 5.0, 2.0, 400
    th = 2 * np.pi * np.arange(2 * n) / n
    u = a * np.sin(th)
    S = epp(u, k, F)[n:]
    m = hy.measure(u[n:], S)
    assert m.h_eq == pytest.approx(2 / np.pi * (1 - F / k / a), rel=1e-3)
    assert m.K_eq == pytest.approx(F / a, rel=1e-3)


def test_rigid_plastic_coulomb_loop():
    """Coulomb friction (a stiff EPP spring): h = 2/pi."""
    _, u = sine(2000, 1.0)
    u = np.concatenate([u, u])
    S = epp(u, 1e7, 3.0)[2000:]
    m = hy.measure(u[2000:], S)
    assert m.h_eq == pytest.approx(2 / np.pi, rel=1e-3)
    assert m.S_a == pytest.approx(3.0)


def test_a_wrong_area_fails():
    """The check can fail: the area without closing the loop is off for the Coulomb loop."""
    _, u = sine(400, 1.0)
    S = np.where(np.gradient(u) >= 0, 1.0, -1.0)
    open_area = float(np.trapz(S, u))
    assert abs(open_area - hy.loop_area(u, S)) > 0.01


def test_masing_loop_damping_is_the_closed_form():
    """A dense Masing loop of an R-O model has the damping h = (2/pi)(r-1)/(r+1)(1 - K_eq/K0)."""
    ro = hy.RO(K0=2.0e5, S_y=300.0, r=2.4)
    for S_a in (50.0, 300.0, 900.0):
        u, S = ro.loop(S_a, n=20000)
        m = hy.measure(u, S)
        assert m.K_eq / ro.K0 == pytest.approx(ro.secant_ratio(S_a), rel=1e-6)
        assert m.h_eq == pytest.approx(ro.damping(S_a), rel=2e-3)


def test_backbone_inverse():
    ro = hy.RO(K0=2.0e5, S_y=300.0, r=2.4)
    S = np.array([-800.0, -10.0, 0.0, 5.0, 600.0])
    assert np.allclose(ro.S(ro.u(S)), S, rtol=1e-12, atol=1e-9)


def test_fit_recovers_known_parameters():
    """Masing loops of a known R-O model sampled as the deck samples a run (a sine in u, 200
    rows per cycle, at six amplitudes): the fit returns K0, S_y, r within 1 %."""
    true = hy.RO(K0=1.8e5, S_y=250.0, r=2.2)
    loops = []
    for ua in (0.25e-3, 0.5e-3, 1e-3, 2e-3, 3e-3, 5e-3):
        S_a = float(true.S(ua)[0])
        th = 2 * np.pi * (np.arange(200) + 0.5) / 200
        u = ua * np.sin(th)
        # S along the Masing branches of the loop through +-(ua, S_a), for these u
        down = np.cos(th) < 0
        S = np.where(down, S_a - 2 * true.S((ua - u) / 2), -S_a + 2 * true.S((u + ua) / 2))
        loops.append((u, S))
    f = hy.fit(loops)
    assert f.model.K0 == pytest.approx(true.K0, rel=0.01)
    assert f.model.S_y == pytest.approx(true.S_y, rel=0.01)
    assert f.model.r == pytest.approx(true.r, rel=0.01)
    assert f.rms_loops < 0.01
    # a wrong model does not fit: r forced far off leaves a large error
    bad = hy.RO(K0=true.K0, S_y=true.S_y, r=3.5)
    err = [np.abs(bad.branch_u(S, *hy.branches(u, S)) - u).max() / np.abs(u).max() for u, S in loops]
    assert max(err) > 0.05
