"""Scenarios with overrides, body files and the parameter table."""

from __future__ import annotations

import ast
import os
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping, Optional, Union

import pandas as pd

from . import _native

PathLike = Union[str, "os.PathLike[str]"]


def override_text(value: Any) -> str:
    """The ``--set`` text of a Python value: ``True``/``False`` → ``true``/``false``, ``None`` →
    ``None``, a number → its shortest round-trip form, a :class:`pathlib.Path` → a quoted
    absolute path, a tuple → ``(a, b, …)``, a list → ``[a, b, …]``, a mapping → a struct
    ``(name: a, …)`` (``{"linear_dyn_s_per_cm3": 0.0, "quadratic_g_per_cm3": 1.0}`` for
    ``drag``); a ``str`` is RON text as the command line takes it (``"Trefoil(Left)"``,
    ``"SparseMaximal"``, ``'"my_body.ron"'`` for a file name)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "None"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, Path):
        return '"' + str(value.resolve()) + '"'
    if isinstance(value, tuple):
        return "(" + ", ".join(override_text(v) for v in value) + ")"
    if isinstance(value, list):
        return "[" + ", ".join(override_text(v) for v in value) + "]"
    if isinstance(value, Mapping):
        return "(" + ", ".join(f"{k}: {override_text(v)}" for k, v in value.items()) + ")"
    if isinstance(value, str):
        return value
    raise TypeError(f"cannot turn {value!r} ({type(value).__name__}) into a scenario value")


def params() -> pd.DataFrame:
    """Every scenario parameter (the dotted paths overrides use): columns ``name``, ``unit``,
    ``default`` and ``meaning``, as ``hagfish params`` prints them."""
    return pd.DataFrame(_native.params(), columns=["name", "unit", "default", "meaning"])


@dataclass(frozen=True)
class Body:
    """A body file (hagfish biometrics or a uniform rod), loaded and checked.

    ``table`` has one row per rigid body: ``index``, ``s_over_L`` (its centre's arc length as
    a fraction of the body length), ``radius_cm``, ``mass_g`` and ``joint``."""

    path: Path
    name: str
    kind: str
    length_cm: float
    mass_g: float
    bodies: int
    dofs: int
    table: pd.DataFrame = field(repr=False, compare=False)

    @classmethod
    def load(cls, path: PathLike) -> "Body":
        """Loads and derives ``path``; raises :class:`hagfish.HagfishError` at file:line:column
        for a malformed or invalid file."""
        path = Path(path).resolve()
        derived = _native.body(str(path))
        return cls(
            path=path,
            name=derived["name"],
            kind=derived["kind"],
            length_cm=derived["length_cm"],
            mass_g=derived["mass_g"],
            bodies=derived["bodies"],
            dofs=derived["dofs"],
            table=pd.DataFrame(derived["rows"]),
        )

    def read_field(self, name: str) -> Any:
        """A top-level number, string or list of this body file as written:
        ``body.read_field("circumferences_cm")`` → ``[5.6, 5.5, 5.6, 4.3]``. A field the file does
        not have, or whose value is not a plain literal, raises ``KeyError``."""
        found = _field_pattern(name).search(self.path.read_text())
        try:
            return ast.literal_eval(found.group(2)) if found else _missing(self.path, name)
        except (ValueError, SyntaxError):
            raise KeyError(f"{self.path}: field `{name}` is not a plain literal") from None

    def variant(self, out: PathLike, **fields: Any) -> "Body":
        """A copy of this body file with top-level fields changed, written to ``out`` and
        loaded (checked): ``body.variant("long.ron", length_cm=50.0, mass_g=94.3)``. Values
        are as for :func:`override_text`; a field the file does not have raises
        ``KeyError``. For studies of the body: scenario overrides cannot reach a body file."""
        text = self.path.read_text()
        for name, value in fields.items():
            pattern = _field_pattern(name)
            if not pattern.search(text):
                _missing(self.path, name)
            replacement = override_text(value)
            text = pattern.sub(lambda m: m.group(1) + replacement + m.group(3), text, count=1)
        out = Path(out)
        out.write_text(text)
        return Body.load(out)


def _field_pattern(name: str) -> "re.Pattern[str]":
    """A body file's top-level line ``name: value,  // comment``: groups (prefix, value,
    the rest)."""
    return re.compile(rf"^(\s*{re.escape(name)}\s*:\s*)([^\n]*?)(,?\s*(//[^\n]*)?)$", re.M)


def _missing(path: Path, name: str) -> Any:
    raise KeyError(f"{path}: no top-level field `{name}`")


@dataclass(frozen=True)
class Scenario:
    """A scenario file with overrides, checked when made.

    ``overrides`` maps the dotted paths of :func:`params` (``time_step_s``,
    ``Thigmotaxis.parameters.tail_pull_dyn``, ``phases[2].Thigmotaxis.until.seconds``) to
    values (see :func:`override_text`); they are applied in order, exactly as ``hagfish run
    SCENARIO --set PATH=VALUE`` applies them, and ``body`` replaces the scenario's body file
    as ``--body`` does. ``resolved`` is the scenario as a run records it (``scenario.ron``)."""

    path: Path
    overrides: Mapping[str, str]
    body: Optional[Path] = None
    resolved: str = field(default="", repr=False, compare=False)

    @classmethod
    def load(
        cls,
        path: PathLike,
        overrides: Optional[Mapping[str, Any]] = None,
        *,
        body: Union[None, PathLike, Body] = None,
        **keywords: Any,
    ) -> "Scenario":
        """Loads ``path`` with ``overrides`` (a dict of dotted paths) and keyword overrides of
        top-level fields (``time_step_s=0.02``); raises :class:`hagfish.HagfishError` for a
        malformed file, a path that names nothing or a value of the wrong type."""
        merged = {**(overrides or {}), **keywords}
        texts = {str(k): override_text(v) for k, v in merged.items()}
        body_path = None
        if body is not None:
            body_path = body.path if isinstance(body, Body) else Path(body).resolve()
        path = Path(path).resolve()
        resolved = _native.resolve(str(path), _set(texts), _opt(body_path))
        return cls(path=path, overrides=texts, body=body_path, resolved=resolved)

    def with_overrides(
        self,
        overrides: Optional[Mapping[str, Any]] = None,
        *,
        body: Union[None, PathLike, Body] = None,
        **keywords: Any,
    ) -> "Scenario":
        """This scenario with more overrides (later ones win), checked."""
        merged = {**self.overrides, **(overrides or {}), **keywords}
        return Scenario.load(self.path, merged, body=body if body is not None else self.body)

    def set_arguments(self) -> list:
        """The overrides as ``PATH=VALUE`` texts, in order (``body`` last, as ``--body``)."""
        texts = _set(self.overrides)
        if self.body is not None:
            texts.append(f'body="{self.body}"')
        return texts


def _set(overrides: Mapping[str, str]) -> list:
    return [f"{k}={v}" for k, v in overrides.items()]


def _opt(path: Optional[Path]) -> Optional[str]:
    return None if path is None else str(path)
