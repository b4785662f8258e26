# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Scenes, solving and analyses on the C library: arguments checked here, work done in C.
import math
import numbers
import os
import signal
import threading

import _signal

import numpy as np

from ._dal import ffi, lib

_MSG = 4096

# ---------------------------------------------------------------------------------------------
# errors


class Error(Exception):
    """A failure of the C library: its status (negative int), status name, message, and the
    partial result up to the last accepted step (``result``, or None where no run took place)."""

    def __init__(self, status, message, result=None):
        self.status = status
        self.name = ffi.string(lib.dal_status_name(status)).decode()
        self.message = message
        self.result = result
        super().__init__(f"{self.name}: {message}")


class ArgumentError(Error, ValueError):
    """The library refused an argument or an option (DAL_E_ARG, DAL_E_NONFINITE, DAL_E_TIME,
    DAL_E_UNSUPPORTED, DAL_E_STATE)."""


class ModelError(Error):
    """The model cannot be evaluated there (DAL_E_DOMAIN, DAL_E_SINGULAR, DAL_E_CONSTRAINT,
    DAL_E_INIT)."""


class IntegrationError(Error):
    """The integrator failed (DAL_E_STEP, DAL_E_MAXSTEPS, DAL_E_CONV, DAL_E_SOLVER)."""


class CallbackError(Error):
    """A callback (an event function, a monitor) failed (DAL_E_CALLBACK)."""


class ResourceError(Error):
    """Memory or input/output (DAL_E_NOMEM, DAL_E_IO), or a verification mismatch."""


class Cancelled(KeyboardInterrupt):
    """Ctrl-C stopped a run: ``result`` holds what was computed up to the last accepted step."""

    def __init__(self, message, result=None):
        self.message = message
        self.result = result
        super().__init__(message)


_FAMILY = {
    lib.DAL_E_ARG: ArgumentError, lib.DAL_E_NONFINITE: ArgumentError,
    lib.DAL_E_TIME: ArgumentError, lib.DAL_E_UNSUPPORTED: ArgumentError,
    lib.DAL_E_STATE: ArgumentError,
    lib.DAL_E_DOMAIN: ModelError, lib.DAL_E_SINGULAR: ModelError,
    lib.DAL_E_CONSTRAINT: ModelError, lib.DAL_E_INIT: ModelError,
    lib.DAL_E_STEP: IntegrationError, lib.DAL_E_MAXSTEPS: IntegrationError,
    lib.DAL_E_CONV: IntegrationError, lib.DAL_E_SOLVER: IntegrationError,
    lib.DAL_E_CALLBACK: CallbackError,
    lib.DAL_E_NOMEM: ResourceError, lib.DAL_E_IO: ResourceError, lib.DAL_E_VERIFY: ResourceError,
}


def _error(status, message, result=None):
    return _FAMILY.get(status, Error)(status, message, result)


def _s(p):
    return ffi.string(p).decode() if p != ffi.NULL else ""


# ---------------------------------------------------------------------------------------------
# argument checks (before any C call)

METHODS = {ffi.string(lib.dal_method_name(m)).decode(): m for m in (
    lib.DAL_METHOD_AUTO, lib.DAL_METHOD_DOPRI5, lib.DAL_METHOD_FEHLBERG78, lib.DAL_METHOD_BS,
    lib.DAL_METHOD_RK4, lib.DAL_METHOD_ADAMS, lib.DAL_METHOD_BDF, lib.DAL_METHOD_VARIATIONAL,
    lib.DAL_METHOD_VARIATIONAL4, lib.DAL_METHOD_VARIATIONAL6, lib.DAL_METHOD_RATTLE,
    lib.DAL_METHOD_RATTLE4, lib.DAL_METHOD_RATTLE6)}
FORMULATIONS = {ffi.string(lib.dal_formulation_name(f)).decode(): f for f in (
    lib.DAL_FORM_AUTO, lib.DAL_FORM_ODE, lib.DAL_FORM_GGL, lib.DAL_FORM_INDEX1,
    lib.DAL_FORM_INDEX3)}


def _real(name, x, *, positive=False, allow_none=False):
    if x is None and allow_none:
        return None
    if isinstance(x, bool) or not isinstance(x, numbers.Real):
        raise TypeError(f"{name} must be a real number, not {type(x).__name__}")
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite, got {x}")
    if positive and x <= 0:
        raise ValueError(f"{name} must be > 0, got {x}")
    return x


def _vector(name, x, n):
    if isinstance(x, (str, bytes)) or not hasattr(x, "__len__") and not hasattr(x, "__array__"):
        raise TypeError(f"{name} must be an array of {n} real numbers, not {type(x).__name__}")
    try:
        a = np.asarray(x)
    except Exception as e:  # ragged lists and the like
        raise TypeError(f"{name} must be an array of {n} real numbers: {e}") from None
    if a.dtype == object or a.dtype.kind not in "iuf" or a.dtype == np.bool_:
        raise TypeError(f"{name} must hold real numbers, not {a.dtype}")
    if a.ndim != 1 or a.shape[0] != n:
        raise ValueError(f"{name} must have shape ({n},), got {a.shape}")
    a = np.ascontiguousarray(a, dtype=np.float64)
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite, got {a[~np.isfinite(a)][0]} "
                         f"at index {int(np.flatnonzero(~np.isfinite(a))[0])}")
    return a


def _choice(name, x, table):
    if not isinstance(x, str):
        raise TypeError(f"{name} must be a string, one of {', '.join(table)}")
    if x not in table:
        raise ValueError(f"{name}: unknown {name} '{x}'; known: {', '.join(table)}")
    return table[x]


# ---------------------------------------------------------------------------------------------
# running C work cancellably: in the main thread, with Python's default SIGINT handler in
# place, the C call runs under a C handler that sets the int the library's cancel hook reads
# (dal_solve_opts.cancel: asked after every accepted step); the GIL is released meanwhile (cffi).
# A worker thread with the main thread waiting in short joins was the first design: its
# hand-off cost 0.2 - 1 ms per call, more than a small run.


def _cancellable(fn, *args, cancel):
    if threading.current_thread() is not threading.main_thread() or \
            _signal.getsignal(_signal.SIGINT) is not signal.default_int_handler:
        return fn(*args), False
    lib.pyd_sigint_begin(cancel)
    try:
        rc = fn(*args)
    finally:
        lib.pyd_sigint_end()
    return rc, bool(cancel[0])


class _Progress:
    """A text progress bar on sys.stderr, redrawn every 0.1 s by a thread while C works."""

    def __init__(self, rows, t0, t1):
        self.rows, self.t0, self.t1 = rows, t0, t1
        self.stop = threading.Event()
        self.th = threading.Thread(target=self._run, daemon=True)
        self.th.start()

    def _draw(self, end="\r"):
        import sys
        t = lib.pyd_progress(self.rows)
        f = min(1.0, (t - self.t0) / (self.t1 - self.t0)) if self.t1 > self.t0 else 1.0
        sys.stderr.write(f"\r[{'#' * int(30 * f):<30}] {100 * f:5.1f}%  t = {t:.6g}{end}")
        sys.stderr.flush()

    def _run(self):
        while not self.stop.wait(0.1):
            self._draw()

    def close(self):
        self.stop.set()
        self.th.join()
        self._draw("\n")


