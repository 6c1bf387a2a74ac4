"""Straight passes and their views, shared by the survey-pass, three-view, noise and
reconstruction chapters: one pass and its exact ping, passes as world-frame views, navigation
errors shared per pass, how measurement errors spread the loci (Monte Carlo and first order).
"""
