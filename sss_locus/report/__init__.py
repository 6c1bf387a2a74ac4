"""Everything a reader sees: figures (one module per chapter) and prose formatting.

The only layer that draws (matplotlib, seaborn). Plot helpers take data and ``ax=None`` and
return the axes or the figure; :mod:`~sss_locus.report.style` gives platforms their names and
colours from the data, :mod:`~sss_locus.report.text` formats numbers for glued prose.
"""