# ---------------------------------------------------------------------------------------------
# scenes


class _Handle:
    """Owns one dal_scene; results keep it alive while they need its system."""

    def __init__(self, ptr, name):
        self.ptr = ffi.gc(ptr, lib.dal_scene_destroy)
        self.name = name
        self.sys = lib.dal_scene_system(ptr)


def _parse(text, name):
    out = ffi.new("dal_scene **")
    msg = ffi.new("char[]", _MSG)
    rc = lib.dal_scene_parse(text.encode(), name.encode(), out, msg, _MSG)
    if rc:
        raise _error(rc, _s(msg))
    return _Handle(out[0], name)


def _text(h, show=0, fmt=0):
    rc = ffi.new("int *")
    msg = ffi.new("char[]", _MSG)
    p = lib.pyd_scene_text(h.ptr, show, fmt, rc, msg, _MSG)
    try:
        s = _s(p) if p != ffi.NULL else ""
    finally:
        lib.pyd_free(p)
    if rc[0]:
        raise _error(rc[0], _s(msg) or f"writing {h.name} failed")
    return s


def _formula_value(formula, vals):
    keep = [ffi.new("char[]", k.encode()) for k in vals]
    names = ffi.new("const char *[]", keep) if keep else ffi.NULL
    values = ffi.new("double[]", list(vals.values())) if vals else ffi.NULL
    out = ffi.new("double *")
    msg = ffi.new("char[]", _MSG)
    rc = lib.pyd_formula_value(formula.encode(), len(vals), names, values, out, msg, _MSG)
    if rc:
        raise _error(rc, _s(msg))
    return out[0]


class Params:
    """The scene's `param` lines as a mapping: ``scene.params["omega"] = 6.0`` rebuilds the
    system; an unknown name raises KeyError listing the known ones."""

    def __init__(self, scene):
        self._scene = scene

    def _values(self):
        # the lines written back: a number, or a formula of the parameters above it
        vals = {}
        for line in _text(self._scene._h).splitlines():
            if line.startswith("param "):
                name, _, v = line[6:].partition(" = ")
                try:
                    vals[name] = float(v)
                except ValueError:
                    vals[name] = _formula_value(v, vals)
        return vals

    def __getitem__(self, name):
        vals = self._values()
        if name not in vals:
            raise KeyError(f"no parameter {name!r}; known: {', '.join(vals) or '(none)'}")
        return vals[name]

    def __setitem__(self, name, value):
        if not isinstance(name, str):
            raise TypeError(f"parameter names are strings, not {type(name).__name__}")
        vals = self._values()
        if name not in vals:
            raise KeyError(f"no parameter {name!r}; known: {', '.join(vals) or '(none)'}")
        value = _real(f"params[{name!r}]", value)
        # a new scene from the text written back: results of the old one keep their system
        h = _parse(_text(self._scene._h), self._scene._h.name)
        msg = ffi.new("char[]", _MSG)
        rc = lib.dal_scene_set_param(h.ptr, name.encode(), value, msg, _MSG)
        if rc:
            raise _error(rc, _s(msg))
        h.sys = lib.dal_scene_system(h.ptr)
        self._scene._h = h

    def __iter__(self):
        return iter(self._values())

    def __len__(self):
        return len(self._values())

    def __contains__(self, name):
        return name in self._values()

    def keys(self):
        return self._values().keys()

    def items(self):
        return self._values().items()

    def values(self):
        return self._values().values()

    def update(self, other=(), **kw):
        for k, v in dict(other, **kw).items():
            self[k] = v

    def __repr__(self):
        return f"Params({self._values()!r})"


class Equations:
    """The scene's equations of motion as text and LaTeX (a notebook shows the LaTeX)."""

    def __init__(self, text, latex):
        self.text = text
        self.latex = latex

    def __str__(self):
        return self.text

    def __repr__(self):
        return self.text

    def _repr_latex_(self):
        # one display block per equation, as the library prints them
        lines = [ln.strip().strip("$") for ln in self.latex.splitlines() if ln.strip()]
        return "$$\\begin{aligned}" + "\\\\ ".join(
            ln.replace("=", "&=", 1) for ln in lines) + "\\end{aligned}$$"


