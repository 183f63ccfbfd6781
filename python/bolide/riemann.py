"""Exact solution of the Riemann problem for the one-dimensional Euler
equations of an ideal gas, P = (gamma - 1) rho u_int, following Toro (2009),
"Riemann Solvers and Numerical Methods for Fluid Dynamics", 3rd ed.,
chapter 4.  Equation numbers below are Toro's.

The star-region pressure p* is the root of f(p) = f_L(p) + f_R(p) + du
(eq. 4.5), found by Newton iteration (eq. 4.44) from the adaptive initial
guess of section 4.3.2 / 9.5.1; u* follows from eq. 4.9.  The self-similar
solution W(x/t) is sampled as in section 4.5 (figures 4.14, 4.15), vectorised
over x/t.  Cases where the data generate a vacuum (eq. 4.40) are refused.

Usage:
    sol = RiemannSolution((1.0, 0.0, 1.0), (0.125, 0.0, 0.1), gamma=1.4)
    sol.p_star, sol.u_star, sol.rho_star_left, sol.rho_star_right
    rho, u, p = sol.sample(x / t)
"""

import numpy as np


class RiemannSolution:
    """Exact solution of one Riemann problem.

    left, right: (rho, u, p) of the two initial states (rho, p > 0).
    gamma:       ratio of specific heats (> 1).
    Attributes after construction: p_star, u_star, rho_star_left,
    rho_star_right, and the wave speeds (see `wave_speeds`).
    """

    def __init__(self, left, right, gamma=1.4, tol=1e-15, max_iter=100):
        self.gamma = float(gamma)
        if not self.gamma > 1.0:
            raise ValueError("gamma must exceed 1, got %g" % self.gamma)
        self.rho_l, self.u_l, self.p_l = (float(v) for v in left)
        self.rho_r, self.u_r, self.p_r = (float(v) for v in right)
        if min(self.rho_l, self.rho_r, self.p_l, self.p_r) <= 0.0:
            raise ValueError("densities and pressures must be positive")
        g = self.gamma
        self.c_l = np.sqrt(g * self.p_l / self.rho_l)
        self.c_r = np.sqrt(g * self.p_r / self.rho_r)
        # Pressure positivity condition, eq. 4.40: otherwise vacuum appears.
        if 2.0 * (self.c_l + self.c_r) / (g - 1.0) <= self.u_r - self.u_l:
            raise ValueError("the initial data generate a vacuum (Toro eq. 4.40)")
        self.p_star = self._solve_p_star(tol, max_iter)
        fl, _ = self._f_k(self.p_star, self.rho_l, self.p_l, self.c_l)
        fr, _ = self._f_k(self.p_star, self.rho_r, self.p_r, self.c_r)
        self.u_star = 0.5 * (self.u_l + self.u_r) + 0.5 * (fr - fl)  # eq. 4.9
        self.rho_star_left = self._rho_star(self.rho_l, self.p_l)
        self.rho_star_right = self._rho_star(self.rho_r, self.p_r)

    # ----------------------------------------------------------- star region
    def _f_k(self, p, rho_k, p_k, c_k):
        """f_K(p) and its derivative, eqs. 4.6-4.7 (shock branch for p > p_K,
        rarefaction branch otherwise) and eq. 4.37."""
        g = self.gamma
        if p > p_k:
            a_k = 2.0 / ((g + 1.0) * rho_k)
            b_k = (g - 1.0) / (g + 1.0) * p_k
            q = np.sqrt(a_k / (b_k + p))
            return (p - p_k) * q, q * (1.0 - 0.5 * (p - p_k) / (b_k + p))
        ratio = p / p_k
        f = 2.0 * c_k / (g - 1.0) * (ratio ** ((g - 1.0) / (2.0 * g)) - 1.0)
        df = 1.0 / (rho_k * c_k) * ratio ** (-(g + 1.0) / (2.0 * g))
        return f, df

    def _initial_guess(self):
        """Adaptive guess (Toro section 9.5.1): the primitive-variable
        estimate (eq. 4.47) when it lies between p_L and p_R; the
        two-rarefaction estimate (eq. 4.46) below; two-shock (eq. 4.48)
        above."""
        g = self.gamma
        rl, ul, pl, cl = self.rho_l, self.u_l, self.p_l, self.c_l
        rr, ur, pr, cr = self.rho_r, self.u_r, self.p_r, self.c_r
        p_pv = max(0.0, 0.5 * (pl + pr) - 0.125 * (ur - ul) * (rl + rr) * (cl + cr))
        p_min, p_max = min(pl, pr), max(pl, pr)
        if p_min <= p_pv <= p_max:
            return max(p_pv, 1e-300)
        if p_pv < p_min:
            z = (g - 1.0) / (2.0 * g)
            p_tr = ((cl + cr - 0.5 * (g - 1.0) * (ur - ul))
                    / (cl / pl ** z + cr / pr ** z)) ** (1.0 / z)
            return max(p_tr, 1e-300)
        a_l, b_l = 2.0 / ((g + 1.0) * rl), (g - 1.0) / (g + 1.0) * pl
        a_r, b_r = 2.0 / ((g + 1.0) * rr), (g - 1.0) / (g + 1.0) * pr
        g_l = np.sqrt(a_l / (p_pv + b_l))
        g_r = np.sqrt(a_r / (p_pv + b_r))
        p_ts = (g_l * pl + g_r * pr - (ur - ul)) / (g_l + g_r)
        return max(p_ts, 1e-300)

    def _solve_p_star(self, tol, max_iter):
        """Newton iteration on f(p) (eq. 4.44) with the relative change
        criterion of eq. 4.45.  f is monotone and concave (section 4.3.1), so
        Newton converges from any positive guess; a negative iterate is
        replaced by a fraction of the previous one."""
        du = self.u_r - self.u_l
        p = self._initial_guess()
        for _ in range(max_iter):
            fl, dfl = self._f_k(p, self.rho_l, self.p_l, self.c_l)
            fr, dfr = self._f_k(p, self.rho_r, self.p_r, self.c_r)
            p_new = p - (fl + fr + du) / (dfl + dfr)
            if p_new <= 0.0:
                p_new = 0.1 * p
            change = 2.0 * abs(p_new - p) / (p_new + p)
            p = p_new
            if change < tol:
                return p
        if change < 1e-12:
            return p  # converged to rounding; the last digit oscillates
        raise RuntimeError("Newton iteration for p* did not converge (change %g)" % change)

    def _rho_star(self, rho_k, p_k):
        """Density behind a shock (eq. 4.50/4.57) or rarefaction (eq. 4.53/4.60)."""
        g = self.gamma
        ratio = self.p_star / p_k
        if ratio > 1.0:
            gm = (g - 1.0) / (g + 1.0)
            return rho_k * (ratio + gm) / (gm * ratio + 1.0)
        return rho_k * ratio ** (1.0 / g)

    # ------------------------------------------------------------ wave speeds
    def wave_speeds(self):
        """Dictionary of the characteristic speeds of the solution:
        left_head, left_tail (equal, the shock speed S_L, for a left shock,
        eq. 4.52), contact (u*), right_tail, right_head (S_R for a right
        shock, eq. 4.59; head S_HR and tail S_TR of a rarefaction, eqs.
        4.55/4.62)."""
        g = self.gamma
        out = {"contact": self.u_star}
        if self.p_star > self.p_l:
            s = self.u_l - self.c_l * np.sqrt((g + 1.0) / (2.0 * g) * self.p_star / self.p_l
                                              + (g - 1.0) / (2.0 * g))
            out["left_head"] = out["left_tail"] = s
        else:
            c_star = self.c_l * (self.p_star / self.p_l) ** ((g - 1.0) / (2.0 * g))
            out["left_head"] = self.u_l - self.c_l
            out["left_tail"] = self.u_star - c_star
        if self.p_star > self.p_r:
            s = self.u_r + self.c_r * np.sqrt((g + 1.0) / (2.0 * g) * self.p_star / self.p_r
                                              + (g - 1.0) / (2.0 * g))
            out["right_head"] = out["right_tail"] = s
        else:
            c_star = self.c_r * (self.p_star / self.p_r) ** ((g - 1.0) / (2.0 * g))
            out["right_head"] = self.u_r + self.c_r
            out["right_tail"] = self.u_star + c_star
        return out

    # --------------------------------------------------------------- sampling
    def sample(self, xi):
        """rho, u, p of the self-similar solution at xi = (x - x0) / t
        (array or scalar; x0 is the initial discontinuity).  Section 4.5."""
        g = self.gamma
        xi = np.asarray(xi, dtype=float)
        scalar = xi.ndim == 0
        xi = np.atleast_1d(xi)
        rho = np.empty_like(xi)
        u = np.empty_like(xi)
        p = np.empty_like(xi)
        speeds = self.wave_speeds()
        left = xi <= self.u_star

        # Left of the contact: W_L, (fan), W*_L.
        head, tail = speeds["left_head"], speeds["left_tail"]
        m = left & (xi < head)
        rho[m], u[m], p[m] = self.rho_l, self.u_l, self.p_l
        m = left & (xi >= tail)
        rho[m], u[m], p[m] = self.rho_star_left, self.u_star, self.p_star
        m = left & (xi >= head) & (xi < tail)  # empty for a shock
        if np.any(m):  # left rarefaction fan, eq. 4.56
            base = 2.0 / (g + 1.0) + (g - 1.0) / ((g + 1.0) * self.c_l) * (self.u_l - xi[m])
            rho[m] = self.rho_l * base ** (2.0 / (g - 1.0))
            u[m] = 2.0 / (g + 1.0) * (self.c_l + 0.5 * (g - 1.0) * self.u_l + xi[m])
            p[m] = self.p_l * base ** (2.0 * g / (g - 1.0))

        # Right of the contact: W*_R, (fan), W_R.
        right = ~left
        head, tail = speeds["right_head"], speeds["right_tail"]
        m = right & (xi > head)
        rho[m], u[m], p[m] = self.rho_r, self.u_r, self.p_r
        m = right & (xi <= tail)
        rho[m], u[m], p[m] = self.rho_star_right, self.u_star, self.p_star
        m = right & (xi > tail) & (xi <= head)
        if np.any(m):  # right rarefaction fan, eq. 4.63
            base = 2.0 / (g + 1.0) - (g - 1.0) / ((g + 1.0) * self.c_r) * (self.u_r - xi[m])
            rho[m] = self.rho_r * base ** (2.0 / (g - 1.0))
            u[m] = 2.0 / (g + 1.0) * (-self.c_r + 0.5 * (g - 1.0) * self.u_r + xi[m])
            p[m] = self.p_r * base ** (2.0 * g / (g - 1.0))
        if scalar:
            return rho[0], u[0], p[0]
        return rho, u, p


