"""hodr: second-order optimisation of discontinuous black boxes, such as renderers.

hodr smooths an objective f with a Gaussian of width sigma and estimates the smoothed
function's gradient, Hessian and Hessian-vector products by Monte Carlo sampling, so a
loss with jumps and plateaus (a shape that does not yet overlap its target) still has
slope and curvature. Its default optimiser, Auto, needs only a start x0 and a scale
sigma0 (the distance over which the parameters matter, as CMA-ES asks for).

    >>> import numpy as np, hodr
    >>> res = hodr.minimize(lambda x: float(np.sum(np.round(x) ** 2)), [3.2, -2.7], 1.0)
    >>> res.success, res.fun
    (True, 0.0)

Functions:

* ``minimize(fun, x0, sigma0, ...)`` -> ``OptimizeResult`` (scipy.optimize style);
* ``Optimizer(x0, sigma0, ...)`` with ``ask()``, ``tell(values)``, ``stop()`` and
  ``result`` (pycma style), for evaluating batches wherever you like;
* ``gradient``, ``hessian``, ``hvp`` -> (estimate, evaluations).

The objective receives float64 numpy arrays: one point of shape (n,), or with
``batch=True`` a (k, n) array of points to evaluate at once (a renderer that renders a
batch), returning k values; anything but real numbers is a TypeError naming ``fun``.
An exception it raises propagates unchanged; Ctrl-C (KeyboardInterrupt) stops the work
within one batch of evaluations, the run so far in the exception's ``result``.
"""

from __future__ import annotations

import functools
import inspect
import numbers
import secrets
import sys
from typing import Any, Callable, Optional, Sequence, Tuple, Union

import numpy as np

from . import _hodr

__all__ = ["OptimizeResult", "Optimizer", "minimize", "gradient", "hessian", "hvp"]

METHODS = ("auto",)


class OptimizeResult(dict):
    """The result of ``minimize``, as in scipy.optimize: a dict whose keys are also
    attributes.

    Attributes
    ----------
    x : ndarray
        The best point found.
    fun : float
        f(x). Where ``fun`` never returned a finite value, the first infinite value it
        returned (NaN where every value was NaN, or before any evaluation).
    nfev : int
        Objective evaluations: the points handed to ``fun`` (after a Ctrl-C, those
        handed to it before).
    nit : int
        Iterations.
    ndescents : int
        Descents the run began: 1, and one more for each fresh start from a point
        jumped away from the best so far (made once a descent has ended, with a
        ``budget``, on an objective that is not ``noisy``; ``options["fresh_starts"]``)
        and for each probe that found a point below it. Restarts within a descent do
        not count.
    success : bool
        True when the run converged (the samples' spread fell below its tolerance)
        or stagnated (no lower value within its patience); False when the budget ran
        out first, the callback stopped it, the run diverged or reached the
        evaluation cap of a run without a budget, or ``fun`` never returned a finite
        value.
    status : int
        0 converged, 1 budget used, 2 stagnated, 3 stopped by the callback, 4
        interrupted (the ``result`` of the KeyboardInterrupt), 5 failed (the
        ``result`` of the ValueError for a non-finite value under
        ``options={"non_finite": "error"}``), 6 diverged (the samples' spread grew
        2**64-fold in some coordinate, or ``fun`` fell below -2**-64 of the largest
        float, whatever the budget: ``fun`` looks unbounded below, or ``sigma0``
        understates the problem's scale about as much), 7 evaluation cap (no
        ``budget`` was given and the run used 1000·(n + 3)**2 evaluations without
        converging: ``fun`` may approach its infimum only at infinity, or be too noisy
        to converge; a ``budget`` runs longer).
    message : str
        Why the run ended.
    history : dict of ndarray
        Per iteration: ``nfev`` (evaluations so far), ``fun`` (f at the best point),
        ``sigma`` (the smoothing width and trust radius) and ``descent`` (the descent
        the run is in once the iteration has ended, from 1).
    seed : int
        The seed the run used: the one given, or the one drawn for ``seed=None``.
        Passing it again repeats the run.
    model : str
        The model the run used, ``"full"`` or ``"diagonal"`` (``options["model"]``): the
        one named, or Auto's own choice.
    """

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError as e:
            raise AttributeError(name) from e

    __setattr__ = dict.__setitem__
    __delattr__ = dict.__delitem__

    def __repr__(self) -> str:
        keys = ("message", "success", "status", "fun", "x", "nit", "nfev", "ndescents", "model",
                "seed")
        width = max(map(len, keys))
        return "\n".join(f"{k.rjust(width)}: {self[k]!r}" for k in keys if k in self)


