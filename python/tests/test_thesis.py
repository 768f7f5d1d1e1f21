"""The thesis's values through Python, to the printed digit (tests/python/samples.json, generated
from src/samples.rs)."""
import math

import numpy as np
import pytest

import rocking


def prints_as(value, printed, decimals):
    return abs(value - printed) <= 0.5 * 10.0 ** -decimals * (1 + 1e-9)


def test_eq10_mass_matrix(samples):
    case = samples["two_block_impact"]
    M, q = rocking.column_mass_matrix(case["width"], case["height"], case["block_mass"])
    assert M.shape == (4, 4) and q.shape == (4,)
    assert M.dtype == np.float64
    for got, want in zip(M.ravel(), case["thesis_eq10_mass"]):
        assert prints_as(got, want, 3), (got, want)


@pytest.mark.parametrize("solver", ["auto", "enumerate", "projection"])
@pytest.mark.parametrize("answer", [0, 1], ids=["one impact (Eq. 11)", "two impacts (SPEC 2)"])
def test_eq11_two_block_impact(samples, solver, answer):
    case = samples["two_block_impact"]
    a = case["answers"][answer]
    M, _ = rocking.column_mass_matrix(case["width"], case["height"], case["block_mass"])
    status, v, report = rocking.impact_model(
        M, case["status"], case["velocity"], case["closing"], n_impacts=a["n_impacts"], solver=solver
    )
    assert status.dtype == np.int8 and v.dtype == np.float64
    assert status.tolist() == [-1, -1]
    assert prints_as(v[0], a["rates"][0], 4) and prints_as(v[1], a["rates"][1], 4), v
    assert v[2] == 0.0 and v[3] == 0.0
    assert prints_as(100 * report.energy_loss, a["loss_percent"], 1)
    assert report.changed and report.impacts_applied == a["n_impacts"]
    assert report.solver == ("projection" if solver == "projection" else "enumerate")
    assert report.kinetic_before == pytest.approx(0.5 * M[3, 3])


def test_fig19e_top_push_opens_both_ways(samples):
    push = samples["two_block_top_push"]
    for solver in ["enumerate", "projection"]:
        status, acc, report = rocking.opening_model(push["mass"], push["load"], [0, 0], solver=solver)
        assert status.tolist() == push["expected_status"]
        assert report.changed
        # The accelerations live on the chosen DOFs only: phî_0 (bottom, left corner) and phĭ_1.
        assert acc[2] > 0 and acc[1] < 0 and acc[0] == 0 and acc[3] == 0
    holds, reactions, must_open = rocking.check_configuration(push["mass"], push["load"], [0, 0])
    assert not holds and len(must_open) > 0
    assert reactions.shape == (4,)


def test_gravity_alone_keeps_the_column_closed(samples):
    case = samples["two_block_impact"]
    M, q = rocking.column_mass_matrix(case["width"], case["height"], case["block_mass"])
    status, acc, report = rocking.opening_model(M, q, [0, 0])
    assert status.tolist() == [0, 0] and not report.changed and not acc.any()
    holds, reactions, must_open = rocking.check_configuration(M, q, [0, 0])
    assert holds and must_open.size == 0
    # Admissible reactions: λ <= 0 on phĭ, λ >= 0 on phî.
    assert (reactions[:2] <= 0).all() and (reactions[2:] >= 0).all()


@pytest.mark.parametrize("i", range(9))
def test_single_block_energy_losses(samples, i):
    """Thesis Table 1 (Housner) and Appendix A Eq. A3 (Prieto 2007's cut corners)."""
    c = samples["single_block_losses"][i]
    contact = None if c["contact_width"] is None else [c["contact_width"]]
    M, _ = rocking.column_mass_matrix([c["width"]], [c["height"]], [1.0], contact_width=contact)
    status, v, report = rocking.impact_model(M, [1], [0.0, -1.0], 0)
    assert prints_as(100 * report.energy_loss, c["loss_percent"], 1), (c["label"], report.energy_loss)
    if contact is None:
        # Housner's ratio (2h² − b²)/(2h² + 2b²) for the 2h × 2b block (Eq. 1), exact.
        h, b = c["height"] / 2, c["width"] / 2
        assert -v[0] == pytest.approx((2 * h * h - b * b) / (2 * h * h + 2 * b * b), rel=1e-12)


