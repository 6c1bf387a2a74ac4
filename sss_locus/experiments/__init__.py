"""The paper's experiments, as numbers: inputs, samplers, studies and their statistics.

Imports only :mod:`sss_locus.geometry` (and :mod:`sss_locus.paths`); never plots, formats prose,
caches or knows about notebooks.

Rooms (shared rooms, then one per chapter of the book in ``_toc.yml`` order; CONTRIBUTING.md,
"Architecture"):

``stats/``
    Statistics shared by the chapters: replicate-batch intervals, row statistics, the Gaussian
    norm quantile, numbers to significant figures, and where the Monte Carlo chunks run
    (``scale``: this process or Dask). Modules: ``gaussian_norm``, ``replicates``, ``rowstats``,
    ``scale``, ``significant``.
``datamodel/``
    The data model: the TOML inputs read and validated (each value sourced or marked as an
    assumption), platforms, survey envelopes, seafloor models, the water column, a user's data
    (``--data``/``--set``), the noise model, a survey area file's table. Modules: ``datadoc``,
    ``envelopes``, ``inputs``, ``models``, ``noise_model``, ``platforms``, ``schema``,
    ``sourced``, ``terrain``, ``userdata``, ``water_column``.
``sonar_files/``
    A user's recorded sonar files and the sightings picked on them: XTF bytes read strictly,
    which end of a channel is near, layback, an XTF file's summary, sightings CSVs and XTF
    matches. Modules: ``observations``, ``observations_xtf``, ``sample_order``, ``towfish``,
    ``xtf_packets``, ``xtf_summary``.
``passes/``
    Straight passes and their views, shared by the survey-pass, three-view, noise and
    reconstruction chapters: one pass and its exact ping, passes as world-frame views,
    navigation errors shared per pass, how measurement errors spread the loci (Monte Carlo and
    first order). Modules: ``pass_noise``, ``propagation``, ``straight_pass``, ``view_sets``.
``adjustment/``
    The joint adjustment (acoustic bundle adjustment) of every feature and every pass's
    navigation, used by the reconstruction, your-pings and survey-design chapters. Modules:
    ``covariance``, ``metrics``, ``model``, ``nview``, ``residuals``, ``solver``.
``pose_space/``
    The pose-space chapter: candidate draws, the Monte Carlo, its statistics, claims and
    choices. Modules: ``choices``, ``claims``, ``draw``, ``reduce``, ``stats``, ``study``.
``survey_passes/``
    The survey-pass chapter and its second notebook, planning: two straight passes against
    crossing angle, the planning bands, verdicts, the reduction on workers. Modules:
    ``planning``, ``reduce``, ``study``, ``verdicts``.
``three_views/``
    The three-view chapter: three passes over one feature, patterns and heading sweeps. Modules:
    ``patterns``.
``noise/``
    The noise chapter: the spread of every pass pair's locus under the chapter's noise models.
    Modules: ``study``.
``water/``
    The water chapter: the crop to the water column, compared in pairs. Modules: ``study``.
``reconstruction/``
    The reconstruction chapter: a survey over seafloor models, the estimators, their errors over
    independent surveys, the closed-form error on a slope. Modules: ``estimators``, ``joint``,
    ``slope_error``, ``study``, ``surveys``, ``terrain_survey``.
``your_pings/``
    The your-pings chapter: a user's sightings and XTF files, per-feature results, the joint
    adjustment of a user's sightings, the example survey. Modules: ``example``, ``files``,
    ``joint``, ``study``, ``views``.
``survey_design/``
    The survey-design chapter: area polygons, lines and turns, routes, measured coverage,
    objectives, plans, the Pareto front and the recommended plan, plans scored over seeds.
    Modules: ``area``, ``bathymetry``, ``coverage``, ``front``, ``joint``, ``lines``,
    ``objectives``, ``plans``, ``route``, ``scoring``, ``settings``, ``turns``.
"""
