"""The derivation chapter's display of the algebra.
"""