def _bounds(bounds: Any, n: int) -> Optional[Tuple[list, list]]:
    """(lower, upper) from the forms scipy accepts: an object with ``lb`` and ``ub``
    (``scipy.optimize.Bounds``, scalars or length-n), n (low, high) pairs with None for
    an open side, or one (low, high) pair of scalars for every coordinate."""
    if bounds is None:
        return None
    if hasattr(bounds, "lb") and hasattr(bounds, "ub"):
        limits = (_reals(f"bounds.{side}", getattr(bounds, side)) for side in ("lb", "ub"))
        try:
            lower, upper = (np.broadcast_to(b, (n,)) for b in limits)
        except ValueError:
            raise ValueError(f"bounds: lb and ub must be scalars or have {n} elements") from None
        return lower.tolist(), upper.tolist()
    try:
        pairs = list(bounds)
    except TypeError:
        raise TypeError("bounds must be (low, high) pairs, one (low, high) pair or a Bounds") from None
    if len(pairs) == 2 and all(p is None or np.ndim(p) == 0 for p in pairs):
        pairs = [tuple(pairs)] * n
    if len(pairs) != n or not all(np.ndim(p) == 1 and len(p) == 2 for p in pairs):
        raise ValueError(
            f"bounds must be {n} (low, high) pairs, one (low, high) pair of scalars, or an "
            "object with lb and ub (scipy.optimize.Bounds)"
        )

    def limit(i: int, value: Any, open_side: float) -> float:
        if value is None:
            return open_side
        return _real(f"bounds[{i}]", value, "a pair of real numbers or None")

    lower = [limit(i, lo, -np.inf) for i, (lo, _) in enumerate(pairs)]
    upper = [limit(i, hi, np.inf) for i, (_, hi) in enumerate(pairs)]
    return lower, upper


#: numpy's kinds of real numbers: bool, signed and unsigned int, float.
_REAL_KINDS = "biuf"

#: What an array of another kind holds, for messages.
_KIND_NAMES = {"U": "str", "S": "bytes", "c": "complex", "M": "datetime64", "m": "timedelta64"}


