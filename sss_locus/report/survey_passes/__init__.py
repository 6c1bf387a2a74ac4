"""The survey-pass and planning chapters' figures, findings and verdict words.
"""
