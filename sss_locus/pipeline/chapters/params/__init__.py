"""Every chapter's parameters, declared once: one module per notebook, named after it, holding
``Params`` (a :class:`sss_locus.pipeline.run.params.NotebookParams`).

The registry finds a notebook's model here by its registry name
(:func:`sss_locus.pipeline.run.registry.params_model`); the notebook's ``parameters`` cell is
the model rendered by :func:`sss_locus.pipeline.run.paramcell.parameters_cell` (rewrite the cells
after changing a model: ``python -m sss_locus.pipeline.run.paramcell --write``). The modules import
only pydantic and the base model, so validating ``-p`` values loads no chapter. This package's
``__init__`` imports nothing.
"""
