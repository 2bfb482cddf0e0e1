"""The report.html of a run that has one page of its own (bench, invariance, warps alone): a link to it, so
results/latest/report.html always opens something."""
from __future__ import annotations

from html import escape


def link_page(href: str, title: str) -> str:
    """A minimal page that links `href` under `title`."""
    return f'<!DOCTYPE html><meta charset="utf-8"><a href="{escape(href)}">{escape(title)}</a>'
