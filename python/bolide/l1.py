"""L1 error of particle values against an analytic profile.

Definition used by every Bolide tool and test (state it when quoting a
number):

    L1(f) = sum_i w_i |f_i - f(x_i)| / sum_i w_i

over the particles i in the chosen region, with weights w_i = 1 by default
(the plain mean over particles, as in the Sod comparisons of Springel 2010,
MNRAS 401, 791, section 8.1) or w_i = m_i / rho_i (volume weights, which
approximate (1/V) int |f - f_exact| dV for particles of unequal volume).  The
result has the units of f; with `relative=True` it is divided by the same
weighted mean of |f(x_i)|, which makes it dimensionless.
"""

import numpy as np


def l1_error(values, exact, mask=None, weights=None, relative=False):
    """L1 error of VALUES (per particle) against EXACT (the analytic profile
    evaluated at the particles' positions).

    mask:     boolean array selecting the region (None: every particle).
    weights:  per-particle weights w_i (None: equal weights).
    relative: divide by the weighted mean of |exact| (dimensionless result).
    Raises ValueError for mismatched shapes, an empty region or non-finite
    values.
    """
    values = np.asarray(values, dtype=float)
    exact = np.asarray(exact, dtype=float)
    if values.shape != exact.shape:
        raise ValueError("values and exact differ in shape: %s vs %s"
                         % (values.shape, exact.shape))
    w = np.ones_like(values) if weights is None else np.asarray(weights, dtype=float)
    if w.shape != values.shape:
        raise ValueError("weights have shape %s, values %s" % (w.shape, values.shape))
    if mask is not None:
        mask = np.asarray(mask, dtype=bool)
        values, exact, w = values[mask], exact[mask], w[mask]
    if values.size == 0:
        raise ValueError("no particle in the region of the L1 error")
    if not (np.all(np.isfinite(values)) and np.all(np.isfinite(exact))):
        raise ValueError("non-finite value in the L1 error")
    wsum = np.sum(w)
    if not wsum > 0:
        raise ValueError("the weights of the L1 error sum to %g" % wsum)
    err = np.sum(w * np.abs(values - exact)) / wsum
    if relative:
        scale = np.sum(w * np.abs(exact)) / wsum
        if scale == 0:
            raise ValueError("relative L1 error of an identically zero profile")
        err /= scale
    return float(err)