def _reals(name: str, value: Any, what: str = "a real number or a sequence of them") -> np.ndarray:
    """``value`` as a float64 array of its own shape: real numbers (Python or numpy
    floats, ints, bools, or objects with ``__float__`` that are not complex), nested in
    sequences or arrays. TypeError naming ``name`` for anything else (None, strings,
    complex numbers), ValueError for an int too large for a float."""
    if value is None or isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be {what}, got {type(value).__name__}")
    try:
        array = np.asarray(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be {what}, got {type(value).__name__}") from None
    kind = array.dtype.kind
    if kind in _REAL_KINDS:
        return array.astype(float)
    if kind != "O":
        got = type(value).__name__
        if array.ndim > 0:
            got += f" of {_KIND_NAMES.get(kind, str(array.dtype))}"
        raise TypeError(f"{name} must be {what}, got {got}")
    floats = np.empty(array.shape)
    for index in np.ndindex(array.shape):
        element = array[index]
        at = name + "".join(f"[{i}]" for i in index)
        got = type(element).__name__ + (f" at {at}" if index else "")
        if (
            element is None
            or isinstance(element, (str, bytes))
            or (isinstance(element, numbers.Complex) and not isinstance(element, numbers.Real))
            or np.ndim(element) != 0
        ):
            raise TypeError(f"{name} must be {what}, got {got}")
        try:
            floats[index] = float(element)
        except OverflowError:
            raise ValueError(f"{at} is too large for a float") from None
        except (TypeError, ValueError):
            raise TypeError(f"{name} must be {what}, got {got}") from None
    return floats


def _real(name: str, value: Any, what: str = "a real number") -> float:
    """``value`` as a float, or TypeError/ValueError naming ``name`` (as ``_reals``)."""
    array = _reals(name, value, what)
    if array.ndim != 0:
        raise TypeError(f"{name} must be {what}, got {type(value).__name__}")
    return float(array)


def _vector(name: str, value: Any) -> list:
    """A 1-D float vector, or TypeError/ValueError naming the argument."""
    array = _reals(name, value, "a sequence of real numbers")
    if array.ndim != 1:
        raise ValueError(f"{name} must be 1-D, got shape {array.shape}")
    return array.tolist()


def _estimate_args(x: Any, sigma: Any) -> Tuple[list, float]:
    """x as a vector and sigma as a float; TypeError/ValueError naming the argument. (The
    extension refuses a sigma at or below what x's floats resolve, 8·eps·max|x_i|, where
    every sample would round to x and the estimate be an exact, meaningless zero.)"""
    return _vector("x", x), _real("sigma", sigma)


def _scales(sigma0: Any, n: int) -> list:
    """sigma0 as n scales: a real number for every coordinate, or one per coordinate;
    TypeError/ValueError naming it. The extension checks that each is finite and > 0."""
    array = _reals("sigma0", sigma0)
    if array.ndim == 0:
        if not (np.isfinite(array) and array > 0):
            raise ValueError(f"sigma0 must be finite and > 0, got {float(array)}")
        return [float(array)] * n
    if array.ndim != 1 or len(array) != n:
        raise ValueError(
            f"sigma0 must be one scale or {n} (one per coordinate), got shape {array.shape}"
        )
    return array.tolist()


def _log_scale(log_scale: Any, n: int) -> Optional[list]:
    """The coordinates ``log_scale`` marks for a search in log10 (a bool for every
    coordinate, or n bools), as n bools, or None where it marks none; TypeError/ValueError
    naming it. The extension checks x0 and the bounds against it and does the search in
    log10 (``hodr_core::log_scale``)."""
    if log_scale is None:
        return None
    array = np.asarray(log_scale)
    if array.dtype != np.bool_:
        what = type(log_scale).__name__
        if isinstance(log_scale, (list, tuple, np.ndarray)):
            what += f" of dtype {array.dtype}"
        raise TypeError(
            f"log_scale must be a bool or {n} bools (one per coordinate), got {what}"
        )
    if array.ndim == 0:
        array = np.full(n, bool(array))
    if array.shape != (n,):
        raise ValueError(
            f"log_scale must be a bool or {n} bools (one per coordinate), got shape "
            f"{array.shape}"
        )
    return array.tolist() if array.any() else None


OPTIONS = (
    "tolerance", "patience", "restarts", "fresh_starts", "centre", "probes", "non_finite",
    "model",
)


def _settings(options: Any) -> tuple:
    """(tolerance, patience, restarts, fresh_starts, centre, probes, non_finite, model) from
    the ``options`` mapping, each None where it is not given; TypeError/ValueError naming the key. The
    extension checks the ranges."""
    if options is None:
        return (None, None, None, None, None, None, None, None)
    if not hasattr(options, "items"):
        raise TypeError(f"options must be a dict, got {type(options).__name__}")
    unknown = [k for k in options if k not in OPTIONS]
    if unknown:
        raise ValueError(f"unknown option {unknown[0]!r} (options: {', '.join(OPTIONS)})")
    tolerance = options.get("tolerance")
    if tolerance is not None:
        tolerance = _real("options['tolerance']", tolerance)
    patience = options.get("patience")
    if patience is not None:
        patience = _count("options['patience']", patience, 1)
    restarts = options.get("restarts")
    if restarts is not None:
        restarts = _count("options['restarts']", restarts, 0)
    fresh_starts = _flag(options, "fresh_starts")
    centre = _flag(options, "centre")
    probes = options.get("probes")
    if probes is not None:
        probes = _count("options['probes']", probes, 0)
    non_finite = options.get("non_finite")
    if non_finite is not None and not isinstance(non_finite, str):
        raise TypeError("options['non_finite'] must be 'worst' or 'error'")
    model = options.get("model")
    if model is not None and not isinstance(model, str):
        raise TypeError("options['model'] must be 'full' or 'diagonal'")
    return (tolerance, patience, restarts, fresh_starts, centre, probes, non_finite, model)


def _flag(options: Any, key: str) -> Any:
    """options[key] as a bool, None where it is not given; TypeError naming the key."""
    value = options.get(key)
    if value is None:
        return None
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"options[{key!r}] must be a bool, got {type(value).__name__}")
    return bool(value)


#: Bits of the extension's counts (Rust's usize: evaluations, pairs, iterations).
_USIZE_BITS = (2 * sys.maxsize + 1).bit_length()


