"""Sine, cosine, arctangent, logarithm, exponential, hypotenuse and normal draws that give
the same bits on every machine.

glibc picks its maths functions by CPU at load time (``__sin_fma`` where the CPU has
FMA, other code where it has not), and numba's ``np.sin``, ``math.atan2``, ``np.log`` and
friends call them; so do numpy's own ``np.sin`` and ``np.cos`` on arrays. The variants
differ in the last bit of some results (4 million random arguments in [-7, 7] on one
machine, with ``GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA`` and without: every one of
sin, cos, atan2, log, exp and log1p gave other bits somewhere). A robot's heading
integrates those bits every tick it moves, so the same seed grew other shapes on
another machine (starfish seed 1 after 9000 s).

The functions here use only +, -, *, / and sqrt, each correctly rounded by IEEE 754,
in a fixed order (numba fuses no multiply-add without fast-math flags), so they give
one answer everywhere. They are the classic fdlibm algorithms (Cody-Waite reduction
and minimax polynomials, whose published coefficients they use), accurate to about one
unit in the last place: far below anything the simulated physics can notice. Every
function takes and returns float64 (radians for angles).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

# pi/2 in three pieces of 33 bits each (k * piece is exact for |k| < 2**20)
_PIO2_1 = 1.57079632673412561417e00
_PIO2_2 = 6.07710050630396597660e-11
_PIO2_3 = 2.02226624871116645580e-21
_INV_PIO2 = 6.36619772367581382433e-01

# sin(x) = x + x^3 * S(x^2) and cos(x) = 1 - x^2/2 + x^4 * C(x^2) on [-pi/4, pi/4]
_S1 = -1.66666666666666324348e-01
_S2 = 8.33333333332248946124e-03
_S3 = -1.98412698298579493134e-04
_S4 = 2.75573137070700676789e-06
_S5 = -2.50507602534068634195e-08
_S6 = 1.58969099521155010221e-10
_C1 = 4.16666666666666019037e-02
_C2 = -1.38888888888741095749e-03
_C3 = 2.48015872894767294178e-05
_C4 = -2.75573143513906633035e-07
_C5 = 2.08757232129817482790e-09
_C6 = -1.13596475577881948265e-11

# atan: breakpoints' arctangents (high and low parts) and the odd polynomial's terms
_ATAN_HI = (
    4.63647609000806093515e-01,
    7.85398163397448278999e-01,
    9.82793723247329054082e-01,
    1.57079632679489655800e00,
)
_ATAN_LO = (
    2.26987774529616870924e-17,
    3.06161699786838301793e-17,
    1.39033110312309984516e-17,
    6.12323399573676603587e-17,
)
_AT0 = 3.33333333333329318027e-01
_AT1 = -1.99999999998764832476e-01
_AT2 = 1.42857142725034663711e-01
_AT3 = -1.11111104054623557880e-01
_AT4 = 9.09088713343650656196e-02
_AT5 = -7.69187620504482999495e-02
_AT6 = 6.66107313738753120669e-02
_AT7 = -5.83357013379057348645e-02
_AT8 = 4.97687799461593236017e-02
_AT9 = -3.65315727442169155270e-02
_AT10 = 1.62858201153657823623e-02
_PI = 3.14159265358979311600e00
_PI_LO = 1.22464679914735317723e-16

# log(1 + f) = f - f^2/2 + s * (f^2/2 + R(s^2)), s = f / (2 + f)
_LN2_HI = 6.93147180369123816490e-01
_LN2_LO = 1.90821492927058770002e-10
_LG1 = 6.666666666666735130e-01
_LG2 = 3.999999999940941908e-01
_LG3 = 2.857142874366239149e-01
_LG4 = 2.222219843214978396e-01
_LG5 = 1.818357216161805012e-01
_LG6 = 1.531383769920937332e-01
_LG7 = 1.479819860511658591e-01
_SQRT_HALF = 7.07106781186547524401e-01

# exp(r) = 1 + 2r / (R(r) - r) on |r| <= ln2 / 2, R(r) = 2 + r^2 P(r^2)
_INV_LN2 = 1.44269504088896338700e00
_P1 = 1.66666666666666019037e-01
_P2 = -2.77777777770155933842e-03
_P3 = 6.61375632143793436117e-05
_P4 = -1.65339022054652515390e-06
_P5 = 4.13813679705723846039e-08

# the normal ziggurat: layers, the base layer's right edge r, and each layer's area
_ZIG_LAYERS = 256
_ZIG_R = 3.6541528853610088
_ZIG_AREA = 4.92867323399e-03


@njit(cache=True, inline="always")
def _sin_kernel(x):  # type: ignore[no-untyped-def]
    z = x * x
    return x + x * z * (_S1 + z * (_S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * _S6)))))


@njit(cache=True, inline="always")
def _cos_kernel(x):  # type: ignore[no-untyped-def]
    z = x * x
    r = z * z * (_C1 + z * (_C2 + z * (_C3 + z * (_C4 + z * (_C5 + z * _C6)))))
    hz = 0.5 * z
    w = 1.0 - hz
    return w + (((1.0 - w) - hz) + r)


@njit(cache=True, inline="always")
def sin_cos(x):  # type: ignore[no-untyped-def]
    """``(sin(x), cos(x))`` of ``x`` (rad); accurate to about an ulp for |x| < 1.6e6 and
    the same bits everywhere beyond (NaN for infinite or NaN ``x``)."""
    k = np.floor(x * _INV_PIO2 + 0.5)
    y = ((x - k * _PIO2_1) - k * _PIO2_2) - k * _PIO2_3
    s = _sin_kernel(y)
    c = _cos_kernel(y)
    q = np.int64(k) & 3 if math.isfinite(k) else 0
    if q == 0:
        return s, c
    if q == 1:
        return c, -s
    if q == 2:
        return -s, -c
    return -c, s


@njit(cache=True)
def atan(x):  # type: ignore[no-untyped-def]
    """arctan(x) in (-pi/2, pi/2)."""
    if x != x:
        return x
    t = abs(x)
    if t >= 1e17:
        part = _ATAN_HI[3] + _ATAN_LO[3]
        return part if x > 0 else -part
    idx = -1
    if t < 0.4375:
        if t < 1e-9:
            return x
    elif t < 0.6875:
        idx = 0
        t = (2.0 * t - 1.0) / (2.0 + t)
    elif t < 1.1875:
        idx = 1
        t = (t - 1.0) / (t + 1.0)
    elif t < 2.4375:
        idx = 2
        t = (t - 1.5) / (1.0 + 1.5 * t)
    else:
        idx = 3
        t = -1.0 / t
    z = t * t
    w = z * z
    s1 = z * (_AT0 + w * (_AT2 + w * (_AT4 + w * (_AT6 + w * (_AT8 + w * _AT10)))))
    s2 = w * (_AT1 + w * (_AT3 + w * (_AT5 + w * (_AT7 + w * _AT9))))
    tail = t * (s1 + s2)
    r = t - tail if idx < 0 else _ATAN_HI[idx] - ((tail - _ATAN_LO[idx]) - t)
    return r if x >= 0 else -r


@njit(cache=True)
def atan2(y, x):  # type: ignore[no-untyped-def]
    """The angle of the point (x, y) in [-pi, pi] (rad), as ``math.atan2``."""
    if x != x or y != y:
        return x + y
    if y == 0.0:
        if x > 0.0 or (x == 0.0 and math.copysign(1.0, x) > 0):
            return y  # +-0
        return _PI if math.copysign(1.0, y) > 0 else -_PI
    if x == 0.0:
        return 0.5 * _PI if y > 0 else -0.5 * _PI
    if math.isinf(x) or math.isinf(y):
        if math.isinf(x) and math.isinf(y):
            a = 0.25 * _PI if x > 0 else 0.75 * _PI
        elif math.isinf(x):
            a = 0.0 if x > 0 else _PI
        else:
            a = 0.5 * _PI
        return a if y > 0 else -a
    a = atan(abs(y / x))
    if x < 0.0:
        a = _PI - (a - _PI_LO)
    return a if y > 0 else -a


@njit(cache=True)
def log(x):  # type: ignore[no-untyped-def]
    """Natural logarithm of ``x`` (-inf at 0, NaN below 0)."""
    if x != x or x < 0.0:
        return np.nan
    if x == 0.0:
        return -np.inf
    if math.isinf(x):
        return x
    m, e = math.frexp(x)  # x = m * 2**e, m in [0.5, 1): exact
    if m < _SQRT_HALF:
        m *= 2.0
        e -= 1
    f = m - 1.0
    k = float(e)
    s = f / (2.0 + f)
    z = s * s
    w = z * z
    t1 = w * (_LG2 + w * (_LG4 + w * _LG6))
    t2 = z * (_LG1 + w * (_LG3 + w * (_LG5 + w * _LG7)))
    r = t2 + t1
    hfsq = 0.5 * f * f
    return k * _LN2_HI - ((hfsq - (s * (hfsq + r) + k * _LN2_LO)) - f)


@njit(cache=True)
def exp(x):  # type: ignore[no-untyped-def]
    """e to the power ``x`` (0 below -745, inf above 709.78)."""
    if x != x:
        return x
    if x > 709.782712893384:
        return np.inf
    if x < -745.1332191019411:
        return 0.0
    k = np.floor(x * _INV_LN2 + 0.5)
    hi = x - k * _LN2_HI
    lo = k * _LN2_LO
    r = hi - lo
    z = r * r
    c = r - z * (_P1 + z * (_P2 + z * (_P3 + z * (_P4 + z * _P5))))
    y = 1.0 - ((lo - (r * c) / (2.0 - c)) - hi)
    return math.ldexp(y, int(k))


def _ziggurat_tables() -> tuple[np.ndarray, np.ndarray]:
    """The normal ziggurat's layer edges x_0 > x_1 = r > ... > x_256 = 0 and the density
    exp(-x^2 / 2) at each ((257,) float64 each), computed with this module's functions so
    that they are the same everywhere. Layer 0 is the base strip with the tail beyond r,
    its width the strip's area over f(r)."""
    # (the functions' Python bodies: CPython's float arithmetic rounds as the compiled
    # code does, and no compile is needed at import)
    exp_, log_ = exp.py_func, log.py_func
    x = np.zeros(_ZIG_LAYERS + 1)
    f = np.ones(_ZIG_LAYERS + 1)
    x[0] = _ZIG_AREA / exp_(-0.5 * _ZIG_R * _ZIG_R)
    x[1] = _ZIG_R
    for i in range(1, _ZIG_LAYERS - 1):
        inner = _ZIG_AREA / x[i] + exp_(-0.5 * x[i] * x[i])
        x[i + 1] = math.sqrt(-2.0 * log_(inner)) if inner < 1.0 else 0.0
    for i in range(_ZIG_LAYERS):
        f[i] = exp_(-0.5 * x[i] * x[i])
    return x, f


