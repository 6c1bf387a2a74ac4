"""The paper's experiments, as numbers: inputs, samplers, studies and their statistics.

Imports only :mod:`sss_locus.geometry` (and :mod:`sss_locus.paths`); never plots, formats prose,
caches or knows about notebooks. Modules:

``inputs``, ``datamodel``
    Reading the TOML inputs; their schema as pydantic models (every value sourced or marked as
    an assumption, with its valid range).
``platforms``, ``envelopes``
    Sonars, vehicles and mountings (``data/platforms.toml``); survey envelopes and across-track
    offset models (``data/survey.toml``).
``straight_pass``
    One straight pass: vehicle attitude along a track and the exact ping that sees a feature.
``pose_space``, ``pose_stats``
    The pose-space Monte Carlo (the paper's Figs. 3-4) and its statistics.
``survey_passes``, ``planning``
    Two straight passes against crossing angle (Fig. 5) and the planning bands derived from it.
``view_sets``, ``noise``, ``three_view_patterns``
    Several passes as world-frame views; navigation and range noise; three-view survey patterns.
"""
