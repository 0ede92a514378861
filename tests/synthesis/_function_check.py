"""An independent check of a synthesized function generator: its written model solved by circle intersection.

Used by tests/synthesis/test_function.py and tests/cli/test_hostile_function.py; never the engine.
"""

import tomllib

import numpy as np

#: Independent recomputation tolerance: the model file holds 15 significant digits and the engine
#: closes its loops to 1e-12 of the size; 1e-8 rad (or 1e-8 of the size) leaves room for both.
RECOMPUTE_TOL = 1e-8


def _dyad(model, rows, phi0):
    """Output of the written model at design inputs ``rows``, by circle intersection (not the engine).

    The crank turns from its sketch angle by ``rows - phi0``; the driven pin stays on the side of its
    sketch (the assembly branch); returns the output and the assembly margin (<= 0: cannot close).
    """
    P = {k: np.asarray(v, dtype=float) for k, v in model["points"].items()}
    O2, A0, B0 = P["O2"], P["A"], P["B"]
    a = np.hypot(*(A0 - O2))
    th = np.arctan2(A0[1] - O2[1], A0[0] - O2[0]) + (rows - phi0)
    A = O2 + a * np.column_stack([np.cos(th), np.sin(th)])
    b = np.hypot(*(B0 - A0))
    if "O4" not in P:  # slider on the line y = B0.y through B
        e = B0[1]
        side = np.sign(B0[0] - A0[0])
        h2 = b * b - (e - A[:, 1]) ** 2
        margin = (b - np.abs(e - A[:, 1])) / max(a, b)
        return A[:, 0] + side * np.sqrt(np.maximum(h2, 0.0)), margin
    O4 = P["O4"]
    c = np.hypot(*(B0 - O4))
    side = np.sign((A0 - O4)[0] * (B0 - O4)[1] - (A0 - O4)[1] * (B0 - O4)[0])
    v = A - O4
    r = np.hypot(v[:, 0], v[:, 1])
    margin = np.minimum(r - abs(b - c), b + c - r) / max(a, b, c, np.hypot(*(O4 - O2)))
    # B = O4 + c (cos, sin) of the angle of O4->A plus or minus the angle at O4 (law of cosines)
    gamma = np.arccos(np.clip((c * c + r * r - b * b) / (2 * c * r), -1.0, 1.0))
    ang = np.arctan2(v[:, 1], v[:, 0]) + side * gamma  # B counter-clockwise of O4->A when side > 0
    return ang, margin


def recompute(model, input_angle, output, dense_input, dense_desired):
    """Target errors, structural error (max) and assembly margins of a model, without the engine.

    ``model`` is a dict or the path of a written model file; the crank is turned from its sketch by the
    change of the design input from target 1.
    """
    from gearlever.mechanism.modelfile import model_toml

    if not isinstance(model, dict):
        with open(model, "rb") as fh:
            model = tomllib.load(fh)
    else:
        assert tomllib.loads(model_toml(model)) == model  # the result's model is the file's
    phi0 = input_angle[0]
    gen_t, _ = _dyad(model, input_angle, phi0)
    gen_d, margin = _dyad(model, dense_input, phi0)
    if "O4" in model["points"]:
        P = model["points"]
        th0 = np.arctan2(P["B"][1] - P["O4"][1], P["B"][0] - P["O4"][0])
        # the rocker's link angle minus the output (0 or pi): told by target 1 because the library refuses a
        # four-bar missing a target by more than a quarter turn (past it, the nearest half turn is a guess)
        off = np.pi * np.round((th0 - output[0]) / np.pi)
        err_t = np.angle(np.exp(1j * (gen_t - off - output)))
        # the output turns continuously with the crank, from target 1 (where it is the wanted output within pi)
        cont = np.unwrap(gen_d - off)
        at0 = output[0] + err_t[0]
        cont += 2 * np.pi * np.round((at0 - np.interp(phi0, dense_input, cont)) / (2 * np.pi))
        err_d = cont - dense_desired
    else:
        err_t, err_d = gen_t - output, gen_d - dense_desired
    return err_t, np.abs(err_d).max(), margin