_ZIG_X, _ZIG_F = _ziggurat_tables()


@njit(cache=True, inline="always")
def _ziggurat_point(rng):  # type: ignore[no-untyped-def]
    """One try of the ziggurat: a uniform picks layer ``i`` (its top 8 bits) and the point
    ``x`` in it (the rest); ``inside`` when x lies in the layer's rectangle (accepted)."""
    u = rng.random() * _ZIG_LAYERS
    i = int(u)
    x = (2.0 * (u - i) - 1.0) * _ZIG_X[i]
    return i, x, abs(x) < _ZIG_X[i + 1]


@njit(cache=True)
def _normal_beyond(rng, i, x):  # type: ignore[no-untyped-def]
    """The rest of :func:`normal`'s draw when its first point ``x`` in layer ``i`` fell
    outside the layer's rectangle: the curve test with :func:`exp`, or the tail beyond r
    with :func:`log` for the base layer, and new tries until one is accepted. Kept out of
    line, so that the 98.5 % of draws that end in the rectangle stay a few instructions
    (inlined whole, the draw was too large for LLVM to inline into the radio)."""
    while True:
        if i == 0:
            while True:
                a = -log(1.0 - rng.random()) / _ZIG_R
                b = -log(1.0 - rng.random())
                if b + b >= a * a:
                    return _ZIG_R + a if x > 0.0 else -(_ZIG_R + a)
        y = _ZIG_F[i] + rng.random() * (_ZIG_F[i + 1] - _ZIG_F[i])
        if y < exp(-0.5 * x * x):
            return x
        i, x, inside = _ziggurat_point(rng)
        if inside:
            return x