def shock_tube(x, t, left, right, gamma, x_left, x_right=None, box_length=None):
    """Exact solution in a shock tube with one or two interfaces.

    x:        positions (array).
    t:        time (> 0).
    left, right: (rho, u, p) of the left (usually dense) and right states.
    One interface (x_right None): the left state fills x < x_left, the right
    state x >= x_left, in an unbounded tube.
    Two interfaces (periodic tube of length box_length): the left state fills
    x_left <= x < x_right (modulo box_length), the right state the rest.  The
    Riemann problem at x_right has the left state on its left (the usual
    orientation); the one at x_left is mirrored (right state on its left).
    Each x takes the solution of the nearest interface (periodic distance),
    which is exact until the waves of the two interfaces meet (see
    `tube_valid_until`).
    Returns rho, u, p arrays.
    """
    x = np.asarray(x, dtype=float)
    forward = RiemannSolution(left, right, gamma)
    if x_right is None:
        return forward.sample((x - x_left) / t)
    if box_length is None:
        raise ValueError("two interfaces need the periodic box_length")
    backward = RiemannSolution(right, left, gamma)
    half = 0.5 * box_length
    d_r = np.mod(x - x_right + half, box_length) - half
    d_l = np.mod(x - x_left + half, box_length) - half
    use_r = np.abs(d_r) <= np.abs(d_l)
    rho, u, p = np.empty_like(x), np.empty_like(x), np.empty_like(x)
    for sol, d, m in ((forward, d_r, use_r), (backward, d_l, ~use_r)):
        rho[m], u[m], p[m] = sol.sample(d[m] / t)
    return rho, u, p


def tube_valid_until(left, right, gamma, x_left, x_right, box_length):
    """Latest time at which `shock_tube` with two interfaces is exact: the
    outermost waves of neighbouring interfaces have not reached each other."""
    fwd = RiemannSolution(left, right, gamma).wave_speeds()
    bwd = RiemannSolution(right, left, gamma).wave_speeds()
    gap_left_state = np.mod(x_right - x_left, box_length)  # left state region
    gap_right_state = box_length - gap_left_state
    # Left-state region: bwd's right-going waves meet fwd's left-going waves.
    closing_1 = max(bwd["right_head"], 0.0) - min(fwd["left_head"], 0.0)
    closing_2 = max(fwd["right_head"], 0.0) - min(bwd["left_head"], 0.0)
    t1 = gap_left_state / closing_1 if closing_1 > 0 else np.inf
    t2 = gap_right_state / closing_2 if closing_2 > 0 else np.inf
    return min(t1, t2)
