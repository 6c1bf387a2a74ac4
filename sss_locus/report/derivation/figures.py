"""Display helper of the derivation chapter (``notebooks/derivation.ipynb``): SymPy expressions
of :mod:`sss_locus.geometry.symbolic` shown as LaTeX.

SymPy and IPython are imported inside :func:`show` only, so importing :mod:`sss_locus.report`
does not need them.
"""

from __future__ import annotations


def show(label: str, expr, sep: str = "=") -> None:
    """Display ``label sep expr`` as LaTeX (``expr`` alone when ``label`` is empty).

    ``label`` is LaTeX; ``expr`` a SymPy expression (or anything :func:`sympy.latex` accepts);
    ``sep`` goes between them, e.g. ``""`` when the label already ends the sentence.

    Parameters
    ----------
    label : str
        LaTeX before the expression; ``""`` for none.
    expr : sympy.Expr
        The expression.
    sep : str
        LaTeX between them.
    """
    import sympy as sp
    from IPython.display import Math, display

    display(Math(rf"{label} {sep} {sp.latex(expr)}" if label else sp.latex(expr)))
