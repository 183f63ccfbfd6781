"""Sedov-Taylor similarity solution for a point explosion of energy E in a
uniform, cold (zero-pressure) ideal gas of density rho0 in three dimensions
(Sedov 1959, "Similarity and Dimensional Methods in Mechanics", ch. IV;
Taylor 1950, Proc. R. Soc. A 201, 159; Kamm & Timmes 2007, LA-UR-07-2849).

The shock is at R(t) = xi0 (E t^2 / rho0)^(1/5) and moves at D = dR/dt =
2R / (5t).  With lambda = r/R the flow is

    rho = rho0 G(lambda),  v = D V(lambda),  P = rho0 D^2 Pi(lambda),

and the Euler equations (spherical, adiabatic) reduce to three ODEs in
lambda, derived in theory/analytic.md (A8)-(A10):

    (V - lambda) G' + G V' + 2 G V / lambda = 0                 (mass)
    (V - lambda) V' + Pi' / G + k V = 0                         (momentum)
    (V - lambda) (Pi'/Pi - gamma G'/G) + 2 k = 0                (entropy)

with k = (alpha - 1)/alpha = -3/2 for R ~ t^alpha, alpha = 2/5.  They start
from the strong-shock Rankine-Hugoniot values at lambda = 1 (Zel'dovich &
Raizer 1967, eq. 1.111):

    G = (gamma+1)/(gamma-1),  V = Pi = 2/(gamma+1),

and are integrated inwards (in ln lambda, with ln G and ln Pi as unknowns,
which keeps the power-law behaviour near the centre smooth) by an adaptive
8th-order Runge-Kutta method (DOP853).  Integrated inwards the regular
solution is unstable near the centre, so the table stops at the radius
lambda_min (about 0.01-0.4 depending on gamma) where V/lambda is closest to
its central limit 1/gamma; inside it the centre's power laws
G ~ lambda^(3/(gamma-1)), V ~ lambda, Pi = const take over.  The energy
integral then fixes xi0:

    E = 4 pi rho0 D^2 R^3 I,   I = int_0^1 (G V^2 / 2 + Pi/(gamma-1)) lambda^2 dlambda,
    so xi0 = (25 / (16 pi I))^(1/5).

This is the numerical route to the same solution that Kamm & Timmes (2007)
write in closed form; it agrees with their alpha (E = alpha rho0 R^5/t^2 with
alpha = xi0^-5) to the precision of the integration (see the tests).
"""

import numpy as np
from scipy.integrate import DOP853, OdeSolution, simpson


