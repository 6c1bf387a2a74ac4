"""The pose-space chapter: candidate draws, the Monte Carlo, its statistics, claims and choices.
"""