def _count(name: str, value: Any, minimum: int, bits: int = _USIZE_BITS) -> int:
    """``value`` as an int from ``minimum`` to 2**bits - 1, or TypeError/ValueError
    naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name} must be an int, got {type(value).__name__}")
    value = int(value)
    if value < minimum:
        raise ValueError(f"{name} must be at least {minimum}, got {value}")
    if value.bit_length() > bits:
        got = value if value.bit_length() <= 128 else f"an int of {value.bit_length()} bits"
        raise ValueError(f"{name} must be from {minimum} to 2**{bits} - 1, got {got}")
    return value


def _seed(seed: Any) -> int:
    """The seed: an int from 0 to 2**64 - 1, or for None a fresh one from the operating
    system's entropy (as scipy's and numpy's ``seed=None``)."""
    if seed is None:
        return secrets.randbits(64)
    return _count("seed", seed, 0, 64)


def _with_result(error: BaseException, seed: int, result: Any = None) -> None:
    """Gives ``error`` the run so far as an OptimizeResult: ``result``, or the fields the
    extension attached (with the run's ``seed``)."""
    if result is not None:
        error.result = result
    elif isinstance(getattr(error, "result", None), dict) and not isinstance(
        error.result, OptimizeResult
    ):
        error.result = _result(error.result, seed)