class Scene:
    """A model and its run, read from scene text (include/dalembert/scene.h has the grammar)."""

    def __init__(self, handle):
        self._h = handle

    @classmethod
    def load(cls, path):
        """Read a scene file. Messages name the file and line."""
        if not isinstance(path, (str, bytes, os.PathLike)):
            raise TypeError(f"path must be a str or os.PathLike, not {type(path).__name__}")
        path = os.fsdecode(path)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        return cls(_parse(text, path))

    @classmethod
    def parse(cls, text, name="<string>"):
        """Read a scene from its text."""
        if not isinstance(text, str):
            raise TypeError(f"text must be a str, not {type(text).__name__}")
        if not isinstance(name, str):
            raise TypeError(f"name must be a str, not {type(name).__name__}")
        return cls(_parse(text, name))

    # -- what the scene is
    @property
    def params(self):
        return Params(self)

    @property
    def text(self):
        """The scene written back (numbers %.17g): parse(text) gives the same system."""
        return _text(self._h)

    @property
    def dim(self):
        return lib.dal_system_dim(self._h.sys)

    @property
    def coords(self):
        s = self._h.sys
        return [_s(lib.dal_system_coord_name(s, i)) for i in range(lib.dal_system_ncoords(s))]

    @property
    def particles(self):
        s = self._h.sys
        return [_s(lib.dal_system_particle_name(s, k))
                for k in range(lib.dal_system_nparticles(s))]

    @property
    def constraints(self):
        s = self._h.sys
        return [_s(lib.dal_system_constraint_name(s, i))
                for i in range(lib.dal_system_nconstraints(s))]

    @property
    def run(self):
        """The scene's `run` line: t0, t1, dt, method, formulation, rtol, atol."""
        t0, t1, dt = ffi.new("double *"), ffi.new("double *"), ffi.new("double *")
        o = lib.dal_scene_opts(self._h.ptr, t0, t1, dt)
        return dict(t0=t0[0], t1=t1[0], dt=dt[0],
                    method=_s(lib.dal_method_name(o.method)),
                    formulation=_s(lib.dal_formulation_name(o.form)), rtol=o.rtol, atol=o.atol)

    def __repr__(self):
        return (f"Scene({self._h.name!r}: coords {self.coords}, particles {self.particles}, "
                f"params {dict(self.params.items())})")

    def _initial_state(self):
        st = ffi.new("dal_state **")
        rc = lib.dal_scene_state(self._h.ptr, st)
        if rc:
            raise _error(rc, f"{self._h.name}: the scene's initial state was refused")
        return ffi.gc(st[0], lib.dal_state_destroy)

    def _initial(self):
        st = ffi.new("dal_state **")
        rc = lib.dal_scene_state(self._h.ptr, st)
        if rc:
            raise _error(rc, f"{self._h.name}: the scene's initial state was refused")
        st = ffi.gc(st[0], lib.dal_state_destroy)
        n = lib.dal_system_ncoords(self._h.sys)
        q = np.frombuffer(ffi.buffer(lib.dal_state_q(st), 8 * n), np.float64).copy()
        v = np.frombuffer(ffi.buffer(lib.dal_state_qdot(st), 8 * n), np.float64).copy()
        return lib.dal_state_time(st), q, v

    @property
    def y0(self):
        """The initial state (q, qdot) of the coordinates' q= and v= values."""
        _, q, v = self._initial()
        return np.concatenate([q, v])

    # -- solving
    def _opts(self, method, formulation, rtol, atol, max_steps, fixed_step):
        o = ffi.new("dal_solve_opts *")
        o[0] = lib.dal_scene_opts(self._h.ptr, ffi.NULL, ffi.NULL, ffi.NULL)[0]
        if method is not None:
            o.method = _choice("method", method, METHODS)
        if formulation is not None:
            o.form = _choice("formulation", formulation, FORMULATIONS)
        if rtol is not None:
            rtol = _real("rtol", rtol, positive=True)
            if not 1e-15 <= rtol < 1:
                raise ValueError(f"rtol must lie in [1e-15, 1), got {rtol}")
            o.rtol = rtol
            if atol is None:
                o.atol = 0.0
        if atol is not None:
            o.atol = _real("atol", atol, positive=True)
        if max_steps is not None:
            if isinstance(max_steps, bool) or not isinstance(max_steps, numbers.Integral):
                raise TypeError(f"max_steps must be an int, not {type(max_steps).__name__}")
            if max_steps <= 0:
                raise ValueError(f"max_steps must be > 0, got {max_steps}")
            o.max_steps = int(max_steps)
        if fixed_step is not None:
            o.fixed_step = _real("fixed_step", fixed_step, positive=True)
        return o

    def _state(self, t0, y0):
        sys = self._h.sys
        n = lib.dal_system_ncoords(sys)
        if y0 is None:
            # the scene's initial state, moved to t0 when that is another time
            st = self._initial_state()
            if lib.dal_state_time(st) == t0:
                return st
            q, v = _vec(lib.dal_state_q(st), n), _vec(lib.dal_state_qdot(st), n)
        else:
            p = ffi.new("dal_state **")
            rc = lib.dal_state_create(sys, p)
            if rc:
                raise _error(rc, "creating a state failed")
            st = ffi.gc(p[0], lib.dal_state_destroy)
            q, v = np.ascontiguousarray(y0[:n]), np.ascontiguousarray(y0[n:])
        rc = lib.dal_state_set(sys, st, t0, _p(q), _p(v))
        if rc:
            raise _error(rc, _s(lib.dal_state_errmsg(st)))
        return st

    def _check_span(self, t_span):
        if t_span is None:
            r = self.run
            return r["t0"], r["t1"]
        if isinstance(t_span, (str, bytes)) or not hasattr(t_span, "__len__"):
            raise TypeError(f"t_span must be a pair (t0, t1), not {type(t_span).__name__}")
        if len(t_span) != 2:
            raise ValueError(f"t_span must be a pair (t0, t1), got {len(t_span)} values")
        t0 = _real("t_span[0]", t_span[0])
        t1 = _real("t_span[1]", t_span[1])
        if t1 < t0:
            raise ValueError(f"t_span: integration runs forward; t1 = {t1} < t0 = {t0}")
        return t0, t1

    def _events(self, events):
        """A dal_events set: the scene's own (None), none ([]), or formulas."""
        sys = self._h.sys
        ev = ffi.new("dal_events **")
        if events is None:
            rc = lib.dal_scene_events(self._h.ptr, ev)
            if rc:
                raise _error(rc, "the scene's events")
            evs = ffi.gc(ev[0], lib.pyd_events_destroy)
            if lib.dal_events_size(evs) == 0:
                return None, []  # an empty set attached would still ask for dense output
            names = [_s(lib.dal_events_name(evs, i)) for i in range(lib.dal_events_size(evs))]
            return evs, names
        if isinstance(events, (str, dict)):
            events = [events]
        if not isinstance(events, (list, tuple)):
            raise TypeError("events must be a list of formulas or dicts "
                            f"(g, direction, terminal, name), not {type(events).__name__}")
        spec = []
        for i, e in enumerate(events):
            if isinstance(e, str):
                e = {"g": e}
            if not isinstance(e, dict) or not isinstance(e.get("g"), str):
                raise TypeError(f"events[{i}] must be a formula or a dict with a formula 'g'")
            unknown = set(e) - {"g", "direction", "terminal", "name"}
            if unknown:
                raise ValueError(f"events[{i}]: unknown keys {sorted(unknown)}; "
                                 "known: g, direction, terminal, name")
            d = e.get("direction", 0)
            if d not in (-1, 0, 1) or isinstance(d, bool):
                raise ValueError(f"events[{i}]['direction'] must be -1, 0 or 1, got {d!r}")
            term = e.get("terminal", False)
            if not isinstance(term, bool):
                raise TypeError(f"events[{i}]['terminal'] must be a bool")
            name = e.get("name", f"event{i}")
            if not isinstance(name, str):
                raise TypeError(f"events[{i}]['name'] must be a str")
            spec.append((name, e["g"], d, term))
        if not spec:
            return None, []
        rc = lib.dal_events_create(sys, ev)
        if rc:
            raise _error(rc, "creating the event set failed")
        evs = ffi.gc(ev[0], lib.pyd_events_destroy)
        pv = self.params._values()
        keep = [ffi.new("char[]", k.encode()) for k in pv]
        pnames = ffi.new("const char *[]", keep) if keep else ffi.NULL
        pvals = ffi.new("double[]", list(pv.values())) if pv else ffi.NULL
        msg = ffi.new("char[]", _MSG)
        for i, (name, g, d, term) in enumerate(spec):
            k = lib.pyd_add_event(evs, sys, name.encode(), g.encode(), len(pv), pnames, pvals,
                                  d, int(term), msg, _MSG)
            if k < 0:
                raise _error(k, f"events[{i}]: {_s(msg)}")
        return evs, [s[0] for s in spec]

    def solve(self, t_span=None, y0=None, method=None, rtol=None, atol=None, t_eval=None,
              dense_output=False, events=None, *, dt=None, formulation=None, max_steps=None,
              fixed_step=None, progress=False):
        """Integrate the scene, like scipy.integrate.solve_ivp (docs/python.md).

        t_span (t0, t1): default the scene's run line. y0: (q, qdot) of 2n values; default the
        scene's initial state. method, formulation: names ("auto", "dopri5", "bs", ...);
        default the scene's run line. rtol, atol: default the scene's. t_eval: output times
        (sorted, inside t_span); default the grid t0 + k dt (dt: the scene's). events: None
        (the scene's event and section lines), [] (none), or formulas g(t, q, qdot) as strings
        or dicts {g, direction, terminal, name}. progress=True draws a progress bar on
        sys.stderr (from a thread, by the time of the last output). Returns a Result; a failure raises an Error
        subclass with the partial result attached; Ctrl-C raises Cancelled with it."""
        sys = self._h.sys
        n = lib.dal_system_ncoords(sys)
        t0, t1 = self._check_span(t_span)
        if y0 is not None:
            y0 = _vector("y0", y0, 2 * n)
        if not isinstance(dense_output, bool):
            raise TypeError("dense_output must be a bool")
        if not isinstance(progress, bool):
            raise TypeError("progress must be a bool")
        o = self._opts(method, formulation, rtol, atol, max_steps, fixed_step)
        grid = t_eval is None
        if grid:
            if dt is None:
                dt = self.run["dt"]
                if not dt > 0:
                    dt = (t1 - t0) / 100 if t1 > t0 else 1.0
            dt = _real("dt", dt, positive=True)
            span = (t1 - t0) / dt
            if span > 1e8:
                raise ValueError(f"dt = {dt} gives {span:.3g} outputs over t_span; "
                                 "raise dt or pass t_eval")
            cap = int(math.floor(span)) + 2
            times = ffi.NULL
            ntimes = 0
        else:
            if dt is not None:
                raise ValueError("give t_eval or dt, not both")
            te = np.asarray(t_eval)
            if te.dtype.kind not in "iuf" or te.dtype == np.bool_:
                raise TypeError(f"t_eval must hold real numbers, not {te.dtype}")
            if te.ndim != 1 or te.size == 0:
                raise ValueError(f"t_eval must be a non-empty 1-D array, got shape {te.shape}")
            te = np.ascontiguousarray(te, dtype=np.float64)
            if not np.all(np.isfinite(te)):
                raise ValueError("t_eval must be finite")
            if np.any(np.diff(te) < 0):
                i = int(np.flatnonzero(np.diff(te) < 0)[0]) + 1
                raise ValueError(f"t_eval must be sorted: t_eval[{i}] < t_eval[{i - 1}]")
            if te[0] < t0 or te[-1] > t1:
                raise ValueError(f"t_eval must lie inside t_span [{t0}, {t1}]")
            cap = te.size
            # integrate to t1 as solve_ivp does: t1 as a last time whose row is not kept
            tt = te if te[-1] == t1 else np.append(te, t1)
            times = ffi.from_buffer("double[]", tt)
            ntimes = tt.size
        evs, evnames = self._events(events)
        st = self._state(t0, y0)
        N, d, m = lib.dal_system_nparticles(sys), lib.dal_system_dim(sys), \
            lib.dal_system_nconstraints(sys)
        bufs = dict(t=np.empty(cap), q=np.empty((cap, n)), qdot=np.empty((cap, n)),
                    pos=np.empty((cap, N, max(d, 1))) if N and d else None,
                    lam=np.empty((cap, m)) if m else None, energy=np.empty((cap, 4)))
        rows = ffi.new("pyd_rows *")
        rows.cap, rows.len, rows.n, rows.N, rows.d, rows.m = cap, 0, n, N, d, m
        rows.drop = int(not grid)
        for k, v in bufs.items():
            setattr(rows, k, ffi.from_buffer("double[]", v) if v is not None else ffi.NULL)
        tr = ffi.NULL
        if dense_output:
            trp = ffi.new("dal_trajectory **")
            rc = lib.dal_trajectory_create(sys, trp)
            if rc:
                raise _error(rc, "creating the trajectory failed")
            tr = ffi.gc(trp[0], lib.dal_trajectory_destroy)
        cancel = ffi.new("int[1]")
        rows.tnow = t0
        bar = _Progress(rows, t0, t1) if progress else None
        try:
            rc, interrupted = _cancellable(lib.pyd_solve, sys, st, o, int(grid), t1,
                                           dt if grid else 0.0, times, ntimes, rows, tr,
                                           evs if evs is not None else ffi.NULL, cancel,
                                           cancel=cancel)
        finally:
            if bar:
                bar.close()
        res = Result(self, st, rc, rows.len, bufs, n, tr, evs, evnames)
        if rc == lib.DAL_CANCELLED or interrupted:
            raise Cancelled(res.message or "cancelled by Ctrl-C", res)
        if rc < 0:
            raise _error(rc, res.message, res)
        return res

    # -- analyses
    def equations(self):
        """The equations of motion (text and LaTeX; dal_scene_show)."""
        return Equations(_text(self._h, 1, lib.DAL_EXPR_TEXT),
                         _text(self._h, 1, lib.DAL_EXPR_LATEX))

    def _analysis_state(self, t, q, qdot):
        n = lib.dal_system_ncoords(self._h.sys)
        t0, q0, v0 = self._initial()
        t0 = t0 if t is None else _real("t", t)
        q0 = q0 if q is None else _vector("q", q, n)
        v0 = v0 if qdot is None else _vector("qdot", qdot, n)
        return self._state(t0, np.concatenate([q0, v0]))

    def equilibrium(self, q=None, t=None, xtol=None, max_iter=None, max_step=None):
        """An equilibrium by Newton from q (default the initial q) at time t, with its normal
        modes: an Equilibrium (q, multipliers, report, modes). max_step bounds each Newton
        step (|dq_i|), which keeps it near the start."""
        n = lib.dal_system_ncoords(self._h.sys)
        st = self._analysis_state(t, q, np.zeros(n))
        o = ffi.new("dal_equilibrium_opts *", lib.dal_default_equilibrium_opts())
        if xtol is not None:
            o.xtol = _real("xtol", xtol, positive=True)
        if max_iter is not None:
            if isinstance(max_iter, bool) or not isinstance(max_iter, numbers.Integral):
                raise TypeError("max_iter must be an int")
            o.max_iter = int(max_iter)
        if max_step is not None:
            o.max_step = _real("max_step", max_step, positive=True)
        rep = ffi.new("dal_equilibrium_report *")
        rc = lib.dal_equilibrium(self._h.sys, st, o, rep)
        if rc:
            raise _error(rc, _s(lib.dal_state_errmsg(st)))
        qs = _vec(lib.dal_state_q(st), n)
        m = lib.dal_system_nconstraints(self._h.sys)
        lam = _vec(lib.dal_state_lambda(st), m) if m else np.zeros(0)
        modes = self._modes(st)
        return Equilibrium(qs, lam, dict(iterations=rep.iterations, step=rep.step,
                                         accel=rep.accel, unsteady=rep.unsteady), modes)

    def equilibria(self, starts=None, t=None, max_step=None):
        """Equilibria found by Newton from the initial q and from each q of `starts`,
        duplicates (within 1e-8) removed."""
        n = lib.dal_system_ncoords(self._h.sys)
        qs = [None] if starts is None else [_vector(f"starts[{i}]", s, n)
                                            for i, s in enumerate(starts)]
        found = []
        for q in qs:
            try:
                e = self.equilibrium(q, t, max_step=max_step)
            except (ModelError, IntegrationError):
                continue
            if not any(np.max(np.abs(e.q - f.q)) <= 1e-8 * (1 + np.max(np.abs(f.q)))
                       for f in found):
                found.append(e)
        return found

    def _modes(self, st):
        sys = self._h.sys
        n = lib.dal_system_ncoords(sys)
        k = n - lib.dal_system_nconstraints(sys)
        om2, shapes = np.empty(k), np.empty((k, n))
        lre, lim = np.empty(2 * k), np.empty(2 * k)
        out = ffi.new("dal_modes *")
        rc = lib.dal_normal_modes(sys, st, _p(om2), _p(shapes), _p(lre), _p(lim), out)
        if rc:
            raise _error(rc, _s(lib.dal_state_errmsg(st)))
        return Modes(om2, shapes.T.copy(), lre + 1j * lim,
                     _s(lib.dal_stability_name(out.verdict)), out.max_real, out.tau)

    def modes(self, q=None, qdot=None, t=None, here=False):
        """Normal modes and stability: at the equilibrium Newton finds from q (default the
        initial q), or with here=True at the state (t, q, qdot) itself."""
        if not here:
            return self.equilibrium(q, t).modes
        return self._modes(self._analysis_state(t, q, qdot))

    def linearize(self, inputs=(), q=None, qdot=None, t=None):
        """The exact linearization at a state (default the initial one): M, C, K of
        M dq'' + C dq' + K dq = B2 du and the first-order x' = A x + B u, x = (dq, dqdot).
        inputs: names ("force:<coordinate>", "mass:<particle>", "gravity:<i>", ...)."""
        if isinstance(inputs, str):
            inputs = [inputs]
        if not isinstance(inputs, (list, tuple)) or not all(isinstance(s, str) for s in inputs):
            raise TypeError("inputs must be a list of names")
        sys = self._h.sys
        n = lib.dal_system_ncoords(sys)
        k = n - lib.dal_system_nconstraints(sys)
        st = self._analysis_state(t, q, qdot)
        M, C, K = (np.empty((k, k), order="F") for _ in range(3))
        rc = lib.dal_linearize(sys, st, _p(M), _p(C), _p(K))
        if rc:
            raise _error(rc, _s(lib.dal_state_errmsg(st)))
        ni = len(inputs)
        B2 = np.empty((k, ni), order="F")
        A = np.empty((2 * k, 2 * k), order="F")
        B = np.empty((2 * k, ni), order="F")
        keep = [ffi.new("char[]", s.encode()) for s in inputs]
        names = ffi.new("const char *[]", keep) if keep else ffi.NULL
        rc = lib.dal_linearize_inputs(sys, st, ni, names, _p(B2) if ni else ffi.NULL, _p(A),
                                      _p(B) if ni else ffi.NULL)
        if rc:
            raise _error(rc, _s(lib.dal_state_errmsg(st)))
        return Linearization(M, C, K, A, B, B2, list(inputs))

    def state_transition(self, t1, params=(), y0=None, t0=None, method=None, rtol=None,
                         atol=None):
        """The flow map's derivative from (t0, y0) to t1: Phi = dy(t1)/dy(t0) (2n x 2n) and
        S = dy(t1)/dp for the named parameters (2n x len(params)); returns (Phi, S, y(t1))."""
        if isinstance(params, str):
            params = [params]
        if not isinstance(params, (list, tuple)) or not all(isinstance(s, str) for s in params):
            raise TypeError("params must be a list of names")
        sys = self._h.sys
        n = lib.dal_system_ncoords(sys)
        t1 = _real("t1", t1)
        y0 = None if y0 is None else _vector("y0", y0, 2 * n)
        tstart = self._initial()[0] if t0 is None else _real("t0", t0)
        st = self._state(tstart, y0)
        o = self._opts(method, None, rtol, atol, None, None)
        if o.method not in (lib.DAL_METHOD_AUTO, lib.DAL_METHOD_DOPRI5,
                            lib.DAL_METHOD_FEHLBERG78, lib.DAL_METHOD_BS, lib.DAL_METHOD_RK4):
            o.method = lib.DAL_METHOD_AUTO
        Phi = np.empty((2 * n, 2 * n), order="F")
        S = np.empty((2 * n, len(params)), order="F")
        keep = [ffi.new("char[]", s.encode()) for s in params]
        names = ffi.new("const char *[]", keep) if keep else ffi.NULL
        rc = lib.dal_state_transition(sys, st, o, t1, _p(Phi), len(params), names,
                                      _p(S) if params else ffi.NULL)
        if rc:
            raise _error(rc, _s(lib.dal_state_errmsg(st)))
        y1 = np.concatenate([_vec(lib.dal_state_q(st), n), _vec(lib.dal_state_qdot(st), n)])
        return Phi, S, y1

    def lyapunov(self, t_end, transient=0.0, renorm=1.0, nexp=0, y0=None, t0=None,
                 method="auto", rtol=1e-10, atol=1e-10):
        """Lyapunov exponents (Benettin et al.) with 95% error half-widths:
        returns (exponents, errors), largest first, 1/time. Ctrl-C stops it (Cancelled)."""
        sys = self._h.sys
        n = lib.dal_system_ncoords(sys)
        y0 = None if y0 is None else _vector("y0", y0, 2 * n)
        tstart = self._initial()[0] if t0 is None else _real("t0", t0)
        o = ffi.new("dal_lyapunov_opts *", lib.dal_default_lyapunov_opts())
        o.t_end = _real("t_end", t_end)
        if o.t_end <= tstart:
            raise ValueError(f"t_end = {o.t_end} must be after the start {tstart}")
        o.transient = _real("transient", transient)
        o.renorm = _real("renorm", renorm, positive=True)
        o.method = _choice("method", method, METHODS)
        o.rtol = _real("rtol", rtol, positive=True)
        o.atol = _real("atol", atol, positive=True)
        if isinstance(nexp, bool) or not isinstance(nexp, numbers.Integral):
            raise TypeError("nexp must be an int")
        k = 2 * (n - lib.dal_system_nconstraints(sys))
        if not 0 <= nexp <= k:
            raise ValueError(f"nexp must lie in 0 ... {k}, got {nexp}")
        o.nexp = int(nexp)
        ne = nexp or k
        st = self._state(tstart, y0)
        exps, errs = np.empty(ne), np.empty(ne)
        cancel = ffi.new("int[1]")
        rc, interrupted = _cancellable(lib.pyd_lyapunov, sys, st, o, _p(exps), _p(errs), cancel,
                                       cancel=cancel)
        if interrupted:
            raise Cancelled("lyapunov: cancelled by Ctrl-C", (exps, errs))
        if rc:
            raise _error(rc, _s(lib.dal_state_errmsg(st)))
        return exps, errs

    def section(self, t_span=None, y0=None, surface=None, **solve_kw):
        """The scene's Poincare section: the stroboscopic one (its `section NAME period=T`
        line: the state every period) or, with surface=True or without a period, the
        crossings of its surface `section` lines. Returns (t, y): times (k) and states
        (k x 2n)."""
        T = lib.dal_scene_strobe(self._h.ptr)
        if surface is None:
            surface = T <= 0
        if not surface:
            if T <= 0:
                raise ValueError("the scene has no stroboscopic section (section NAME period=T)")
            r = self.solve(t_span, y0, dt=T, events=[], **solve_kw)
            return r.t, r.y.T
        r = self.solve(t_span, y0, events=None, **solve_kw)
        sel = [i for i in range(len(r.t_events))
               if lib.dal_scene_event_is_section(self._h.ptr, i) == 1]
        if not sel:
            raise ValueError("the scene has no surface section (section NAME rising = g)")
        t = np.concatenate([r.t_events[i] for i in sel])
        y = np.concatenate([r.y_events[i] for i in sel])
        order = np.argsort(t, kind="stable")
        return t[order], y[order]

    def sweep(self, grid, t1=None, y0=None, threads=1, what="final", method=None, rtol=None,
              atol=None, max_step=None):
        """Runs over the grid of parameter values (a dict name -> values; the last name runs
        fastest), `threads` at a time in C. what="final": the state at t1 of each run
        (a SweepResult with y: points x 2n); what="equilibrium": the equilibrium Newton finds
        from y0's q at each point (max_step: Newton's step bound) and its stability. Scene parameters (`param` lines) rebuild
        the model per point; library parameter names (params.h: "mass:bob", "gravity:1",
        "spring:0:k") run through dal_sweep_run on one system."""
        if not isinstance(grid, dict) or not grid:
            raise TypeError("grid must be a non-empty dict {name: values}")
        if isinstance(threads, bool) or not isinstance(threads, numbers.Integral):
            raise TypeError("threads must be an int")
        if threads < 1:
            raise ValueError(f"threads must be >= 1, got {threads}")
        if what not in ("final", "equilibrium"):
            raise ValueError(f"what: unknown '{what}'; known: final, equilibrium")
        axes = []
        for name, vals in grid.items():
            if not isinstance(name, str):
                raise TypeError("grid names must be strings")
            v = np.atleast_1d(np.asarray(vals))
            if v.dtype.kind not in "iuf" or v.ndim != 1 or v.size == 0:
                raise ValueError(f"grid[{name!r}] must be a 1-D array of real numbers")
            if not np.all(np.isfinite(v)):
                raise ValueError(f"grid[{name!r}] must be finite")
            axes.append((name, v.astype(np.float64)))
        names = [a[0] for a in axes]
        mesh = np.meshgrid(*[a[1] for a in axes], indexing="ij")
        values = np.ascontiguousarray(np.stack([m.ravel() for m in mesh], axis=1))
        scene_params = self.params._values()
        lib_names = [s for s in names if ":" in s]
        if lib_names and len(lib_names) != len(names):
            raise ValueError("grid: mix of scene parameters and library parameter names")
        for s in names:
            if ":" not in s and s not in scene_params:
                raise KeyError(f"no parameter {s!r}; known: {', '.join(scene_params)}")
        n = lib.dal_system_ncoords(self._h.sys)
        y0 = self.y0 if y0 is None else _vector("y0", y0, 2 * n)
        t0 = self.run["t0"]
        t1 = self.run["t1"] if t1 is None else _real("t1", t1)
        if lib_names and what != "final":
            raise ValueError(f"what='{what}' sweeps scene parameters only, not {lib_names}")
        if lib_names:
            return self._sweep_lib(names, values, y0, t0, t1, threads, method, rtol, atol)
        if max_step is not None:
            max_step = _real("max_step", max_step, positive=True)
        return self._sweep_rebuild(names, values, y0, t0, t1, threads, what, method, rtol,
                                   atol, max_step)

    def _sweep_lib(self, names, values, y0, t0, t1, threads, method, rtol, atol):
        sys = self._h.sys
        n = lib.dal_system_ncoords(sys)
        ntraj = values.shape[0]
        o = self._opts(method, None, rtol, atol, None, None)
        res = np.full((ntraj, 2 * n), np.nan)
        status = np.zeros(ntraj, np.intc)
        msgs = ffi.new("char[]", ntraj * 256)
        err = ffi.new("char[]", _MSG)
        keep = [ffi.new("char[]", s.encode()) for s in names]
        q0, v0 = np.ascontiguousarray(y0[:n]), np.ascontiguousarray(y0[n:])
        rc = lib.pyd_sweep(sys, len(names), ffi.new("const char *[]", keep), _p(values), ntraj,
                           _p(q0), _p(v0), t0, o, t1, threads, _p(res),
                           ffi.from_buffer("int[]", status), msgs, 256, err, _MSG)
        if rc:
            raise _error(rc, _s(err))
        m = [ffi.string(msgs + 256 * i).decode() for i in range(ntraj)]
        return SweepResult(names, values, res, status, m, None)

    def _sweep_rebuild(self, names, values, y0, t0, t1, threads, what, method, rtol, atol,
                       max_step):
        ntraj = values.shape[0]
        n = lib.dal_system_ncoords(self._h.sys)
        res = np.full((ntraj, 2 * n), np.nan)
        status = np.zeros(ntraj, np.intc)
        msgs = [""] * ntraj
        verdict = [""] * ntraj
        text, name = self.text, self._h.name
        o = self._opts(method, None, rtol, atol, None, None)[0]

        failures = []

        def work(rows):
            try:
                sc = Scene(_parse(text, name))
            except Exception as e:  # handed to the caller below, never lost in a thread
                failures.append(e)
                return
            for i in rows:
                try:
                    for j, p in enumerate(names):
                        sc.params[p] = values[i, j]
                    if what == "equilibrium":
                        e = sc.equilibrium(y0[:n], t0, max_step=max_step)
                        res[i, :n], res[i, n:] = e.q, 0.0
                        verdict[i] = e.modes.verdict
                    else:
                        res[i] = sc._final(y0, t0, t1, o)
                except Error as e:
                    status[i], msgs[i] = e.status, e.message
                except Exception as e:
                    failures.append(e)
                    return
        chunks = [range(k, ntraj, threads) for k in range(threads)]
        ths = [threading.Thread(target=work, args=(c,)) for c in chunks[1:]]
        for th in ths:
            th.start()
        work(chunks[0])
        for th in ths:
            th.join()
        if failures:
            raise failures[0]
        return SweepResult(names, values, res, status, msgs,
                           verdict if what == "equilibrium" else None)

    def _final(self, y0, t0, t1, o):
        sys = self._h.sys
        n = lib.dal_system_ncoords(sys)
        st = self._state(t0, y0)
        oo = ffi.new("dal_solve_opts *", o)
        rc = lib.dal_advance(sys, st, oo, t1)
        if rc < 0:
            raise _error(rc, _s(lib.dal_state_errmsg(st)))
        return np.concatenate([_vec(lib.dal_state_q(st), n), _vec(lib.dal_state_qdot(st), n)])


