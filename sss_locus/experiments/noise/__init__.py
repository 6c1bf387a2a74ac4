"""The noise chapter: the spread of every pass pair's locus under the chapter's noise models
(the model: :mod:`sss_locus.experiments.datamodel.noise_model`; its propagation:
:mod:`sss_locus.experiments.passes.propagation`).
"""