def minimize(
    fun: Callable[[np.ndarray], float],
    x0: Sequence[float],
    sigma0: Union[float, Sequence[float]],
    *,
    args: Any = (),
    bounds: Any = None,
    log_scale: Any = None,
    budget: Optional[int] = None,
    method: str = "auto",
    seed: Optional[int] = 0,
    batch: bool = False,
    noisy: bool = False,
    callback: Optional[Callable[[np.ndarray, float], Any]] = None,
    options: Optional[dict] = None,
    tol: Optional[float] = None,
) -> OptimizeResult:
    """Minimise ``fun`` from ``x0`` with hodr's default optimiser, Auto.

    Auto is a trust-region method on a quadratic model of the Gaussian-smoothed
    objective, fitted to the evaluations it remembers; sigma is both the smoothing
    width and the trust radius, widening on plateaus and shrinking as the model proves
    right. It needs no settings beyond the problem's own.

    Parameters
    ----------
    fun : callable
        ``fun(x) -> float`` for x of shape (n,); with ``batch=True``,
        ``fun(X) -> array of k floats`` (a sequence or 1-D array) for X of shape
        (k, n). A Python or numpy float, int or bool, or a 0-d array, will do; anything
        else (None, a string, a complex number, an array of shape (1,)) is a TypeError.
        NaN or inf counts as worse than any value; a run in which every value was
        non-finite reports the first infinite one as ``fun`` and does not succeed.
        A failed evaluation is repeated at the same point (and seed) until four repeats
        have failed too, then at each doubling of the failures; once one has returned a value, ``fun`` is taken to fail at
        random (a renderer that sometimes crashes) and every failure is repeated while
        the next repeat is likely to return a value, by the rate of random failures and
        the share of failed points that no repeat turns into a value (a wall's) seen so
        far, so a failure rate p costs about 1/(1 - p) of the evaluations.
        Return inf or NaN, or a constant penalty such as 1e10 or ``f + 100``, to
        enforce a constraint other than bounds: the run reaches a minimum that lies on
        such a wall (measured on a half-space at n <= 10, in fewer evaluations than
        pycma).
    x0 : array_like, shape (n,)
        The start.
    sigma0 : float or array_like, shape (n,)
        The scale: how far the parameters must move to make a difference (> 0); one
        per coordinate where they differ (parameters in different units), as pycma's
        ``CMA_stds``. With bounds, a coordinate's scale is cut to a quarter of its
        range where that is narrower. Auto's sigma (``history["sigma"]``) is then the
        scales' geometric mean, its metric stretched along each coordinate by its share.
    args : tuple
        Extra arguments for ``fun``, passed after the point (and after the seed with
        ``noisy``): ``fun(x, *args)``, as in scipy and pycma. A value that is not a
        tuple is the one extra argument.
    bounds : optional
        n ``(low, high)`` pairs as in scipy (None for an open side), one ``(low, high)``
        pair of scalars for every coordinate, or an object with ``lb`` and ``ub`` (a
        ``scipy.optimize.Bounds``); None for unbounded. For arrays ``lower`` and
        ``upper``, pass ``list(zip(lower, upper))``: a pair of two arrays reads as
        per-coordinate pairs when n = 2, as in scipy. Every evaluated point lies inside
        (an x0 outside is projected into the box, as scipy clips it); each pair must
        hold a finite point (low <= high, low < inf, high > -inf). A coordinate bounded
        on both sides is searched across its box: with a budget, one fresh start and
        one probe in five draw anywhere in it, so give None or inf for a side that is
        no bound rather than a large number such as 1e20.
    log_scale : bool or sequence of n bools, optional
        Coordinates searched in log10: a parameter that matters in proportion to its
        size (a rate constant, a learning rate, a regularisation weight), whose box
        spans decades. Auto's point holds log10 x_i there, so a step is a factor, and
        its sigma0 is in decades (1: a factor of 10); x0 must be > 0 there, a lower
        bound at or below 0 (or None) leaves x_i > 0 open, and an upper bound must be
        > 0. ``fun``, ``callback`` and the result see x itself, finite and > 0 there
        however far the search strays. True: every coordinate; default: none.
    budget : int, optional
        At most this many evaluations (never exceeded; 1 to 2**64 - 1). With a
        budget, a deterministic ``fun`` gets it all: once a descent converges or
        stagnates, another starts about the best point (about x0 while no value has
        been finite; basin hopping; ``options["fresh_starts"]``), and the best point of
        all descents is returned, with status 1. Default: until the first descent
        converges, or at most 1000·(n + 3)**2 evaluations (status 7).
    method : str
        ``"auto"`` (the only one).
    seed : int or None
        Seed of every random choice (0 to 2**64 - 1): the same seed gives the same
        points and result. None draws a fresh seed from the operating system; the
        result's ``seed`` is the one used, whichever way it was given.
    batch : bool
        Call ``fun`` with batches of points (see ``fun``).
    noisy : bool
        ``fun`` is stochastic (a Monte Carlo renderer): it is called as
        ``fun(x, seed)`` (with ``batch=True``, ``fun(X, seeds)``, one uint64 seed per
        row) and must draw all of its randomness from the seed, equal seeds giving equal
        noise. Both halves of an antithetic pair get one seed; Auto evaluates each
        iteration's points, θ among them, on one seed, so the renderer's noise cancels
        in their differences, and compares values only within a seed. Without it, a
        ``fun`` that draws fresh noise at every call is noticed (its point is evaluated
        a second time after each restart, and a third once the two differ) and fitted
        robustly, a sampled point replacing the current one only when lower by more
        than the noise's scale; where only a few draws are noisy (outliers on exact
        values), every point is evaluated until two draws agree.
    callback : callable, optional
        ``callback(x, f)`` after every iteration with the best point so far and its
        value; returning True or raising StopIteration stops the run (status 3).
        scipy's forms work too: a callback of one parameter is called as
        ``callback(x)``, and one whose parameter is named ``intermediate_result`` as
        ``callback(OptimizeResult(x=x, fun=f))``.
    options : dict, optional
        Auto's options; none is needed. ``tolerance`` (0 < float < 1): converged once every
        coordinate's spread falls below tolerance times its start (with ``noisy``, once
        sigma < tolerance * sigma0; default 1e-9, or 1e-3 with ``noisy``);
        ``patience`` (int >= 1): iterations without a lower value before a restart
        (default 20 + 10n; before the run's first gain, on a deterministic f,
        counted from the last rejected step to the trust region's edge that shrank
        the scale to a new low); ``restarts`` (int >= 0): restarts without a gain,
        beyond the first, before the descent ends (default 0 where a fresh start
        follows, else 8);
        ``fresh_starts`` (bool): with a ``budget``, spend what the first descent
        leaves on new descents about the best point, each jumping farther and
        starting at a wider sigma than the last, sigma0 to 16 * sigma0, until a
        probe has found a lower point or two wide descents end on the same value
        (default True; False ends the run with its first descent);
        ``centre`` (bool): a descent that ends on a flat piece of ``fun`` (a
        rasteriser without anti-aliasing, rounded coordinates) moves x to the piece's
        centre along each axis, probing for its edges (default True);
        ``probes`` (int >= 0): before each fresh start, up to probes * n points that
        move one block of adjacent coordinates of the best point, anywhere within
        their bounds where they have them (one object's parameters: a shape hidden
        under another, a coordinate in the wrong cell), the
        first lower one starting the next descent (default 20; 0: none; up to
        eight times as many where the run's probes have found lower points more
        often than its fresh descents);
        ``non_finite``: ``"worst"`` (default: NaN or
        inf counts as worse than any value) or ``"error"`` (raise ValueError, whose
        ``result`` attribute holds the run so far);
        ``model``: the shape of Auto's local model and sampling metric, ``"full"`` (a
        full Hessian and metric, which learn curvature along any directions; at most
        n = 127) or ``"diagonal"`` (one curvature and one scale per coordinate: above
        n = 14 it suits a ``fun`` whose parameters interact little, as a sum of terms
        in one or a few of them, but a rotated ill-conditioned ``fun`` stalls it);
        default: full up to n = 14, diagonal above 127, and in between full unless
        the first 4 + 2⌈log₂ n⌉ evaluations find ``fun`` separable (a sum of terms in
        one coordinate each), when it is diagonal.
    tol : float, optional
        scipy's name for ``options["tolerance"]`` (0 < tol < 1); give one or the other.

    Returns
    -------
    OptimizeResult

    Raises
    ------
    TypeError, ValueError
        For bad arguments, naming the argument, and for a value of ``fun`` that is not
        a real number.
        With ``options={"non_finite": "error"}``, ValueError when ``fun`` returns NaN
        or inf; its ``result`` attribute holds the run so far.
    KeyboardInterrupt
        On Ctrl-C, within one batch of evaluations; its ``result`` attribute holds the
        run so far (status 4), with every value ``fun`` returned before.
    Exception
        Whatever ``fun`` or ``callback`` raised, unchanged.
    """
    if not isinstance(method, str) or method.lower() not in METHODS:
        raise ValueError(f"unknown method {method!r} (methods: {', '.join(METHODS)})")
    x0 = _vector("x0", x0)
    sigma0 = _scales(sigma0, len(x0))
    box = _bounds(bounds, len(x0))
    log_scale = _log_scale(log_scale, len(x0))
    if budget is not None:
        budget = _count("budget", budget, 1)
    seed = _seed(seed)
    if callback is not None:
        callback = _callback(callback)
    if tol is not None:
        tol = _real("tol", tol)
        if not 0.0 < tol < 1.0:
            raise ValueError(f"tol must be > 0 and < 1, got {tol!r}")
        if options is None:
            options = {}
        if hasattr(options, "items"):
            if "tolerance" in options:
                raise ValueError("give tol or options['tolerance'], not both")
            options = {**options, "tolerance": tol}
    settings = _settings(options)
    if not isinstance(args, tuple):
        args = (args,)
    if args:
        if not callable(fun):
            raise TypeError("fun must be callable")
        fun = functools.partial(_with_args, fun, args)
    try:
        raw = _hodr.minimize_auto(
            fun, x0, sigma0, box, log_scale, budget, seed, bool(batch), bool(noisy), callback,
            settings,
        )
    except (KeyboardInterrupt, ValueError) as stopped:
        _with_result(stopped, seed)
        raise
    return _result(raw, seed)