@njit(cache=True, inline="always")
def normal(rng):  # type: ignore[no-untyped-def]
    """One standard normal draw from ``rng`` (a numpy Generator): Marsaglia and Tsang's
    ziggurat with 256 layers. One uniform picks the layer (its top 8 bits) and the point
    in it (the other 45); 98.5 % of draws end there, the others test the curve with
    :func:`exp` or draw the tail beyond r with :func:`log` (:func:`_normal_beyond`)."""
    i, x, inside = _ziggurat_point(rng)
    if inside:
        return x
    return _normal_beyond(rng, i, x)


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(cache=True, _nrt=True)
def normal_array(rng, n):  # type: ignore[no-untyped-def]
    """``n`` standard normal draws from ``rng`` by :func:`normal` ((n,) float64)."""
    out = np.empty(n)
    for k in range(n):
        out[k] = normal(rng)
    return out


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(cache=True, _nrt=True)
def sin_cos_array(angles):  # type: ignore[no-untyped-def]
    """``(sin, cos)`` of every angle of ``angles`` (any shape, rad), as two arrays of the
    same shape."""
    flat = angles.ravel()
    s = np.empty(flat.size)
    c = np.empty(flat.size)
    for k in range(flat.size):
        s[k], c[k] = sin_cos(flat[k])
    return s.reshape(angles.shape), c.reshape(angles.shape)


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(cache=True, _nrt=True)
def atan2_array(y, x):  # type: ignore[no-untyped-def]
    """:func:`atan2` of every pair of ``y`` and ``x`` (1-D float64 arrays of one length)."""
    out = np.empty(y.size)
    for k in range(y.size):
        out[k] = atan2(y[k], x[k])
    return out


