"""Markov logic networks, as ``ksmcmc mln`` handles them: query marginals and learn weights.

The rules and the evidence are the texts of ``.mln`` and ``.db`` files (the syntax of
``ksmcmc mln`` and of Alchemy/pracmln: ``Smokes(person)``, ``1.5 Smokes(x) => Cancer(x)``).

>>> from ksmcmc import mln
>>> rules = "Smokes(person)\\nCancer(person)\\n1.5 Smokes(x) => Cancer(x)\\n"
>>> p = mln.query(rules, "Smokes(Anna)\\n", ["Cancer"])   # doctest: +SKIP
>>> round(p["Cancer(Anna)"], 2)                           # doctest: +SKIP
"""

from __future__ import annotations

from typing import Dict, Optional, Sequence

from . import _ksmcmc

__all__ = ["query", "learn"]


def query(rules: str, evidence: str = "", queries: Sequence[str] = ()) -> Dict[str, float]:
    """Marginal probability of every ground atom of the ``queries`` predicates given
    ``evidence``, by the same inference as ``ksmcmc mln query`` (its default method and seed).

    Raises ``ValueError`` with the line and column of a syntax error, or what inference refused.
    """
    if isinstance(queries, str):
        queries = [queries]
    if not queries:
        raise ValueError("query needs the predicates to query, e.g. queries=['Cancer']")
    return dict(_ksmcmc.mln_query(rules, evidence, [str(q) for q in queries]))


def learn(rules: str, databases: Sequence[str], queries: Optional[Sequence[str]] = None) -> str:
    """The rules with weights learned from the training ``databases`` (complete worlds), as
    ``ksmcmc mln learn`` learns them (pseudo-log-likelihood over ``queries``, by default all
    predicates); returns the text of the learned ``.mln``.
    """
    if isinstance(databases, str):
        databases = [databases]
    if not databases:
        raise ValueError("learn needs at least one training database")
    return _ksmcmc.mln_learn(rules, list(databases), [str(q) for q in (queries or [])])