def _callback(callback: Any) -> Callable[[np.ndarray, float], bool]:
    """``callback`` as ``(x, f) -> stop``: called in the form its signature takes
    (``(x, f)``, scipy's ``(x)`` or ``(intermediate_result)``), StopIteration meaning
    stop, as in scipy."""
    if not callable(callback):
        raise TypeError("callback must be callable")
    form = "pair"
    try:
        parameters = list(inspect.signature(callback).parameters.values())
    except (TypeError, ValueError):
        parameters = None
    if parameters is not None:
        positional = [
            p for p in parameters
            if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)
        ]
        variadic = any(p.kind == p.VAR_POSITIONAL for p in parameters)
        if [p.name for p in parameters] == ["intermediate_result"]:
            form = "result"
        elif len(positional) == 1 and not variadic:
            form = "point"

    if form == "result":
        invoke = lambda x, f: callback(OptimizeResult(x=x, fun=f))  # noqa: E731
    elif form == "point":
        invoke = lambda x, f: callback(x)  # noqa: E731
    else:
        invoke = callback

    def call(x: np.ndarray, f: float) -> bool:
        try:
            return bool(invoke(x, f))
        except StopIteration:
            return True

    return call


def _with_args(fun: Callable[..., Any], args: tuple, *point: Any) -> Any:
    """``fun(*point, *args)``: the point (and seed) first, then the caller's ``args``."""
    return fun(*point, *args)