# The selectors below take ``SimParams.portable_math`` (true by default since session 53);
# with it off, runs use the platform's maths, as every run did up to session 52.


@njit(cache=True, inline="always")
def sin_cos_as(x, portable):  # type: ignore[no-untyped-def]
    """:func:`sin_cos` when ``portable``, else the platform's ``(np.sin(x), np.cos(x))``."""
    if portable:
        return sin_cos(x)
    return np.sin(x), np.cos(x)


@njit(cache=True, inline="always")
def hypot(x, y):  # type: ignore[no-untyped-def]
    """sqrt(x^2 + y^2) by IEEE arithmetic alone. glibc's ``hypot`` changed its algorithm
    in 2.35 (other last bits on about 0.3 % of arguments), and numba's ``math.hypot``
    calls it. For the millimetre distances etswarm takes it of, the sum of squares can
    neither overflow nor lose the smaller term's bits that matter."""
    return math.sqrt(x * x + y * y)


@njit(cache=True, inline="always")
def hypot_as(x, y, portable):  # type: ignore[no-untyped-def]
    """:func:`hypot` when ``portable``, else the platform's ``math.hypot``."""
    if portable:
        return hypot(x, y)
    return math.hypot(x, y)


@njit(cache=True, inline="always")
def atan2_as(y, x, portable):  # type: ignore[no-untyped-def]
    """:func:`atan2` when ``portable``, else the platform's ``math.atan2``."""
    if portable:
        return atan2(y, x)
    return math.atan2(y, x)


@njit(cache=True, inline="always")
def log_as(x, portable):  # type: ignore[no-untyped-def]
    """:func:`log` when ``portable``, else the platform's ``np.log``."""
    if portable:
        return log(x)
    return np.log(x)


@njit(cache=True, inline="always")
def normal_as(rng, portable):  # type: ignore[no-untyped-def]
    """:func:`normal` when ``portable``, else ``rng.standard_normal()`` (numpy's own
    ziggurat, which calls the platform's exp and log on rare draws)."""
    if portable:
        return normal(rng)
    return rng.standard_normal()
