"""Dense output of the compiled integrator: the cubic Hermite interpolant of an
accepted step, and the samples it records at requested times."""

from __future__ import annotations

from numba import njit


@njit(cache=True)
def hermite(t0, h, y0, f0, y1, f1, tau, out) -> None:
    """Cubic Hermite interpolation between (t0, y0, f0) and (t0 + h, y1, f1).

    Parameters
    ----------
    t0, h : float
        Start time and length of the step [s].
    y0, f0, y1, f1 : ndarray
        States and derivatives at both ends of the step.
    tau : float
        Time to interpolate at [s], in [t0, t0 + h].
    out : ndarray
        Output: the interpolated state.
    """
    s = (tau - t0) / h
    h00 = (1.0 + 2.0 * s) * (1.0 - s) ** 2
    h10 = s * (1.0 - s) ** 2
    h01 = s * s * (3.0 - 2.0 * s)
    h11 = s * s * (s - 1.0)
    for i in range(y0.shape[0]):
        out[i] = h00 * y0[i] + h * h10 * f0[i] + h01 * y1[i] + h * h11 * f1[i]


@njit(cache=True, inline="always")
def record_samples(
    t, h, y, f0, ynew, f1, t_end, t1, mode, sample_times, i_sample, samples, sample_modes, yint
) -> int:
    """Record the samples whose times fall in (t, t_end] (and before ``t1``) [s] from the
    Hermite interpolant of the accepted step of ``h`` [s] from (t, y, f0) to (ynew, f1).

    Each sample's row of ``sample_modes`` gets the modes in force over the step;
    ``yint`` is overwritten. Returns the index of the next sample to record.
    """
    n = y.shape[0]
    n_samples = sample_times.shape[0]
    while i_sample < n_samples and sample_times[i_sample] <= t_end:
        if sample_times[i_sample] >= t1:
            break
        hermite(t, h, y, f0, ynew, f1, sample_times[i_sample], yint)
        for i in range(n):
            samples[i_sample, i] = yint[i]
        for i in range(mode.shape[0]):
            sample_modes[i_sample, i] = mode[i]
        i_sample += 1
    return i_sample