class Builder:
    """A scene written by calls that mirror the scene grammar (scene.h), one line each;
    build() hands the text to the C reader, whose messages name the line:

        b = Builder(dim=2)
        b.param("l", 1).param("g", 9.81)
        b.coord("theta", q=1, v=0).particle("bob", mass=1)
        b.place("bob", "l*sin(theta)", "-l*cos(theta)").gravity(0, "-g")
        scene = b.build("pendulum")

    Values are numbers (written with repr: exact) or formulas of the parameters (strings)."""

    def __init__(self, dim=2):
        if isinstance(dim, bool) or dim not in (0, 2, 3):
            raise ValueError(f"dim must be 0, 2 or 3, got {dim!r}")
        self.lines = [f"dim {dim}"]

    @staticmethod
    def _name(what, x):
        if not isinstance(x, str) or not x.isidentifier():
            raise ValueError(f"{what} must be a name (letters, digits, _), got {x!r}")
        return x

    @staticmethod
    def _val(what, x, spaces=False):
        if isinstance(x, str):
            if not x.strip() or (not spaces and any(c.isspace() for c in x)) or \
                    any(c in x for c in "#\n;"):
                raise ValueError(f"{what}: formula {x!r} must be non-empty, on one line, "
                                 f"{'' if spaces else 'without spaces, '}without # or ;")
            return x.strip()
        return repr(_real(what, x))

    def _kv(self, what, kw):
        return "".join(f" {k}={self._val(f'{what} {k}', v)}" for k, v in kw.items()
                       if v is not None)

    def param(self, name, value):
        self.lines.append(f"param {self._name('param', name)} = {self._val(name, value)}")
        return self

    def coord(self, name, q=0.0, v=0.0):
        self.lines.append(f"coord {self._name('coord', name)}" + self._kv(name, dict(q=q, v=v)))
        return self

    def particle(self, name, mass=1.0):
        self.lines.append(f"particle {self._name('particle', name)} mass="
                          f"{self._val(name + ' mass', mass)}")
        return self

    def place(self, particle, *formulas, parent=None, primitive=None, coords=(), **params):
        """place p = f1; f2 (formulas of the coordinates, t, parameters, and with parent= the
        parent's x_<parent>, y_<parent>), or place p <primitive> <coords> name=value..."""
        head = f"place {self._name('particle', particle)}"
        if parent is not None:
            head += f" parent={self._name('parent', parent)}"
        if primitive is not None:
            if formulas:
                raise ValueError("place: formulas or a primitive, not both")
            coords = [self._name("coord", c) for c in coords]
            self.lines.append(f"{head} {self._name('primitive', primitive)} "
                              + " ".join(coords) + self._kv(particle, params))
        else:
            if not formulas or params or coords:
                raise ValueError("place: give the formulas of the position (one per axis)")
            self.lines.append(head + " = " + "; ".join(
                self._val(f"place {particle}", f, True) for f in formulas))
        return self

    def constraint(self, name, *formulas, parts=(), primitive=None, **params):
        head = f"constraint {self._name('constraint', name)}"
        if primitive is not None:
            head += f" {self._name('primitive', primitive)}"
        if parts:
            head += " parts=" + ",".join(self._name("part", p) for p in parts)
        if primitive is not None:
            self.lines.append(head + self._kv(name, params))
        else:
            if not formulas:
                raise ValueError(f"constraint {name}: give its formulas or a primitive")
            self.lines.append(head + " = " + "; ".join(
                self._val(f"constraint {name}", f, True) for f in formulas))
        return self

    def _ends(self, kind, a, b, anchor):
        s = f"{kind} {self._name('particle', a)}"
        if b is not None:
            s += f" {self._name('particle', b)}"
        if anchor is not None:
            s += " anchor=" + ",".join(self._val(f"{kind} anchor", x) for x in anchor)
        if (b is None) == (anchor is None):
            raise ValueError(f"{kind}: give a second particle or an anchor, one of them")
        return s

    def spring(self, a, b=None, *, anchor=None, k, L=0.0):
        self.lines.append(self._ends("spring", a, b, anchor) + self._kv("spring", dict(k=k, L=L)))
        return self

    def damper(self, a, b=None, *, anchor=None, c):
        self.lines.append(self._ends("damper", a, b, anchor) + self._kv("damper", dict(c=c)))
        return self

    def gravity(self, *g):
        self.lines.append("gravity " + " ".join(self._val("gravity", x) for x in g))
        return self

    def potential(self, formula):
        self.lines.append("potential = " + self._val("potential", formula, True))
        return self

    def lagrangian(self, formula):
        self.lines.append("lagrangian = " + self._val("lagrangian", formula, True))
        return self

    def event(self, name, formula, direction=0, terminal=False, section=False):
        word = {1: " rising", -1: " falling", 0: ""}.get(direction)
        if word is None or isinstance(direction, bool):
            raise ValueError(f"event {name}: direction must be -1, 0 or 1")
        kind = "section" if section else "event"
        self.lines.append(f"{kind} {self._name(kind, name)}{word}"
                          f"{' terminal' if terminal else ''} = "
                          + self._val(f"{kind} {name}", formula, True))
        return self

    def strobe(self, name, period):
        self.lines.append(f"section {self._name('section', name)} period="
                          f"{self._val('period', period)}")
        return self

    def run(self, method=None, rtol=None, atol=None, t1=None, dt=None):
        self.lines.append("run" + self._kv("run", dict(method=method, rtol=rtol, atol=atol,
                                                        t1=t1, dt=dt)))
        return self

    @property
    def text(self):
        return "\n".join(self.lines) + "\n"

    def build(self, name="<builder>"):
        return Scene.parse(self.text, name)


