"""Fixtures for the tf2 tests: the stock tests' private router, for the process tests."""

from __future__ import annotations

from tests.stock.conftest import router

__all__ = ["router"]
