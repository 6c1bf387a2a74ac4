"""The concept chapter's figures.
"""