def _p(a):
    # a column-major (order="F") matrix is the C-contiguous buffer of its transpose
    return ffi.from_buffer("double[]", a if a.flags.c_contiguous else a.T)


def _vec(p, n):
    if p == ffi.NULL:
        return np.full(n, np.nan)
    return np.frombuffer(ffi.buffer(p, 8 * n), np.float64).copy()


# ---------------------------------------------------------------------------------------------
# results


class DenseSolution:
    """sol(t): the stored dense trajectory (dal_trajectory); y = (q, qdot) at t, shape (2n,)
    for a scalar t, (2n, len(t)) for an array."""

    def __init__(self, handle, tr, n):
        self._h, self._tr, self._n = handle, tr, n
        t0, t1 = ffi.new("double *"), ffi.new("double *")
        lib.dal_trajectory_span(tr, t0, t1)
        self.t_min, self.t_max = t0[0], t1[0]

    def __call__(self, t):
        n = self._n
        ts = np.asarray(t, dtype=np.float64)
        flat = np.atleast_1d(ts).ravel()
        out = np.empty((2 * n, flat.size))
        q, v = ffi.new("double[]", n), ffi.new("double[]", n)
        for j, tj in enumerate(flat):
            rc = lib.dal_trajectory_eval(self._tr, float(tj), q, v)
            if rc:
                raise _error(rc, _s(lib.dal_trajectory_errmsg(self._tr)))
            out[:n, j] = ffi.unpack(q, n)
            out[n:, j] = ffi.unpack(v, n)
        return out[:, 0] if ts.ndim == 0 else out


