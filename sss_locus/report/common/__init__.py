"""Shared look and words of every chapter: the seaborn theme and platform names and colours,
numbers in prose, readable tables.
"""