class SedovSolution:
    """Similarity solution for one gamma (3D, uniform ambient medium).

    Attributes: gamma, xi0, and the tabulated profile (lam, G, V, Pi) from
    lambda = 1 down to lambda_min.
    """

    def __init__(self, gamma=5.0 / 3.0, lambda_min=1e-8, rtol=1e-12, atol=1e-14):
        g = float(gamma)
        if not g > 1.0:
            raise ValueError("gamma must exceed 1, got %g" % g)
        self.gamma = g
        self._k = (0.4 - 1.0) / 0.4  # (alpha - 1)/alpha with alpha = 2/5

        y0 = [np.log((g + 1.0) / (g - 1.0)), 2.0 / (g + 1.0), np.log(2.0 / (g + 1.0))]

        # Integrated inwards, the regular solution (V -> lambda/gamma at the
        # centre) is unstable: rounding and truncation errors grow like
        # lambda^-3 and drive V/lambda away from 1/gamma until the step size
        # collapses.  Integrate as far as it goes, then keep the part down to
        # the radius where V/lambda is closest to 1/gamma (the physical
        # approach decays inwards, the error grows) and use the centre's
        # power laws below it.
        solver = DOP853(self._rhs, 0.0, y0, np.log(lambda_min), rtol=rtol, atol=atol)
        times, pieces, best = [0.0], [], np.inf
        while solver.status == "running":
            solver.step()
            if solver.status == "failed":
                break
            times.append(solver.t)
            pieces.append(solver.dense_output())
            if solver.t < np.log(0.5):
                drift = abs(g * solver.y[1] / np.exp(solver.t) - 1.0)
                best = min(best, drift)
                if drift > 1e-3 and drift > 1e3 * best:
                    break  # well into the growing error: stop
        if len(times) < 2 or times[-1] > np.log(0.5):
            raise RuntimeError("Sedov ODE integration failed near lambda = %g" % np.exp(times[-1]))
        dense = OdeSolution(times, pieces)
        s_end = times[-1]
        s_probe = np.linspace(s_end, np.log(0.5), 8001)
        y_probe = dense(s_probe)
        drift = np.abs(g * y_probe[1] / np.exp(s_probe) - 1.0)
        s_cut = s_probe[np.argmin(drift)]
        self._dense = dense
        self.lambda_min = float(np.exp(s_cut))
        #: Largest relative deviation of V/lambda from 1/gamma at lambda_min.
        self.centre_mismatch = float(drift.min())

        # Fine table in ln(lambda) for quadrature and interpolation.
        s = np.linspace(s_cut, 0.0, 20001)
        y = dense(s)
        self.lam = np.exp(s)
        self.G = np.exp(y[0])
        self.V = y[1]
        self.Pi = np.exp(y[2])
        # Energy integral (Simpson in s = ln lambda, dlambda = lambda ds) plus
        # the core below lambda_min from the power laws of profiles_lambda:
        # G = G_m x^n, V = V_m x, Pi = Pi_m with x = lambda/lambda_m,
        # n = 3/(gamma-1).
        integrand = (0.5 * self.G * self.V ** 2 + self.Pi / (g - 1.0)) * self.lam ** 3
        n = 3.0 / (g - 1.0)
        lm = self.lambda_min
        core = (0.5 * self.G[0] * self.V[0] ** 2 / (n + 5.0) + self.Pi[0] / (3.0 * (g - 1.0))) * lm ** 3
        self.energy_integral = simpson(integrand, x=s) + core
        self.xi0 = (25.0 / (16.0 * np.pi * self.energy_integral)) ** 0.2
        self.alpha = self.xi0 ** -5  # Kamm & Timmes' alpha: E = alpha rho0 R^5 / t^2

    def _rhs(self, s, y):
        """d/ds of (ln G, V, ln Pi), s = ln lambda; the three ODEs solved for
        the derivatives (a 3x3 linear system solved by hand)."""
        g, k = self.gamma, self._k
        lam = np.exp(s)
        G, V, Pi = np.exp(y[0]), y[1], np.exp(y[2])
        w = V - lam
        # dV/dlambda from eliminating G' and Pi' (mass and entropy equations).
        dV = (-k * V * G * w + 2.0 * g * Pi * V / lam + 2.0 * k * Pi) / (G * w * w - g * Pi)
        dlnG = -(dV + 2.0 * V / lam) / w
        dlnPi = g * dlnG - 2.0 * k / w
        return [lam * dlnG, lam * dV, lam * dlnPi]

    # ----------------------------------------------------------------- scales
    def shock_radius(self, t, E=1.0, rho0=1.0):
        """R(t) = xi0 (E t^2 / rho0)^(1/5)."""
        return self.xi0 * (E * np.asarray(t, dtype=float) ** 2 / rho0) ** 0.2

    def shock_speed(self, t, E=1.0, rho0=1.0):
        """D = dR/dt = 2 R / (5 t)."""
        return 0.4 * self.shock_radius(t, E, rho0) / t

    def profiles_lambda(self, lam):
        """G, V, Pi at lambda = r/R (array).  Outside the shock (lambda > 1):
        G = 1, V = Pi = 0.  Below lambda_min: the centre's power laws
        G ~ lambda^(3/(gamma-1)), V ~ lambda, Pi = const (Sedov 1959 ch. IV
        section 11), continued from the tabulated values."""
        lam = np.asarray(lam, dtype=float)
        G = np.ones_like(lam)
        V = np.zeros_like(lam)
        Pi = np.zeros_like(lam)
        inner = (lam <= 1.0) & (lam >= self.lambda_min)
        if np.any(inner):
            y = self._dense(np.log(lam[inner]))
            G[inner], V[inner], Pi[inner] = np.exp(y[0]), y[1], np.exp(y[2])
        core = lam < self.lambda_min
        if np.any(core):
            x = lam[core] / self.lambda_min
            G[core] = self.G[0] * x ** (3.0 / (self.gamma - 1.0))
            V[core] = self.V[0] * x
            Pi[core] = self.Pi[0]
        return G, V, Pi

    def moment_coefficient(self, n=200001):
        """I = int_0^1 (G(lambda) - 1) lambda^3 dlambda: the first radial
        moment of the excess density, int (rho - rho0) r dV = 4 pi rho0 R^4 I.
        Mass conservation makes int (G - 1) lambda^2 dlambda = 0, so I < 0
        measures how far the swept-up mass moved out (theory/analytic.md)."""
        lam = np.linspace(0.0, 1.0, n)
        G, _, _ = self.profiles_lambda(lam)
        return float(np.trapezoid((G - 1.0) * lam ** 3, lam))

    def profiles(self, r, t, E=1.0, rho0=1.0):
        """Density, radial velocity and pressure at radius r (array) and
        time t > 0 for explosion energy E in ambient density rho0."""
        R = self.shock_radius(t, E, rho0)
        D = 0.4 * R / t
        G, V, Pi = self.profiles_lambda(np.asarray(r, dtype=float) / R)
        return rho0 * G, D * V, rho0 * D * D * Pi
