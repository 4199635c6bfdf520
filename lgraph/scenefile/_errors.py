"""Problems found while reading a scene file, collected rather than raised one by one."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

Key = tuple[str | int, ...]


class _Invalid(Exception):
    """Raised during validation; turned into SceneFileError with a location.
    ``more`` holds further problems found in the same file."""

    def __init__(self, key: Key, message: str, more: list[_Invalid] | None = None) -> None:
        super().__init__(message)
        self.key = key
        self.message = message
        self.more = more or []


class _Collect:
    """Runs independent checks and keeps every problem instead of the first."""

    def __init__(self) -> None:
        self.errors: list[_Invalid] = []

    def __call__(self, func: Callable[..., Any], *args: Any, default: Any = None) -> Any:
        try:
            return func(*args)
        except _Invalid as exc:
            self.errors.extend([exc, *exc.more])
            return default

    def raise_all(self) -> None:
        if self.errors:
            first, *rest = self.errors
            raise _Invalid(first.key, first.message, rest)


def _fail(key: Key, message: str) -> None:
    raise _Invalid(key, message)
