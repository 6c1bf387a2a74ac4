"""The three-view chapter: three passes over one feature, patterns and heading sweeps.
"""
