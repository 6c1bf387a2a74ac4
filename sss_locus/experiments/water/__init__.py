"""The water chapter: the crop to the water column, compared in pairs.
"""
