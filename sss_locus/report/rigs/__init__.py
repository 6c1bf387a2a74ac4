"""The rigs chapter's figures.
"""
