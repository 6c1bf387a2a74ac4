"""The water chapter's figures.
"""
