"""The reconstruction chapter: a survey over seafloor models, the estimators, their errors over
independent surveys, the closed-form error on a slope.
"""