def _result(raw: dict, seed: int) -> OptimizeResult:
    """An OptimizeResult from the extension's fields, the history grouped, with the run's
    ``seed``."""
    history = {k: raw.pop(f"history_{k}") for k in ("nfev", "fun", "sigma", "descent")}
    result = OptimizeResult(raw)
    result.history = history
    result.seed = seed
    return result


class Optimizer:
    """Auto driven by ask and tell, as in pycma: the caller evaluates every batch.

    ::

        opt = hodr.Optimizer(x0, sigma0, budget=1000, seed=0)
        while not opt.stop():
            X = opt.ask()                              # (k, n) array of points
            opt.tell([render_loss(x) for x in X])      # or a pool, a GPU batch, a cluster
        res = opt.result                               # an OptimizeResult

    With the same arguments and seed, the points asked and the result are those of
    ``minimize(fun, x0, sigma0, batch=True, ...)``. Arguments as in ``minimize``; with
    ``noisy=True``, render row k of the batch asked with noise seed ``seeds[k]``. The
    optimiser runs on a thread of its own between ``tell`` and the next ``ask``; a
    batch must be told before the next is asked (``ask`` before ``tell`` gives the
    batch asked again). ``result`` is available at any time
    (the best point so far). Once the run has ended, ``ask()`` gives a (0, n) array and
    ``tell([])`` takes its values, so a plain ask/tell loop ends cleanly.

    A Ctrl-C while ``ask`` or ``stop`` waits for the optimiser raises KeyboardInterrupt
    with the run so far in its ``result``; the next ``ask`` hands out the batch.
    Under ``options={"non_finite": "error"}``, ``tell`` raises ValueError for a NaN or
    inf it hands over (``result``: the run so far, status 5), and so do ``ask``,
    ``tell`` and ``stop`` from then on. Dropping the object ends the run.
    """

    def __init__(
        self,
        x0: Sequence[float],
        sigma0: Union[float, Sequence[float]],
        *,
        bounds: Any = None,
        log_scale: Any = None,
        budget: Optional[int] = None,
        seed: Optional[int] = 0,
        noisy: bool = False,
        options: Optional[dict] = None,
    ) -> None:
        x0 = _vector("x0", x0)
        sigma0 = _scales(sigma0, len(x0))
        box = _bounds(bounds, len(x0))
        log_scale = _log_scale(log_scale, len(x0))
        if budget is not None:
            budget = _count("budget", budget, 1)
        self._seed = _seed(seed)
        self._asked: Optional[np.ndarray] = None
        self._run = _hodr.AskTell(
            x0, sigma0, box, log_scale, budget, self._seed, bool(noisy), _settings(options),
        )

    def _call(self, method: Callable, *args: Any) -> Any:
        """``method(*args)`` of the run; a KeyboardInterrupt while it waits for the
        optimiser, or the run's failure, carries the run so far in ``result``."""
        try:
            return method(*args)
        except KeyboardInterrupt as stopped:
            _with_result(stopped, self._seed, self.result)
            raise
        except (ValueError, RuntimeError) as failed:
            _with_result(failed, self._seed)
            raise

    def ask(self) -> np.ndarray:
        """The next batch of points, a float64 array of shape (k, n) — the batch asked
        last, again, until its values are told; (0, n) once the run has ended
        (``tell([])`` then takes its values)."""
        points = self._call(self._run.ask)
        self._asked = points.copy()
        return points

    @property
    def seeds(self) -> np.ndarray:
        """The noise seeds (uint64) of the batch last asked, one per row: a stochastic
        objective (``noisy=True``) draws row k's randomness from ``seeds[k]``."""
        return self._run.seeds

    def tell(self, *args: Any) -> None:
        """``tell(values)``: the objective's values at the points last asked, in their
        order; or ``tell(X, values)`` as in pycma, where X must be the batch asked (hodr
        fits the points it chose: a changed point is a ValueError, not a silent
        mismatch). With ``options={"non_finite": "error"}``, a NaN or inf among the
        values raises ValueError (its ``result`` the run so far), as does every later
        call once the run has failed."""
        if len(args) == 2:
            points, values = args
            asked = self._asked if self._asked is not None else np.empty((0, 0))
            given = _reals("X", points, "the (k, n) array of points asked")
            if given.shape != asked.shape or not np.array_equal(given, asked):
                raise ValueError(
                    f"X (shape {given.shape}) is not the batch asked (shape {asked.shape}): "
                    "tell the values of the points ask() returned, unchanged"
                )
        elif len(args) == 1:
            (values,) = args
        else:
            raise TypeError(f"tell takes values, or X and values, got {len(args)} arguments")
        array = _reals("values", values, "a sequence of real numbers")
        self._call(self._run.tell, np.ascontiguousarray(array.ravel()))

    def stop(self) -> bool:
        """True once the run has ended (converged, stagnated or out of budget)."""
        return self._call(self._run.stop)

    @property
    def result(self) -> OptimizeResult:
        """The run's ``OptimizeResult`` (while running: the best point so far)."""
        return _result(self._run.result(), self._seed)