class Result:
    """What a solve computed (solve_ivp's fields and more):

    t (k), q and qdot (n x k), y = (q; qdot) (2n x k), positions (k x particles x dim),
    multipliers (m x k), energy E = T + U (k), energies (dict of arrays E, T, U, h), stats,
    status (0 reached t1, 2 a terminal event), message, success, sol (with dense_output),
    t_events and y_events (per event: times, states k x 2n), event_names, t_final, y_final
    (the state the run ended in: its last accepted step after a failure)."""

    def __init__(self, scene, st, rc, k, bufs, n, tr, evs, evnames):
        self.status = rc
        self.success = rc >= 0 and rc != lib.DAL_CANCELLED
        self.message = _s(lib.dal_state_errmsg(st)) or ("reached the end of t_span" if rc == 0
                                                         else _s(lib.dal_status_string(rc)))
        self.t = bufs["t"][:k]
        self.q = bufs["q"][:k].T
        self.qdot = bufs["qdot"][:k].T
        self.y = np.concatenate([self.q, self.qdot])
        self.positions = bufs["pos"][:k] if bufs["pos"] is not None else np.zeros((k, 0, 0))
        self.multipliers = bufs["lam"][:k].T if bufs["lam"] is not None else np.zeros((0, k))
        e = bufs["energy"][:k]
        self.energies = dict(E=e[:, 0], T=e[:, 1], U=e[:, 2], h=e[:, 3])
        self.energy = self.energies["E"]
        s = ffi.new("dal_stats *")
        lib.dal_state_stats(st, s)
        self.stats = dict(method=_s(lib.dal_method_name(s.method_used)),
                          formulation=_s(lib.dal_formulation_name(s.form_used)),
                          steps=s.steps, rejected=s.rejected, rhs_evals=s.rhs_evals,
                          jac_evals=s.jac_evals, fallbacks=s.fallbacks, rtol_used=s.rtol_used)
        self.t_final = lib.dal_state_time(st)
        self.y_final = np.concatenate([_vec(lib.dal_state_q(st), n),
                                       _vec(lib.dal_state_qdot(st), n)])
        self.sol = DenseSolution(scene._h, tr, n) if tr != ffi.NULL and \
            lib.dal_trajectory_span(tr, ffi.NULL, ffi.NULL) > 0 else None
        self.event_names = list(evnames)
        self.t_events = [np.empty(0) for _ in evnames]
        self.y_events = [np.empty((0, 2 * n)) for _ in evnames]
        if evs is not None:
            cnt = lib.dal_events_count(evs)
            ts = [[] for _ in evnames]
            ys = [[] for _ in evnames]
            rec = ffi.new("dal_event_record *")
            q, v = ffi.new("double[]", n), ffi.new("double[]", n)
            for i in range(cnt):
                lib.dal_events_get(evs, i, rec, q, v)
                ts[rec.event].append(rec.t)
                ys[rec.event].append(ffi.unpack(q, n) + ffi.unpack(v, n))
            self.t_events = [np.array(a) for a in ts]
            self.y_events = [np.array(a).reshape(-1, 2 * n) for a in ys]
        self._keep = (scene._h, tr, evs)  # the system outlives sol and the event log

    def __repr__(self):
        return (f"Result(status={self.status}, success={self.success}, {self.t.size} outputs, "
                f"stats={self.stats}, message={self.message!r})")


