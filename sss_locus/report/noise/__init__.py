"""The noise chapter's figures.
"""