def gradient(
    fun: Callable,
    x: Sequence[float],
    sigma: float,
    *,
    pairs: int = 16,
    method: str = "aggregate",
    seed: Optional[int] = 0,
    batch: bool = False,
    noisy: bool = False,
) -> Tuple[np.ndarray, int]:
    """Estimate the gradient of the Gaussian-smoothed ``fun`` at ``x`` (``batch`` and
    ``noisy`` as in ``minimize``).

    f_sigma(x) = E[f(x + sigma*eps)], eps ~ N(0, I). The estimate is unbiased (the
    least-squares ``"ls"`` one consistent) with ``pairs`` antithetic pairs.

    Parameters
    ----------
    method : str
        ``"aggregate"`` (importance sampling, one pair serves every coordinate; 2·pairs
        evaluations), ``"per-element"`` (2n·pairs), ``"gaussian"`` (2·pairs), ``"fr22"``
        (the FR22 baseline; exact for separable f only), ``"ls"`` (least squares,
        2·max(pairs, 2n+2)).
    seed : int or None
        Seed of the samples (0 to 2**64 - 1); None draws a fresh one from the operating
        system.

    Returns
    -------
    (g, nfev) : (ndarray of shape (n,), int)

    Raises ``ValueError`` for a sigma at or below what x's floats resolve, 8·eps·max|x_i|
    (every sample would round to x), as ``hessian`` and ``hvp`` do.
    """
    x, sigma = _estimate_args(x, sigma)
    return _hodr.gradient(
        fun, x, sigma, _count("pairs", pairs, 1),
        str(method), _seed(seed), bool(batch), bool(noisy),
    )


def hessian(
    fun: Callable,
    x: Sequence[float],
    sigma: float,
    *,
    pairs: int = 16,
    method: str = "aggregate",
    seed: Optional[int] = 0,
    batch: bool = False,
    noisy: bool = False,
) -> Tuple[np.ndarray, int]:
    """Estimate the Hessian of the Gaussian-smoothed ``fun`` at ``x`` (symmetric).

    ``method``: ``"aggregate"`` (2·pairs + 1 evaluations), ``"gaussian"`` (2·pairs + 1),
    ``"per-element"`` (n(n+1)·pairs + 1).
    The other arguments as in ``gradient``.

    Returns
    -------
    (H, nfev) : (ndarray of shape (n, n), int)
    """
    x, sigma = _estimate_args(x, sigma)
    return _hodr.hessian(
        fun, x, sigma, _count("pairs", pairs, 1),
        str(method), _seed(seed), bool(batch), bool(noisy),
    )


def hvp(
    fun: Callable,
    x: Sequence[float],
    v: Sequence[float],
    sigma: float,
    *,
    pairs: int = 16,
    method: str = "kernel",
    seed: Optional[int] = 0,
    batch: bool = False,
    noisy: bool = False,
) -> Tuple[np.ndarray, int]:
    """Estimate the product of the smoothed ``fun``'s Hessian at ``x`` with ``v``.

    ``method``: ``"kernel"`` (Gaussian kernel, 2·pairs + 1 evaluations, unbiased) or
    ``"central"`` (central difference of two aggregate gradients at x ± (sigma/3)·v/|v|
    on common samples, 4·pairs evaluations).
    The other arguments as in ``gradient``.

    Returns
    -------
    (Hv, nfev) : (ndarray of shape (n,), int)
    """
    x, sigma = _estimate_args(x, sigma)
    return _hodr.hvp(
        fun, x, _vector("v", v), sigma,
        _count("pairs", pairs, 1), str(method), _seed(seed), bool(batch), bool(noisy),
    )