class Modes:
    """Normal modes: omega2 (k, ascending), shapes (k x n: row i is mode i), eigenvalues of
    df/dy (2k, complex), the verdict ("unstable", "marginal", "neutral", "asymptotic"),
    max_real and its tolerance tau."""

    def __init__(self, omega2, shapes, eigenvalues, verdict, max_real, tau):
        self.omega2, self.shapes, self.eigenvalues = omega2, shapes, eigenvalues
        self.verdict, self.max_real, self.tau = verdict, max_real, tau

    @property
    def frequencies(self):
        """sqrt(omega2) where omega2 >= 0 (rad/time), NaN where negative."""
        with np.errstate(invalid="ignore"):
            return np.where(self.omega2 >= 0, np.sqrt(np.abs(self.omega2)), np.nan)

    def __repr__(self):
        return f"Modes(verdict={self.verdict!r}, omega2={self.omega2})"


class Equilibrium:
    """An equilibrium: q, multipliers (static loads), Newton's report, modes there."""

    def __init__(self, q, multipliers, report, modes):
        self.q, self.multipliers, self.report, self.modes = q, multipliers, report, modes

    def __repr__(self):
        return f"Equilibrium(q={self.q}, verdict={self.modes.verdict!r})"


class Linearization:
    """M, C, K (k x k) of M dq'' + C dq' + K dq = B2 du; A (2k x 2k) and B (2k x inputs) of
    x' = A x + B u, x = (dq, dqdot); the input names."""

    def __init__(self, M, C, K, A, B, B2, inputs):
        self.M, self.C, self.K, self.A, self.B, self.B2 = M, C, K, A, B, B2
        self.inputs = inputs

    def __iter__(self):  # A, B = scene.linearize(...)
        return iter((self.A, self.B))


class SweepResult:
    """A sweep: names, values (points x names), y (points x 2n: the final state, or the
    equilibrium's q with zero rates), status (points; 0 ok), messages, verdict (equilibria)."""

    def __init__(self, names, values, y, status, messages, verdict):
        self.names, self.values, self.y = names, values, y
        self.status, self.messages, self.verdict = status, messages, verdict

    def __repr__(self):
        return (f"SweepResult({self.names}, {self.values.shape[0]} points, "
                f"{int(np.count_nonzero(self.status))} failed)")


def version():
    """The linked C library's version."""
    return _s(lib.dal_version())