def appendix_c_nodal_model(width, height, block_mass, phi, ag, g=9.81):
    """Three mass points per block on its axis (bottom, centre, top; ends I / (2 (h/2)²)), thesis
    Appendix C, in the geometry of the DOF angles `phi`, with B (Eq. C2, C11, C14) built here from
    the positions: the FE route, independent of the library's closed form."""
    n = len(width)
    half_contact = [0.5 * min(width[k - 1], width[k]) if k else 0.5 * width[0] for k in range(n)]
    # Pose: blocks as rigid transforms (angle, translation), rotations applied bottom-up about
    # each interface's corner in the current geometry.
    angle = [0.0] * n
    shift = [np.zeros(2) for _ in range(n)]

    def place(j, p):
        c, s = math.cos(angle[j]), math.sin(angle[j])
        return np.array([c * p[0] - s * p[1], s * p[0] + c * p[1]]) + shift[j]

    base = np.cumsum([0.0] + list(height[:-1]))
    corners = []  # (right, left) pivot of each interface, current geometry
    for k in range(n):
        right_ref, left_ref = np.array([half_contact[k], base[k]]), np.array([-half_contact[k], base[k]])
        if k == 0:
            right, left = right_ref, left_ref
        else:
            right, left = place(k - 1, right_ref), place(k - 1, left_ref)
        corners.append((right, left))
        theta = phi[k] + phi[n + k]
        if theta:
            pivot = right if phi[k] else left
            c, s = math.cos(theta), math.sin(theta)
            rot = np.array([[c, -s], [s, c]])
            for j in range(k, n):
                angle[j] += theta
                shift[j] = rot @ (shift[j] - pivot) + pivot
    points, masses, owner = [], [], []
    for j in range(n):
        inertia = block_mass[j] * (width[j] ** 2 + height[j] ** 2) / 12
        end = inertia / (2 * (height[j] / 2) ** 2)
        for y, m in [(0.0, end), (0.5 * height[j], block_mass[j] - 2 * end), (height[j], end)]:
            points.append(place(j, np.array([0.0, base[j] + y])))
            masses.append(m)
            owner.append(j)
    npts = len(points)
    B = np.zeros((2 * npts, 2 * n))
    for a in range(2 * n):
        k = a % n
        P = corners[k][0] if a < n else corners[k][1]
        for i, (r, j) in enumerate(zip(points, owner)):
            if j >= k:
                B[i, a] = -(r[1] - P[1])
                B[npts + i, a] = r[0] - P[0]
    nodal_mass = np.diag(masses + masses)
    nodal_load = np.array([-m * ag for m in masses] + [-m * g for m in masses])
    return B, nodal_mass, nodal_load


@pytest.mark.parametrize("i", [0, 1])
def test_appendix_c_both_routes(samples, i):
    """Eq. C12-C16 to the printed digit through column_mass_matrix, and reduce(B, M, p) of the
    three-mass-point model (the FE route) equal to it."""
    ac = samples["appendix_c"]
    answer = ac["answers"][i]
    phi = answer["phi"]
    ag = ac["ground_acceleration"]
    M, q = rocking.column_mass_matrix(ac["width"], ac["height"], ac["block_mass"], phi=phi, ground_acceleration=ag)
    for got, want in zip([M[0, 0], M[0, 1], M[1, 1]], answer["mass"]):
        assert prints_as(got, want, 3), (answer["label"], got, want)
    for got, want in zip(q[:2], answer["load"]):
        assert prints_as(got, want, 3), (answer["label"], got, want)
    B, nodal_mass, nodal_load = appendix_c_nodal_model(ac["width"], ac["height"], ac["block_mass"], phi, ag)
    Mr, qr = rocking.reduce(B, nodal_mass, nodal_load)
    np.testing.assert_allclose(Mr, M, rtol=0, atol=1e-10)
    np.testing.assert_allclose(qr, q, rtol=0, atol=1e-10)


def test_reduction_equals_the_closed_form_in_any_pose():
    width, height, mass = [0.4, 0.3, 0.35], [1.2, 0.9, 1.0], [3.0, 2.0, 2.5]
    for phi in ([0, 0, 0, 0, 0, 0], [-0.05, 0, 0, 0, 0.2, 0], [0, -0.1, 0, 0, 0, 0.03]):
        B, nm, nl = appendix_c_nodal_model(width, height, mass, phi, ag=0.7)
        Mr, qr = rocking.reduce(B, nm, nl)
        M, q = rocking.column_mass_matrix(width, height, mass, phi=phi, ground_acceleration=0.7)
        np.testing.assert_allclose(Mr, M, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(qr, q, rtol=1e-12, atol=1e-12)
        assert rocking.reduce(B, nm)[1] is None
