"""MkDocs hook: show Sphinx roles in docstrings as plain code.

Many docstrings use Sphinx roles (:class:`X`, :func:`~a.b.f`, :mod:`m`).
mkdocstrings' google parser leaves them as text, so the API pages would read
":class:`X`". This hook drops the role and a leading "~" (which in Sphinx
shortens the name to its last part) from the rendered page.
"""

from __future__ import annotations

import re

ROLE = re.compile(
    r":(?:attr|class|data|exc|func|meth|mod|obj):<code>(~)?([^<]*)</code>"
)


def _plain(match: re.Match[str]) -> str:
    shorten, name = match.groups()
    return f"<code>{name.rsplit('.', 1)[-1] if shorten else name}</code>"


def on_page_content(html: str, **kwargs) -> str:
    """Replace every ":role:<code>name</code>" by "<code>name</code>"."""
    return ROLE.sub(_plain, html)
