"""The reconstruction chapter's figures.
"""
